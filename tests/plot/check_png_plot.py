#!/usr/bin/env python3
"""`cncc plot --format=png` draws the SVG plot as a PNG of the same size:

    check_png_plot.py --cncc build/tools/cncc/cncc --work DIR
"""

import argparse
import re
import struct
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--cncc", required=True)
    parser.add_argument("--work", required=True, type=Path)
    options = parser.parse_args()
    options.work.mkdir(parents=True, exist_ok=True)
    source = ROOT / "examples" / "s_profile.cdl"
    png = options.work / "s_profile.png"
    svg = subprocess.run([options.cncc, "plot", str(source), "-o", "-"], capture_output=True,
                         check=True).stdout.decode()
    subprocess.run([options.cncc, "plot", str(source), "--format=png", "-o", str(png)],
                   check=True)
    data = png.read_bytes()
    if data[:8] != b"\x89PNG\r\n\x1a\n" or data[12:16] != b"IHDR":
        sys.exit(f"{png} is not a PNG")
    width, height = struct.unpack(">II", data[16:24])
    match = re.search(r'<svg [^>]*width="(\d+)" height="(\d+)"', svg)
    if (width, height) != (int(match.group(1)), int(match.group(2))):
        sys.exit(f"the PNG is {width}x{height}, the SVG {match.group(1)}x{match.group(2)}")
    print(f"the plot as PNG: {width}x{height}, {len(data)} bytes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
