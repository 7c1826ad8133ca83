"""Tests of the G-code writer (``arcspline.outputs.gcode``), read back independently and by
LinuxCNC."""
