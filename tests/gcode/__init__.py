"""Tests of the G-code writer (``service.gcode``), read back independently and by LinuxCNC."""
