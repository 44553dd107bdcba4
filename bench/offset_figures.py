#!/usr/bin/env python3
"""Tool-radius offsets (side=left|right) on every target: blocks, bytes and
the largest deviation from the exact offset, as `cncc verify` measures them.

    bench/offset_figures.py CNCC

writes each case below to a scratch directory, verifies it for each target
and prints a Markdown table; then the cases that must be refused, with the
diagnostic each gets; then the same cases with the controller's cutter
radius compensation (comp=controller) on the targets that print it.
"""

import re
import subprocess
import sys
import tempfile
from pathlib import Path

POLAR = "polar(r = 18 + 4*cos(2*t)*cos(6*t), t = 0 .. 2*pi)"
S_PROFILE = (
    "nurbs(order=4, points=[(25,50), (42.8735,24.1467), (70.5832,72.3597), "
    "(86.608,165.3624), (112.4532,38.3852), (132.4671,35.1148), (175,150)], "
    "weights=[1,1,1,1,1,3,1])"
)
TARGETS = ["gcode", "jit", "sinumerik", "linuxcnc", "fanuc", "m80", "heidenhain"]
CONTROLLER_TARGETS = ["fanuc", "m80", "gcode", "linuxcnc", "sinumerik", "heidenhain"]
# (name, curve, tool diameter, side)
CASES = [
    ("polar contour outside", POLAR, 4, "right"),
    ("polar contour inside", POLAR, 4, "left"),
    ("S-profile left", S_PROFILE, 4, "left"),
    ("S-profile right", S_PROFILE, 4, "right"),
]
REFUSALS = [
    ("polar contour outside, 5 mm tool", POLAR, 5, "right"),
    ("polar contour inside, 5 mm tool", POLAR, 5, "left"),
    ("S-profile left, 10 mm tool", S_PROFILE, 10, "left"),
    ("S-profile right, 10 mm tool", S_PROFILE, 10, "right"),
]


def source(curve, diameter, side, comp="host"):
    return (
        "part p() {\n"
        f"  tool 1 diameter={diameter} feed=300\n"
        "  safe z=5\n"
        f"  curve {curve} side={side} comp={comp} tolerance=0.01\n"
        "}\n"
    )


def table(cncc, scratch, targets, comp):
    print("| case | " + " | ".join(targets) + " |")
    print("|---|" + "---|" * len(targets))
    for name, curve, diameter, side in CASES:
        path = Path(scratch) / "case.cdl"
        path.write_text(source(curve, diameter, side, comp))
        cells = []
        for target in targets:
            figures, error = verify(cncc, path, target)
            cells.append(f"{figures[0]} / {figures[1]} / {figures[2]}" if figures else error)
        print(f"| {name} | " + " | ".join(cells) + " |")


def verify(cncc, path, target):
    run = subprocess.run(
        [cncc, "verify", str(path), "-t", target], capture_output=True, text=True, check=False
    )
    text = run.stdout + run.stderr
    program = re.search(r"program: (\d+) blocks, (\d+) bytes", text)
    deviation = re.search(r"overall: max deviation ([0-9.]+) mm", text)
    if run.returncode != 0 or not program or not deviation:
        error = re.search(r"error: (.*)", text)
        return None, error.group(1) if error else text.strip()
    return (int(program.group(1)), int(program.group(2)), deviation.group(1)), None


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    cncc = sys.argv[1]
    with tempfile.TemporaryDirectory() as scratch:
        table(cncc, scratch, TARGETS, "host")
        print()
        for name, curve, diameter, side in REFUSALS:
            path = Path(scratch) / "case.cdl"
            path.write_text(source(curve, diameter, side))
            figures, error = verify(cncc, path, "gcode")
            outcome = f"cut: max deviation {figures[2]} mm" if figures else f"refused: {error}"
            print(f"- {name}: {outcome}")
        print()
        table(cncc, scratch, CONTROLLER_TARGETS, "controller")


if __name__ == "__main__":
    main()
