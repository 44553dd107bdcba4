#!/usr/bin/env python3
"""Runs a LinuxCNC program through LinuxCNC's interpreter as a library (the
`gcode` Python module of the Debian package linuxcnc-uspace) and prints its
canonical calls at full double precision, one a line, in the form `rs274 -g`
prints them:

    12 N..... STRAIGHT_FEED(1.2345678901234567, 2.0, -0.5, 0.0, 0.0, 0.0)

`rs274` prints four decimals; the module hands every value over as a double,
so this is the interpreter's arithmetic to the last bit (17 significant
digits).

    linuxcnc_canon_moves.py [--inches] [--maximum-calls N] PROGRAM TOOL_TABLE PARAMETERS

TOOL_TABLE is rs274's (`T5 P5 D0.25 ;`, diameters in inches); PARAMETERS is
its parameter file (work offsets). The module hands lengths over in inches
whatever the program's units; they are printed in the program's units:
millimetres, or inches with --inches. The interpreter starts in G21 with a
feed rate of 0, as rs274 does. With --maximum-calls it stops after printing N calls.

cncc embeds this script (backends/linuxcnc, runGcodeModule) and runs it with
Debian's /usr/bin/python3, for which the module is built; `cncc verify -t
linuxcnc` reads the path from it, and the tests compare the virtual
controller's LinuxCNC moves with it.

Exit status: 0 when the program ran to its end, 1 when the interpreter
stopped with an error (on standard error, with its line), 3 when the module
is not installed (cncc runs `rs274` instead), 4 when the program makes more
than the maximum number of calls.
"""

import argparse
import ctypes
import os
import sys
import tempfile

try:
    import gcode
except ImportError as error:
    print(f"{error}", file=sys.stderr)
    sys.exit(3)

MM_PER_INCH = 25.4
# A tool table entry: the tool number, nine axis offsets, the diameter, the
# front and back angles and the orientation (what get_tool returns).
EMPTY_TOOL = (-1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0)


def read_tool_table(path):
    """Pocket -> (tool, diameter in inches), from rs274's table format."""
    pockets = {}
    with open(path, encoding="ascii") as table:
        for line in table:
            words = line.split(";")[0].split()
            fields = {word[0].upper(): word[1:] for word in words if len(word) > 1}
            if "T" in fields and "P" in fields:
                pockets[int(fields["P"])] = (int(fields["T"]), float(fields.get("D", "0")))
    return pockets


def share_tool_table(path, directory):
    """LinuxCNC 2.9's interpreter finds tools in a table that the process
    running it shares in a file mapped into memory (`$HOME/.tool.mmap`,
    libtooldata); `rs274` creates and fills it, the module expects a running
    LinuxCNC to have. Created here in `directory`, a fresh one, so that no
    other run reads it. Without libtooldata (LinuxCNC before 2.9) the
    interpreter asks the canon's get_tool instead: nothing to create."""
    os.environ["HOME"] = directory
    try:
        tooldata = ctypes.CDLL("libtooldata.so.0")
    except OSError:
        return None, []
    # The C++ names of tool_mmap_creator(const EMC_TOOL_STAT*, int random),
    # tooldata_init(bool random) and tooldata_load(const char*, char* comments[]).
    if tooldata._Z17tool_mmap_creatorPK13EMC_TOOL_STATi(None, 0) != 0:
        raise RuntimeError("cannot create the tool table's shared file in " + directory)
    tooldata._Z13tooldata_initb(ctypes.c_bool(False))
    # One comment buffer for each pocket (1000 in LinuxCNC 2.9), with room.
    buffers = [ctypes.create_string_buffer(1024) for _ in range(2048)]
    comments = (ctypes.c_char_p * len(buffers))(*[ctypes.cast(b, ctypes.c_char_p) for b in buffers])
    if tooldata._Z13tooldata_loadPKcPPc(path.encode(), comments) != 0:
        raise RuntimeError("LinuxCNC does not read the tool table " + path)
    return tooldata, buffers


def number(value):
    return repr(float(value))


