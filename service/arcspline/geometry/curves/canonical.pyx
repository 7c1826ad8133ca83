# cython: language_level=3
"""Python's view of the canonical spiral's compiled arithmetic (``canonical.pxd``)."""


def length(double turn_angle_rad, double u0=0.0, double u1=1.0):
    """Arc length over ``[u0, u1]`` of the canonical spiral of turn angle θ (Gauss–Legendre
    on graded panels, docs/method.md §6); a spiral's is this times its size ``a``."""
    return arc_length(canonical(turn_angle_rad), u0, u1)
