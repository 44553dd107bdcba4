#!/usr/bin/env python3
"""How long cncc takes on the examples with their numbers changed as a typo would.

    bench/extreme_numbers.py CNCC [--changes N] [--seed S] [--cpu-limit SECONDS]

picks N changes (default 300) of one number literal in one example part,
each replaced by an extreme value (0, -1, 1e-9, 1e9, -5, 1e6, 0.001), and
for each change compiles the part for every controller target and, where
the compile succeeds, runs `cncc verify` for that target. It prints the
outcomes (compiled and verified, refused with an error, crashed, timed
out, verify's deviation beyond the tolerance) and the slowest runs by CPU time (user + system of the child: the
machine may be busy with other work). The goal is that every run ends,
with a program or a clear error, in under 5 s.
"""

import argparse
import os
import random
import re
import resource
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TARGETS = ["gcode", "fanuc", "m80", "linuxcnc", "sinumerik", "heidenhain"]
EXTREMES = ["0", "-1", "1e-9", "1e9", "-5", "1e6", "0.001"]
# A number literal outside comments: digits with an optional fraction and
# exponent, not part of a name (tool 1, G54.1 and such are numbers too).
NUMBER = re.compile(r"(?<![A-Za-z_0-9.])\d+(\.\d*)?([eE][-+]?\d+)?")


def number_spans(text):
    """(start, end) of each number literal outside // comments."""
    spans = []
    offset = 0
    for line in text.splitlines(keepends=True):
        code = line.split("//", 1)[0]
        for match in NUMBER.finditer(code):
            spans.append((offset + match.start(), offset + match.end()))
        offset += len(line)
    return spans


def parts_of(text):
    return re.findall(r"^part\s+([A-Za-z_][A-Za-z_0-9]*)", text, re.MULTILINE)


def run(command, cpu_limit):
    """(outcome, cpu seconds, output): outcome is the exit code, 'timeout' (past
    cpu_limit seconds of CPU: the machine may be busy, so the limit is on
    CPU, not wall time) or 'crash'; the output is standard output and error."""
    def limit_cpu():
        resource.setrlimit(resource.RLIMIT_CPU, (int(cpu_limit), int(cpu_limit) + 1))

    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    output = ""
    try:
        result = subprocess.run(command, capture_output=True, text=True, preexec_fn=limit_cpu,
                                timeout=50 * cpu_limit)
        code = result.returncode
        if code in (-signal.SIGXCPU, -signal.SIGKILL):
            outcome = "timeout"
        else:
            outcome = "crash" if code < 0 or code > 1 else code
        output = result.stdout + result.stderr
    except subprocess.TimeoutExpired:
        outcome = "timeout"
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return outcome, cpu, output


def changes(count, seed):
    generator = random.Random(seed)
    candidates = []
    for path in sorted((ROOT / "examples").glob("*.cdl")):
        text = path.read_text()
        for part in parts_of(text) or [""]:
            for span in number_spans(text):
                candidates.append((path, part, span))
    picked = []
    for _ in range(count):
        path, part, span = generator.choice(candidates)
        picked.append((path, part, span, generator.choice(EXTREMES)))
    return picked


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cncc")
    parser.add_argument("--changes", type=int, default=300)
    parser.add_argument("--seed", type=int, default=18)
    parser.add_argument("--cpu-limit", type=float, default=60,
                        help="CPU seconds a run may take before it counts as a runaway")
    arguments = parser.parse_args()

    # refused: the compile's error; verify refused: verify's own error (a
    # limit of the measurement, the controller's alarm, a limit its host
    # reference meets); verify failed: a deviation beyond the tolerance or a
    # cut not cut (a broken promise).
    outcomes = {"verified": 0, "refused": 0, "verify refused": 0, "verify failed": 0, "crash": 0,
                "timeout": 0}
    slowest = []
    with tempfile.TemporaryDirectory() as scratch:
        for number, (path, part, (start, end), value) in enumerate(
                changes(arguments.changes, arguments.seed)):
            text = path.read_text()
            changed = text[:start] + value + text[end:]
            source = Path(scratch) / path.name
            source.write_text(changed)
            line = text.count("\n", 0, start) + 1
            what = f"{path.name}:{line} {text[start:end]} -> {value}"
            select = ["-p", part] if part else []
            for target in TARGETS:
                program = Path(scratch) / f"out.{target}"
                compiled, cpu, _ = run([arguments.cncc, str(source), *select, "-t", target, "-o",
                                     str(program)], arguments.cpu_limit)
                slowest.append((cpu, "compile", target, what))
                if compiled in ("crash", "timeout"):
                    outcomes[compiled] += 1
                    print(f"{compiled}: compile -t {target} {what}", flush=True)
                    continue
                if compiled != 0:
                    outcomes["refused"] += 1
                    continue
                verified, cpu, output = run([arguments.cncc, "verify", str(source), *select, "-t", target],
                                    arguments.cpu_limit)
                slowest.append((cpu, "verify", target, what))
                if verified in ("crash", "timeout"):
                    outcomes[verified] += 1
                    print(f"{verified}: verify -t {target} {what}", flush=True)
                elif verified == 0:
                    outcomes["verified"] += 1
                elif "EXCEEDED" in output or "NOT CUT" in output:
                    outcomes["verify failed"] += 1
                    print(f"verify failed -t {target} {what}:\n{output}", flush=True)
                else:
                    outcomes["verify refused"] += 1
            if (number + 1) % 25 == 0:
                print(f"{number + 1} changes done", file=sys.stderr, flush=True)

    runs = len(slowest)
    print(f"\n{arguments.changes} changes, {runs} runs (compile and verify, "
          f"{len(TARGETS)} targets)")
    for outcome, count in outcomes.items():
        print(f"  {outcome}: {count}")
    slowest.sort(reverse=True)
    over = sum(1 for cpu, *_ in slowest if cpu >= 5)
    print(f"runs of 5 s or more of CPU: {over}")
    print("slowest runs (CPU seconds):")
    for cpu, step, target, what in slowest[:10]:
        print(f"  {cpu:6.2f}  {step} -t {target}  {what}")
    return 1 if outcomes["crash"] or outcomes["timeout"] or outcomes["verify failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
