#!/usr/bin/env python3
"""Program size of parts on every controller target: motion blocks and bytes.

    bench/motion_blocks.py CNCC [CNCC_BEFORE --root-before DIR] [--examples]
    bench/motion_blocks.py CNCC --machines

compiles each case below with each cncc given (the second, when given, is
an older build to compare with, compiling the case files of its own
checkout DIR where it has them) and prints a Markdown table. A motion block
is a program line with a motion word (G0..G3 in any spelling) or an axis
word (X, Y, Z) outside comments; the bytes are the whole program's. For the
macro targets the figure counts the lines printed, not the blocks executed
(a loop is printed once). With --examples every example is a case, and
the table has the blocks (every line but `%`) beside the motion blocks.
With --machines every example is compiled for the built-in target and for
each machine file of examples/machines with that target (its sequences,
line numbers and comments), side by side.
"""

import argparse
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

CASES = [
    ("examples/helix_bore.cdl", "bore_plate_mm"),
    ("examples/bolt_circle.cdl", ""),
]
TARGETS = ["fanuc", "m80", "linuxcnc", "gcode", "sinumerik"]

COMMENT = re.compile(r"\([^)]*\)|;.*$")
MOTION = re.compile(r"(^|[\s\]N0-9])G0?[0-3](?![0-9.])|(^|\s)[XYZ][-+#\[.0-9]")


def motion_blocks(text):
    count = 0
    for line in text.splitlines():
        if MOTION.search(COMMENT.sub("", line)):
            count += 1
    return count


def blocks(text):
    return sum(1 for line in text.splitlines() if line.strip() not in ("", "%"))


def example_cases():
    cases = []
    for path in sorted((ROOT / "examples").glob("*.cdl")):
        source = str(path.relative_to(ROOT))
        cases.append((source, "bore_plate_mm" if path.stem == "helix_bore" else ""))
    return cases


def compile_case(cncc, root, source, part, target, machine=None):
    path = root / source if (root / source).exists() else ROOT / source
    arguments = [cncc, str(path)] + (["--machine", str(machine)] if machine else ["-t", target])
    if part:
        arguments += ["-p", part]
    result = subprocess.run(arguments, capture_output=True, text=True)
    if result.returncode != 0:
        return None
    return result.stdout


def figures_of(text):
    if text is None:
        return ["error"] * 3
    return [str(blocks(text)), str(motion_blocks(text)), str(len(text.encode()))]


def machine_table(cncc):
    columns = ["blocks", "motion blocks", "bytes"]
    print("| part | machine | " + " | ".join(f"built-in: {c}" for c in columns) + " | " +
          " | ".join(f"machine file: {c}" for c in columns) + " |")
    print("|" + "---|" * 8)
    for machine in sorted((ROOT / "examples" / "machines").glob("*.toml")):
        target = re.search(r'^target = "(\w+)"', machine.read_text(), re.M).group(1)
        for source, part in example_cases():
            builtin = compile_case(cncc, ROOT, source, part, target)
            shop = compile_case(cncc, ROOT, source, part, target, machine)
            name = Path(source).stem + (f" -p {part}" if part else "")
            print(f"| {name} | {machine.stem} | " + " | ".join(figures_of(builtin)) + " | " +
                  " | ".join(figures_of(shop)) + " |")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("cncc")
    parser.add_argument("before", nargs="?")
    parser.add_argument("--root-before", type=Path, default=ROOT)
    parser.add_argument("--examples", action="store_true")
    parser.add_argument("--machines", action="store_true")
    options = parser.parse_args()
    if options.machines:
        machine_table(options.cncc)
        return 0
    cases = example_cases() if options.examples else CASES
    builds = [("after", options.cncc, ROOT)]
    if options.before:
        builds.insert(0, ("before", options.before, options.root_before))
    columns = ["blocks", "motion blocks", "bytes"] if options.examples else [
        "motion blocks", "bytes"]
    header = "| part | target | " + " | ".join(
        f"{name}: {column}" for name, _, _ in builds for column in columns) + " |"
    print(header)
    print("|" + "---|" * (2 + len(columns) * len(builds)))
    for source, part in cases:
        for target in TARGETS:
            cells = []
            for _, cncc, root in builds:
                text = compile_case(cncc, root, source, part, target)
                figures = [] if text is None else [
                    str(motion_blocks(text)), str(len(text.encode()))]
                if options.examples and text is not None:
                    figures.insert(0, str(blocks(text)))
                cells += figures or ["error"] * len(columns)
            name = Path(source).stem + (f" -p {part}" if part else "")
            print(f"| {name} | {target} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