class Canon:
    """The calls the interpreter makes; the moves and the feed rate are
    printed, the rest answered as rs274's standalone canon answers them."""

    def __init__(self, parameter_file, pockets, scale, maximum_calls):
        self.parameter_file = parameter_file  # read by the module
        self.pockets = pockets
        self.spindle_pocket = 0
        self.scale = scale  # inches to the program's units
        self.line = 0
        self.calls = 0
        self.maximum_calls = maximum_calls

    def emit(self, name, values):
        if self.maximum_calls is not None and self.calls >= self.maximum_calls:
            sys.stdout.flush()
            print(f"more than {self.maximum_calls} canonical calls", file=sys.stderr)
            os._exit(4)  # at once: the interpreter would go on calling
        self.calls += 1
        print(f"{self.calls:5d} N..... {name}({', '.join(values)})")

    def lengths(self, values):
        return [number(value * self.scale) for value in values]

    # What the interpreter asks of the machine.
    def get_external_length_units(self):
        return 1 / MM_PER_INCH  # the machine works in inches, as rs274's does

    def get_external_angular_units(self):
        return 1.0

    def get_axis_mask(self):
        return 0x7  # X Y Z

    def get_block_delete(self):
        return False

    def check_abort(self):
        return False

    def get_tool(self, pocket):
        if pocket == 0:
            pocket = self.spindle_pocket
        if pocket not in self.pockets:
            return EMPTY_TOOL
        tool, diameter = self.pockets[pocket]
        return (tool,) + (0.0,) * 9 + (diameter, 0.0, 0.0, 0)

    def change_tool(self, pocket):
        self.spindle_pocket = pocket

    # What it commands.
    def next_line(self, state):
        self.line = state.sequence_number

    def straight_traverse(self, x, y, z, a, b, c, u, v, w):
        self.emit("STRAIGHT_TRAVERSE", self.lengths((x, y, z)) + [number(a), number(b), number(c)])

    def straight_feed(self, x, y, z, a, b, c, u, v, w):
        self.emit("STRAIGHT_FEED", self.lengths((x, y, z)) + [number(a), number(b), number(c)])

    def arc_feed(self, end1, end2, centre1, centre2, turns, end3, a, b, c, u, v, w):
        self.emit(
            "ARC_FEED",
            self.lengths((end1, end2, centre1, centre2))
            + [str(int(turns))]
            + self.lengths((end3,))
            + [number(a), number(b), number(c)],
        )

    def set_g5x_offset(self, index, x, y, z, a, b, c, u=0.0, v=0.0, w=0.0):
        # What tells the retract to the machine's Z0 (G53) from a move of the part.
        self.emit("SET_G5X_OFFSET", [str(int(index))] + self.lengths((x, y, z)))

    def set_feed_rate(self, rate):
        self.emit("SET_FEED_RATE", self.lengths((rate,)))

    # Probing and tapping are not compared (the virtual controller refuses
    # them); printed as handed over, in inches, so that they are not lost.
    def straight_probe(self, *values):
        self.emit("STRAIGHT_PROBE", [number(value) for value in values])

    def rigid_tap(self, *values):
        self.emit("RIGID_TAP", [number(value) for value in values])

    def dwell(self, seconds):
        self.emit("DWELL", [number(seconds)])

    # Calls that move nothing the comparison reads.
    def ignore(self, *values):
        pass

    set_g92_offset = set_xy_rotation = set_plane = ignore
    set_traverse_rate = tool_offset = comment = message = user_defined_function = ignore


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--inches", action="store_true", help="print lengths in inches")
    parser.add_argument("--maximum-calls", type=int, help="stop after this many calls")
    parser.add_argument("program")
    parser.add_argument("tool_table")
    parser.add_argument("parameters")
    arguments = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="cncc-gcode-") as home:
        tooldata, comments = share_tool_table(arguments.tool_table, home)
        try:
            return run(arguments)
        finally:
            if tooldata is not None:
                tooldata._Z15tool_mmap_closev()
            del comments


def run(arguments):
    canon = Canon(
        arguments.parameters,
        read_tool_table(arguments.tool_table),
        1.0 if arguments.inches else MM_PER_INCH,
        arguments.maximum_calls,
    )
    result, line = gcode.parse(arguments.program, canon, ["G21", "F0"])
    sys.stdout.flush()
    if result > gcode.MIN_ERROR:
        print(f"line {line}: {gcode.strerror(result)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
