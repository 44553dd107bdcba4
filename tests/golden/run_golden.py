#!/usr/bin/env python3
"""File-based golden tests for the cncc driver.

Each folder under tests/golden/ is a suite; each NAME.cdl directly inside it
is a case, and so is each NAME.ir (textual IR, for `cncc opt`; `//` starts a
comment line in IR too). The first line of a case may give the arguments:

    // ARGS: %s -t gcode -p roughing
    // ARGS: opt %s --passes=fold,dce

(shell-style quoting; %s is the case's path relative to the repository root,
%d its folder, %% a percent sign). Without it the arguments are `check %s`.
cncc runs in the repository root, colour off, with a 120 s timeout.

A case whose leading comment has the line

    // SANITIZERS: skip (why)

is left out with --sanitized (the build under AddressSanitizer and
UndefinedBehaviorSanitizer, many times slower): a case that measures
hundreds of thousands of moves, whose code paths smaller cases run there.

NAME.expected holds what must happen, byte for byte:

    exit code: 1
    --- stdout ---
    ...standard output...
    --- stderr ---
    ...standard error...

An output that does not end in a line break is followed by a line
`--- (no newline at end of stdout) ---`. The repository's absolute path is
written as <root>. A hang, or an exit code of 128 or more (a crash, a
sanitizer report), fails whatever the expectations say.

    run_golden.py --build build                 run every suite
    run_golden.py --build build emit cli/x.cdl  run a suite, or one case
    run_golden.py --build build --update        rewrite the expectations
    run_golden.py --build build --coverage      check every diagnostic is tested

--coverage checks that every name printed by `cncc --list-diagnostics`
appears in brackets, `[name]`, in some tests/golden/diagnostics/*.expected.
"""

import argparse
import concurrent.futures
import difflib
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from cncc_binary import find_cncc  # noqa: E402

GOLDEN_DIR = Path(__file__).resolve().parent
ROOT = GOLDEN_DIR.parent.parent
DEFAULT_ARGUMENTS = "check %s"
# A hang still fails; generous because the sanitizer build runs cncc many
# times slower (verify and --stats execute whole programs).
TIMEOUT_SECONDS = 120
COVERAGE_SUITE = "diagnostics"
CASE_SUFFIXES = (".cdl", ".ir")


class Case:
    def __init__(self, source):
        self.source = source
        self.expected = source.with_suffix(".expected")
        self.relative = source.relative_to(ROOT).as_posix()

    def skipped_when_sanitized(self):
        with open(self.source, encoding="utf-8", errors="replace") as file:
            for line in file:
                if not line.startswith("//"):
                    return False
                if re.match(r"//\s*SANITIZERS:\s*skip\b", line):
                    return True
        return False

    def arguments(self):
        with open(self.source, encoding="utf-8", errors="replace") as file:
            first_line = file.readline().rstrip("\r\n")
        match = re.match(r"//\s*ARGS:(.*)$", first_line)
        text = match.group(1) if match else DEFAULT_ARGUMENTS
        folder = Path(self.relative).parent.as_posix()
        return [substitute(word, self.relative, folder) for word in shlex.split(text)]


def substitute(word, path, folder):
    return re.sub(r"%[sd%]", lambda m: {"%s": path, "%d": folder, "%%": "%"}[m.group(0)], word)


class Outcome:
    def __init__(self, case, text=None, problem=None):
        self.case = case
        self.text = text  # the serialised result, as NAME.expected holds it
        self.problem = problem  # why the case failed regardless of expectations


def environment():
    env = dict(os.environ)
    env.pop("CNCC_STDLIB", None)
    env["TERM"] = "dumb"
    # Make sanitizer reports abort, so they count as crashes.
    env["ASAN_OPTIONS"] = join_options(env.get("ASAN_OPTIONS"), "abort_on_error=1")
    env["UBSAN_OPTIONS"] = join_options(
        env.get("UBSAN_OPTIONS"), "halt_on_error=1:abort_on_error=1:print_stacktrace=1"
    )
    return env


def join_options(existing, extra):
    return f"{existing}:{extra}" if existing else extra


def normalise(data):
    return data.decode("utf-8", errors="backslashreplace").replace(str(ROOT), "<root>")


def section(name, text):
    result = f"--- {name} ---\n{text}"
    if text and not text.endswith("\n"):
        result += f"\n--- (no newline at end of {name}) ---\n"
    return result


def serialise(exit_code, stdout, stderr):
    return f"exit code: {exit_code}\n" + section("stdout", stdout) + section("stderr", stderr)


def run_case(cncc, case):
    try:
        command = [str(cncc)] + case.arguments()
    except ValueError as error:  # unbalanced quotes in // ARGS:
        return Outcome(case, problem=f"cannot read the ARGS line: {error}")
    try:
        result = subprocess.run(
            command, cwd=ROOT, env=environment(), capture_output=True, timeout=TIMEOUT_SECONDS
        )
    except subprocess.TimeoutExpired:
        return Outcome(case, problem=f"timed out after {TIMEOUT_SECONDS} s: {shlex.join(command)}")
    stdout, stderr = normalise(result.stdout), normalise(result.stderr)
    if result.returncode < 0 or result.returncode >= 128:
        return Outcome(
            case,
            problem=f"crashed (exit code {result.returncode}): {shlex.join(command)}\n{stderr}",
        )
    return Outcome(case, text=serialise(result.returncode, stdout, stderr))


