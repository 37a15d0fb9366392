"""LinuxCNC's preview interpreter (the `gcode` module of Debian's
linuxcnc-uspace, the one AXIS draws with) as an oracle for spline
geometry: `rs274 -g` prints a spline only as `NURBS_FEED(count, ...)`,
while the preview's canon cuts it into straight feeds at points of the
curve evaluated by LinuxCNC's own `nurbs_point` (15 per control point,
uniform in the parameter; gcodemodule.cc).

Usage: /usr/bin/python3 linuxcnc_preview.py PROGRAM PARAMETER_FILE

Prints one line per straight feed, `F line x y` (the source line, the end
point in the program frame in inches, full precision), and `M line` for
every other move, so a reader can cut the feeds into runs. Used by
tests/nc_linuxcnc_oracle.rs.
"""

import sys

import gcode


class Canon:
    def __init__(self, parameter_file):
        self.parameter_file = parameter_file
        self.line = 0

    def next_line(self, code):
        self.line = code.gcodes[0]

    def straight_feed(self, x, y, *rest):
        print("F %d %r %r" % (self.line, x, y))

    def straight_traverse(self, *args):
        print("M %d" % self.line)

    def arc_feed(self, *args):
        print("M %d" % self.line)

    def rigid_tap(self, *args):
        print("M %d" % self.line)

    def get_block_delete(self):
        # on, as rs274 is run (-b) and as mtmotion's default
        return True

    def get_tool(self, pocket):
        return (pocket,) + (0.0,) * 12 + (0,)

    def get_axis_mask(self):
        return 0x1FF

    def get_external_angular_units(self):
        return 1.0

    def get_external_length_units(self):
        return 1.0

    def check_abort(self):
        return False

    def __getattr__(self, name):
        return lambda *args: None


def main():
    # G21 first: a program that states no unit is read in mm, as rs274
    # (standalone) reads it; the preview still reports inches
    result = gcode.parse(sys.argv[1], Canon(sys.argv[2]), "G21", "")
    # (error code, line): codes above 1 (INTERP_EXECUTE_FINISH) are errors
    if result[0] > 1:
        sys.stderr.write("preview stopped at line %d: code %d\n" % (result[1], result[0]))
        sys.exit(1)


main()
