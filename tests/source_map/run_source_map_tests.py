#!/usr/bin/env python3
"""Source maps and `cncc where`:

    run_source_map_tests.py --cncc build/tools/cncc/cncc --work DIR [--sanitized]

- every line of every example's program, on every target that prints a
  program, maps to a CDL location inside its source file, the cuts' lines
  to cut statements, and the map is the program's (its hash);
- on the macro targets a line inside a controller loop maps to the cut
  statement that made the loop, and `cncc where` says so; every parameter
  has the variable that holds it;
- on Sinumerik with --subprograms, every line of a spline's subprogram maps
  to the cut statement whose blocks call it, and --annotate names that cut
  after each subprogram's header, which stays where its file begins;
- `cncc where` refuses a line past the end, a block number the program does
  not have, a map of another program, a missing map, a malformed one and
  one whose entry is not a position in its source (exit 1, a message
  naming the problem).
"""

import argparse
import json
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent
TARGETS = ["fanuc", "m80", "linuxcnc", "gcode", "sinumerik", "heidenhain"]


def fnv1a(text):
    value = 14695981039346656037
    for byte in text:
        value ^= byte
        value = (value * 1099511628211) % (1 << 64)
    return f"{value:016x}"


# The examples whose compilation takes longest (seconds per target under the
# sanitizers, where only memory and undefined behaviour are checked): with
# --sanitized only their Sinumerik subprograms are mapped, as the sanitizer
# stage of CI leaves out their tests.
LARGEST_EXAMPLES = {"rosette_plate.cdl"}
SANITIZED = False


def example_parts(every_example=False):
    for path in sorted((ROOT / "examples").glob("*.cdl")):
        if SANITIZED and not every_example and path.name in LARGEST_EXAMPLES:
            continue
        for line in path.read_text().splitlines():
            if line.startswith("part "):
                yield path, line.split()[1].split("(")[0].rstrip("{").strip()


def block_code(text):
    """A block without its comment and block number."""
    code = text.split(";")[0].strip()
    if code.startswith("N") and code[1:].split(" ")[0].isdigit():
        code = code.split(" ", 1)[1] if " " in code else ""
    return code.strip()


def subprogram_sections(lines):
    """{name: (indexes of the main program's lines calling it, indexes of its
    own lines)} for each `%_N_NAME_SPF` section of a Sinumerik program."""
    sections = {}
    current = None
    for k, text in enumerate(lines):
        if text.startswith("%_N_"):
            current = text[4:-4] if text.endswith("_SPF") else None
            if current is not None:
                sections[current] = ([], [])
        if current is not None:
            sections[current][1].append(k)
    for k, text in enumerate(lines):
        if block_code(text) in sections and not text.startswith("%"):
            sections[block_code(text)][0].append(k)
    return sections


