#!/usr/bin/env python3
"""Builds examples/family (a copy, with a copy of its machine file) twice
with CMake and Ninja and checks that cncc's depfiles make the build tool
rebuild exactly the programs a change touches:

    run_family_build.py --cncc build/tools/cncc/cncc --work DIR

- the first build makes every program, the second has nothing to do;
- touching the shop module (imported by flange.cdl) rebuilds the flange
  programs and not the plate programs;
- touching the machine file rebuilds every program.
"""

import argparse
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent
FLANGES = ["O2001", "O2002", "O2003"]
PLATES = ["O2011", "O2012"]


def build(build_dir):
    result = subprocess.run(["cmake", "--build", str(build_dir), "-j2"], capture_output=True,
                            text=True)
    if result.returncode != 0:
        sys.exit(f"the family does not build:\n{result.stdout}{result.stderr}")
    return result.stdout


def stamps(build_dir):
    return {name: (build_dir / f"{name}.nc").stat().st_mtime_ns for name in FLANGES + PLATES}


def touch(path):
    # Later than anything built so far, whatever the file system's clock
    # resolution (the inputs start in the past, see main).
    later = time.time() + 1
    os.utime(path, (later, later))


def age(folder):
    earlier = time.time() - 100
    for path in folder.rglob("*"):
        os.utime(path, (earlier, earlier))


def rebuilt(build_dir, before):
    after = stamps(build_dir)
    return sorted(name for name in after if after[name] != before[name])


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--cncc", required=True)
    parser.add_argument("--work", required=True, type=Path)
    options = parser.parse_args()
    shutil.rmtree(options.work, ignore_errors=True)
    source = options.work / "family"
    shutil.copytree(ROOT / "examples" / "family", source)
    machine = options.work / "vmc.toml"
    shutil.copy(ROOT / "examples" / "machines" / "fanuc-0i-mf-vmc.toml", machine)
    age(options.work)
    build_dir = options.work / "build"
    subprocess.run(["cmake", "-S", str(source), "-B", str(build_dir), "-G", "Ninja",
                    f"-DCNCC={Path(options.cncc).resolve()}", f"-DMACHINE={machine}"],
                   check=True, capture_output=True)
    build(build_dir)
    for name in FLANGES + PLATES:
        program = (build_dir / f"{name}.nc").read_text()
        if f"O{name[1:]}" not in program.splitlines()[1]:
            sys.exit(f"{name}.nc does not have its program number:\n{program[:200]}")
    if "no work to do" not in build(build_dir):
        sys.exit("the second build rebuilt something")
    failures = []
    before = stamps(build_dir)
    touch(source / "shop" / "slots.cdl")
    build(build_dir)
    if rebuilt(build_dir, before) != FLANGES:
        failures.append(f"touching shop/slots.cdl rebuilt {rebuilt(build_dir, before)}, "
                        f"not the flanges {FLANGES}")
    before = stamps(build_dir)
    touch(machine)
    build(build_dir)
    if rebuilt(build_dir, before) != sorted(FLANGES + PLATES):
        failures.append(f"touching the machine file rebuilt {rebuilt(build_dir, before)}, "
                        "not every program")
    for failure in failures:
        print(f"FAIL {failure}")
    if not failures:
        print(f"the family builds, then rebuilds exactly what each change touches "
              f"({len(FLANGES + PLATES)} programs)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
