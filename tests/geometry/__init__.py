"""Tests of the pure geometry core (``arcspline.geometry``)."""