def suite_names():
    return sorted(
        path.name
        for path in GOLDEN_DIR.iterdir()
        if path.is_dir() and not path.name.startswith((".", "_"))
    )


def cases_of(suite):
    folder = GOLDEN_DIR / suite
    if not folder.is_dir():
        return []
    return [Case(path) for path in sorted([*folder.glob("*.cdl"), *folder.glob("*.ir")])]


def select_cases(selectors):
    """Cases named by suite ("emit"), or by file ("emit/x", "tests/golden/emit/x.cdl")."""
    if not selectors:
        return [case for suite in suite_names() for case in cases_of(suite)]
    cases = []
    for selector in selectors:
        if (GOLDEN_DIR / selector).is_dir():
            cases += cases_of(selector)
            continue
        path = Path(selector)
        candidates = [path, ROOT / path, GOLDEN_DIR / path]
        found = [
            c.with_suffix(suffix)
            for c in candidates
            for suffix in CASE_SUFFIXES
            if c.with_suffix(suffix).is_file()
        ]
        if not found:
            sys.exit(f"run_golden.py: no suite or case named '{selector}'")
        cases.append(Case(found[0].resolve()))
    return cases


def orphan_expectations(cases):
    suites = {case.source.parent for case in cases}
    return sorted(
        expected
        for folder in suites
        for expected in folder.glob("*.expected")
        if not any(expected.with_suffix(suffix).is_file() for suffix in CASE_SUFFIXES)
    )


def check_outcome(outcome, update):
    """Returns a failure message, or None when the case passes."""
    case = outcome.case
    if outcome.problem:
        return outcome.problem
    # An internal error is a bug to fix, never an expectation to record.
    if "internal error" in outcome.text:
        return "cncc reported an internal error:\n" + outcome.text
    old = case.expected.read_text(encoding="utf-8") if case.expected.is_file() else None
    if update:
        if outcome.text != old:
            case.expected.write_text(outcome.text, encoding="utf-8")
            print(f"updated {case.expected.relative_to(ROOT)}")
        return None
    if old is None:
        return f"{case.expected.relative_to(ROOT)} is missing; run with --update to create it"
    if outcome.text == old:
        return None
    diff = difflib.unified_diff(
        old.splitlines(keepends=True),
        outcome.text.splitlines(keepends=True),
        fromfile=f"{case.expected.relative_to(ROOT)} (expected)",
        tofile="actual",
    )
    return f"args: {shlex.join(case.arguments())}\n" + "".join(diff)


def run_cases(cncc, cases, update):
    workers = min(32, (os.cpu_count() or 1) + 2)
    with concurrent.futures.ThreadPoolExecutor(max_workers=workers) as pool:
        outcomes = list(pool.map(lambda case: run_case(cncc, case), cases))
    failures = 0
    for outcome in outcomes:
        message = check_outcome(outcome, update)
        if message:
            failures += 1
            print(f"FAIL {outcome.case.relative}\n{message.rstrip()}\n")
    for orphan in orphan_expectations(cases):
        failures += 1
        print(f"FAIL {orphan.relative_to(ROOT)} has no .cdl or .ir beside it\n")
    print(f"{len(cases) - failures} of {len(cases)} golden cases passed")
    return 1 if failures else 0


def check_coverage(cncc):
    result = subprocess.run(
        [str(cncc), "--list-diagnostics"], cwd=ROOT, capture_output=True, text=True, check=False
    )
    if result.returncode != 0:
        print(f"FAIL cncc --list-diagnostics exited with {result.returncode}\n{result.stderr}")
        return 1
    names = result.stdout.split()
    tested = set()
    for expected in (GOLDEN_DIR / COVERAGE_SUITE).glob("*.expected"):
        tested.update(re.findall(r"\[([A-Za-z0-9_-]+)\]", expected.read_text(encoding="utf-8")))
    missing = [name for name in names if name not in tested]
    if missing:
        print(f"FAIL {len(missing)} of {len(names)} diagnostics appear in no "
              f"tests/golden/{COVERAGE_SUITE}/*.expected:")
        for name in missing:
            print(f"  {name}")
        return 1
    print(f"all {len(names)} diagnostics are covered by tests/golden/{COVERAGE_SUITE}/")
    return 0


def main():
    parser = argparse.ArgumentParser(
        description="Run the golden tests of cncc.",
        epilog="Update the expectations: python3 tests/golden/run_golden.py --build build --update",
    )
    parser.add_argument("selectors", nargs="*", help="suites or cases to run (default: all)")
    parser.add_argument("--build", default="build", help="the build directory (default: build)")
    parser.add_argument("--cncc", help="the cncc binary (overrides --build)")
    parser.add_argument("--update", action="store_true", help="rewrite the .expected files")
    parser.add_argument("--coverage", action="store_true",
                        help="check that every diagnostic appears in some expectation")
    parser.add_argument("--sanitized", action="store_true",
                        help="leave out the cases marked '// SANITIZERS: skip'")
    arguments = parser.parse_args()
    cncc = find_cncc(arguments, "run_golden.py")
    if arguments.coverage:
        return check_coverage(cncc)
    cases = select_cases(arguments.selectors)
    if arguments.sanitized:
        skipped = [case for case in cases if case.skipped_when_sanitized()]
        for case in skipped:
            print(f"skipped under the sanitizers: {case.relative}")
        cases = [case for case in cases if case not in skipped]
    return run_cases(cncc, cases, arguments.update)


if __name__ == "__main__":
    sys.exit(main())