class Checks:
    def __init__(self, cncc, work):
        self.cncc = cncc
        self.work = work
        self.failures = []
        self.programs = 0

    def fail(self, message):
        self.failures.append(message)

    def compile(self, source, part, target, name, *extra):
        program = self.work / f"{name}.nc"
        source_map = self.work / f"{name}.nc.map.json"
        result = subprocess.run([self.cncc, str(source), "-p", part, "-t", target, "-o",
                                 str(program), "--source-map", str(source_map), *extra],
                                cwd=ROOT, capture_output=True, text=True)
        if result.returncode != 0:
            self.fail(f"{name}: does not compile: {result.stderr}")
            return None, None
        return program, json.loads(source_map.read_text())

    def check_map(self, name, program, source_map):
        text = program.read_bytes()
        lines = text.decode().splitlines()
        if source_map.get("version") != 1 or source_map.get("programHash") != fnv1a(text):
            self.fail(f"{name}: the map's version or hash is not the program's")
        if len(source_map["lines"]) != len(lines):
            self.fail(f"{name}: {len(lines)} program lines, {len(source_map['lines'])} in the map")
            return
        sources = [(ROOT / path).read_text().splitlines() for path in source_map["sources"]]
        for number, entry in enumerate(source_map["lines"], 1):
            source = sources[entry["source"]]
            if not 1 <= entry["line"] <= len(source) or entry["column"] < 1 or \
                    entry["column"] > len(source[entry["line"] - 1]) + 1:
                self.fail(f"{name}:{number}: maps to {entry}, outside its source")
                return

    def check_cuts(self, name, program, source_map, measured):
        """Each cut entry sums the blocks and bytes of the lines mapped to its
        statement; with --stats it has the deviation, within the tolerance."""
        lines = program.read_text().splitlines()
        expected = {}
        for text, entry in zip(lines, source_map["lines"]):
            if entry["statement"] == "cut":
                key = (entry["source"], entry["line"], entry["column"])
                blocks, size = expected.get(key, (0, 0))
                code = text.split("(")[0].split(";")[0].strip()
                expected[key] = (blocks + (1 if code else 0), size + len(text) + 1)
        found = {(cut["source"], cut["line"], cut["column"]): (cut["blocks"], cut["bytes"])
                 for cut in source_map["cuts"]}
        if found != expected:
            self.fail(f"{name}: the cuts say {found}, the lines {expected}")
        for cut in source_map["cuts"]:
            if measured != ("deviation" in cut):
                self.fail(f"{name}: deviation {'missing' if measured else 'unmeasured'}: {cut}")
            elif measured and cut["tolerance"] is not None and \
                    not cut["deviation"] <= cut["tolerance"]:
                self.fail(f"{name}: the cut's deviation is over its tolerance: {cut}")

    def check_controller_loops(self, name, source_map):
        inside = [entry for entry in source_map["lines"] if entry["loopDepth"] > 0]
        if inside and not any(entry["statement"] == "cut" for entry in inside):
            self.fail(f"{name}: no line inside a controller loop maps to a cut")
        # The loops the printer says hold each line are the loops its text
        # opens around it, each made by a statement of the part.
        loops = source_map.get("loops", [])
        for number, entry in enumerate(source_map["lines"], 1):
            held = entry.get("loops", [])
            if len(held) != entry["loopDepth"] or any(k >= len(loops) for k in held):
                self.fail(f"{name}:{number}: loops {held} of {len(loops)}, "
                          f"loop depth {entry['loopDepth']}")
                return
        for loop in loops:
            if loop["kind"] not in ("for", "passes", "curve") or \
                    (loop["kind"] != "for") != (loop["statement"] == "cut"):
                self.fail(f"{name}: a loop {loop}")

    def check_passes(self, name, source_map):
        """The written-out passes of each cut statement go 1 .. N in program
        order, as often as the statement runs."""
        runs = {}
        for entry in source_map["lines"]:
            pass_ = entry.get("pass")
            if pass_ is None or pass_["number"] == 0:
                continue
            key = (entry["source"], entry["line"], entry["column"])
            if entry["statement"] != "cut":
                self.fail(f"{name}: a pass on a line of a {entry['statement']} statement")
                return
            passes = runs.setdefault(key, [])
            if not passes or passes[-1] != (pass_["number"], pass_["count"]):
                passes.append((pass_["number"], pass_["count"]))
        for key, passes in runs.items():
            count = passes[0][1]
            expected = [(k % count + 1, count) for k in range(len(passes))]
            if passes != expected or len(passes) % count != 0:
                self.fail(f"{name}: the passes of the cut at {key} come as {passes}")
        return runs

    def check_variables(self, name, source_map):
        meanings = [held["meaning"] for held in source_map.get("variables", {}).values()]
        for parameter in source_map["parameters"]:
            if f"parameter {parameter}" not in meanings:
                self.fail(f"{name}: no variable holds parameter {parameter}: {meanings}")
        if source_map["parameters"] and not any(
                held["statements"] for held in source_map["variables"].values()):
            self.fail(f"{name}: no variable names the statements of its values")

    def run_examples(self):
        for source, part in example_parts():
            for target in TARGETS:
                name = f"{part}-{target}"
                program, source_map = self.compile(source, part, target, name)
                if program is None:
                    continue
                self.programs += 1
                self.check_map(name, program, source_map)
                self.check_cuts(name, program, source_map, False)
                if not any(entry["statement"] == "cut" for entry in source_map["lines"]):
                    self.fail(f"{name}: no line maps to a cut statement")
                if target in ("fanuc", "m80", "linuxcnc"):
                    self.check_controller_loops(name, source_map)
                self.check_passes(name, source_map)
                if target in ("fanuc", "m80"):
                    self.check_variables(name, source_map)

    def run_passes(self):
        """A swept cut on gcode writes passes 1, 2, 3 of each hole; on fanuc
        the same lines are the cut's pass loop, in the loop of the `for`."""
        source = ROOT / "examples/bolt_circle.cdl"
        cut = ("cut", 16, 5)
        program, source_map = self.compile(source, "bolt_circle", "gcode", "passes-gcode")
        if program is None:
            return
        runs = self.check_passes("passes-gcode", source_map) or {}
        passes = runs.get((0, 16, 5), [])
        if passes[:3] != [(1, 3), (2, 3), (3, 3)] or len(passes) != 18:
            self.fail(f"bolt_circle on gcode: the passes of its cut are {passes}")
        program, source_map = self.compile(source, "bolt_circle", "fanuc", "passes-fanuc")
        if program is None:
            return
        loops = source_map.get("loops", [])
        described = [(loop["statement"], loop["line"], loop["column"], loop["kind"])
                     for loop in loops]
        if described != [("for", 13, 3, "for"), cut + ("passes",)]:
            self.fail(f"bolt_circle on fanuc: the loops are {described}")
            return
        in_passes = [k for k, entry in enumerate(source_map["lines"], 1)
                     if entry.get("loops") == [0, 1]]
        if not in_passes or any(source_map["lines"][k - 1].get("pass", {}).get("number", 0)
                                for k in in_passes):
            self.fail(f"bolt_circle on fanuc: lines in the pass loop: {in_passes}")
            return
        result = subprocess.run([self.cncc, "where", str(program), str(in_passes[-1]),
                                 "--source-map", str(self.work / "passes-fanuc.nc.map.json")],
                                capture_output=True, text=True)
        if result.returncode != 0 or \
                "loop made by the passes of the cut at " not in result.stdout or \
                "bolt_circle.cdl:16:5" not in result.stdout or \
                "loop made by the for statement at " not in result.stdout:
            self.fail(f"where on a line of the pass loop says {result.stdout}{result.stderr}")
        gcode = self.work / "passes-gcode.nc"
        gcode_map = json.loads((self.work / "passes-gcode.nc.map.json").read_text())
        second = next((k for k, entry in enumerate(gcode_map["lines"], 1)
                       if entry.get("pass", {}).get("number") == 2), None)
        result = subprocess.run([self.cncc, "where", str(gcode), str(second),
                                 "--source-map", str(self.work / "passes-gcode.nc.map.json")],
                                capture_output=True, text=True)
        if result.returncode != 0 or "pass 2 of 3" not in result.stdout:
            self.fail(f"where on a line of pass 2 says {result.stdout}{result.stderr}")

    def run_measured(self):
        for target in ("fanuc", "gcode"):
            name = f"measured-{target}"
            program, source_map = self.compile(ROOT / "examples/s_profile.cdl", "s_profile",
                                               target, name, "--stats")
            if program is not None:
                self.check_cuts(name, program, source_map, True)

    def run_subprograms(self):
        """Sinumerik --subprograms: a subprogram's lines come from the cut
        statement that calls it (the call's own line says which)."""
        subprograms = 0
        for source, part in example_parts(every_example=True):  # one target
            name = f"{part}-sinumerik-subprograms"
            program, source_map = self.compile(source, part, "sinumerik", name, "--subprograms")
            if program is None:
                continue
            self.check_map(name, program, source_map)
            self.check_cuts(name, program, source_map, False)
            sections = subprogram_sections(program.read_text().splitlines())
            entries = source_map["lines"]
            where = lambda k: (entries[k]["source"], entries[k]["line"], entries[k]["column"],
                               entries[k]["statement"])
            for subprogram, (calls, lines) in sections.items():
                subprograms += 1
                called_from = {where(k) for k in calls}
                if len(called_from) != 1 or next(iter(called_from))[3] != "cut":
                    self.fail(f"{name}: the calls of {subprogram} map to {called_from}")
                    continue
                for k in lines:
                    if where(k) not in called_from:
                        self.fail(f"{name}:{k + 1}: in {subprogram}, maps to {where(k)}, "
                                  f"its cut is {called_from}")
                        break
            self.check_annotated_subprograms(source, part, name, sections, source_map)
        if subprograms < 2:
            self.fail(f"only {subprograms} spline subprograms in the examples")

    def check_annotated_subprograms(self, source, part, name, sections, source_map):
        """--annotate puts `; file.cdl:LINE` of the calling cut after each
        subprogram's two header lines, and nothing before a header."""
        name += "-annotated"
        program, annotated_map = self.compile(source, part, "sinumerik", name, "--subprograms",
                                              "--annotate")
        if program is None:
            return
        self.check_map(name, program, annotated_map)
        lines = program.read_text().splitlines()
        annotated = subprogram_sections(lines)
        if annotated.keys() != sections.keys():
            self.fail(f"{name}: subprograms {list(annotated)}, without --annotate {list(sections)}")
            return
        for subprogram, (calls, body) in annotated.items():
            header = body[0]
            if not sections[subprogram][0]:
                continue  # no call: reported above
            if header > 0 and block_code(lines[header - 1]) not in ("M17", "M30"):
                self.fail(f"{name}:{header + 1}: {lines[header - 1]!r} before the header")
            cut_line = source_map["lines"][sections[subprogram][0][0]]["line"]
            expected = f"; {Path(source).name}:{cut_line}"
            if lines[header + 2] != expected:
                self.fail(f"{name}:{header + 3}: {lines[header + 2]!r}, expected {expected!r}")

    def where(self, *arguments):
        return subprocess.run([self.cncc, "where", *map(str, arguments)], cwd=ROOT,
                              capture_output=True, text=True)

    def run_where(self):
        program, source_map = self.compile(ROOT / "examples" / "bolt_circle.cdl", "bolt_circle",
                                           "fanuc", "where-bolt-circle")
        if program is None:
            return
        loop_line = max(range(len(source_map["lines"])),
                        key=lambda k: source_map["lines"][k]["loopDepth"]) + 1
        result = self.where(program, loop_line)
        expected = ["bolt_circle.cdl:16:5: note: printed from this cut statement",
                    "inside 2 controller loops", "curve circle(", "holes=6, pcd=80"]
        if result.returncode != 0 or any(part not in result.stdout for part in expected):
            self.fail(f"where {program} {loop_line}:\n{result.stdout}{result.stderr}")
        lines = program.read_text().splitlines()
        self.expect_refusal("a line past the end", [program, len(lines) + 1],
                            f"has {len(lines)} lines")
        self.expect_refusal("a block number the program lacks", [program, "N77777"],
                            "has no block N77777")
        edited = self.work / "edited.nc"
        edited.write_text(program.read_text().replace("G54", "G55"))
        self.expect_refusal("a map of another program",
                            [edited, 3, "--source-map", str(program) + ".map.json"],
                            "is for another program")
        self.expect_refusal("a missing map", [edited, 3], "cannot read the source map")
        self.expect_refusal("a folder for a program", [self.work, 3], "cannot read the program")
        self.expect_refusal("a folder for a map", [program, 3, "--source-map", self.work],
                            "cannot read the source map")
        malformed = self.work / "malformed.json"
        malformed.write_text('{"version": 1, "lines": [')
        self.expect_refusal("a malformed map", [program, 3, "--source-map", malformed],
                            "is not valid JSON")
        for what, change, message in [
                ("a negative source line", {"line": -5}, "gives no valid line for line"),
                ("a source line that is not a number", {"line": 1.5e300},
                 "gives no valid line for line"),
                ("a column that is not a number", {"column": "a"}, "gives no valid column"),
                ("a source line past the source's end", {"line": 100000},
                 "bolt_circle.cdl:100000, but that file has")]:
            wrong = dict(source_map)
            wrong["lines"] = [dict(entry, **change) for entry in source_map["lines"]]
            wrong_map = self.work / "wrong-entry.json"
            wrong_map.write_text(json.dumps(wrong))
            self.expect_refusal(what, [program, loop_line, "--source-map", wrong_map], message)

    def expect_refusal(self, what, arguments, message):
        result = self.where(*arguments)
        if result.returncode != 1 or message not in result.stderr:
            self.fail(f"where with {what}: exit {result.returncode}, expected 1 and "
                      f"'{message}':\n{result.stderr}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--cncc", required=True)
    parser.add_argument("--work", required=True, type=Path)
    parser.add_argument("--sanitized", action="store_true",
                        help="leave out the largest examples (a sanitizer build)")
    options = parser.parse_args()
    global SANITIZED
    SANITIZED = options.sanitized
    shutil.rmtree(options.work, ignore_errors=True)
    options.work.mkdir(parents=True)
    checks = Checks(str(Path(options.cncc).resolve()), options.work)
    checks.run_examples()
    checks.run_where()
    checks.run_measured()
    checks.run_passes()
    checks.run_subprograms()
    for failure in checks.failures:
        print(f"FAIL {failure}")
    print(f"{checks.programs} programs mapped line by line; {len(checks.failures)} failures")
    return 1 if checks.failures else 0


if __name__ == "__main__":
    sys.exit(main())
