"""Tests of the pure geometry core (``service.geometry``)."""
