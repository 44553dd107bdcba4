"""The cncc under test, for the test runners (golden/, docs/): --cncc PATH,
or BUILD/tools/cncc/cncc for --build BUILD, a relative BUILD taken from the
working directory or else from the repository root."""

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def find_cncc(arguments, runner):
    if arguments.cncc:
        cncc = Path(arguments.cncc)
    else:
        build = Path(arguments.build)
        if not build.is_absolute() and not build.exists():
            build = ROOT / build
        cncc = build / "tools" / "cncc" / "cncc"
    if not cncc.is_file():
        sys.exit(f"{runner}: no cncc at '{cncc}'; build first or pass --build/--cncc")
    return cncc.resolve()
