"""Test support: an independent oracle for the geometry core's guarantees."""
