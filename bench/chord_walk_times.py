#!/usr/bin/env python3
"""CPU time of the chord walk's slow cases: a 20-turn Archimedean spiral
r = 1 + 2t within 0.001 mm beside a 1 mm tool, as arcs, as Sinumerik
BSPLINE blocks, and `cncc verify` of the S-profile with an extreme weight.

    bench/chord_walk_times.py CNCC [--digest]

writes each case below to a scratch directory, compiles it for each of its
targets and prints a Markdown table of CPU seconds (user + system of the
cncc process, from resource.getrusage of the children), with the outcome
where it is not a plain success: "refused" (an error), "warning" (compiled
with a warning). With --digest each cell also has the first 8 hex digits of
the program's SHA-256, to check that a change keeps every program the same.
"""

import hashlib
import resource
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TARGETS = ["m80", "fanuc", "sinumerik", "gcode", "linuxcnc", "heidenhain", "jit"]
SPIRAL = "polar(r = 1 + 2*t, t = 0 .. 40*pi)"


def spiral_part(parameters, diameter, modifiers):
    return (
        f"part spiral({parameters}) {{\n"
        "  units mm\n"
        f"  tool 1 diameter={diameter} spindle=6000\n"
        "  safe z=2\n"
        "  feed 100\n"
        f"  curve {SPIRAL} tolerance=0.001 {modifiers}\n"
        "}\n"
    )


# (name, source text or example path, extra arguments, targets, subcommand)
CASES = [
    ("side=left, fixed diameter", spiral_part("", "1", "side=left"), [], TARGETS, None),
    ("side=left, diameter a parameter", spiral_part("d = 1", "d", "side=left"), [], TARGETS, None),
    ("`--arcs`", spiral_part("", "1", ""), ["--arcs"], ["m80", "fanuc", "gcode", "linuxcnc"], None),
    ("`method=bspline`", spiral_part("", "1", "method=bspline"), [], ["sinumerik"], None),
    ("verify s_profile -D w6=1e6", ROOT / "examples" / "s_profile.cdl", ["-D", "w6=1e6"], ["m80"],
     "verify"),
]


def children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run_case(cncc, path, extra, target, subcommand, scratch):
    output = Path(scratch) / "program.out"
    if output.exists():
        output.unlink()
    arguments = [cncc] + ([subcommand] if subcommand else []) + [str(path), "-t", target] + extra
    if not subcommand:
        arguments += ["-o", str(output)]
    before = children_cpu()
    run = subprocess.run(arguments, capture_output=True, text=True, check=False)
    seconds = children_cpu() - before
    if run.returncode != 0:
        outcome = "refused"
    elif "warning:" in run.stderr:
        outcome = "warning"
    else:
        outcome = ""
    text = output.read_bytes() if output.exists() else run.stdout.encode()
    return seconds, outcome, hashlib.sha256(text).hexdigest()[:8]


def main():
    arguments = [a for a in sys.argv[1:] if a != "--digest"]
    if len(arguments) != 1:
        sys.exit(__doc__)
    cncc, digest = arguments[0], "--digest" in sys.argv[1:]
    print("| case | " + " | ".join(TARGETS) + " |")
    print("|---|" + "---|" * len(TARGETS))
    with tempfile.TemporaryDirectory() as scratch:
        for name, source, extra, targets, subcommand in CASES:
            if isinstance(source, Path):
                path = source
            else:
                path = Path(scratch) / "spiral.cdl"
                path.write_text(source)
            cells = []
            for target in TARGETS:
                if target not in targets:
                    cells.append("")
                    continue
                seconds, outcome, program = run_case(cncc, path, extra, target, subcommand, scratch)
                cell = f"{seconds:.1f}" + (f" ({outcome})" if outcome else "")
                cells.append(cell + (f" {program}" if digest else ""))
            print(f"| {name} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
