"""Type stub of the compiled strategy kernel (see the ``.pyx`` docstring)."""

from . import FitMany

fit_many: FitMany
MONOTONE_PIECES: bool
