# cython: language_level=3
"""Python's view of a curve piece's compiled arithmetic (``piece.pxd``)."""


def spiral_length(double turn_angle_rad, double u0=0.0, double u1=1.0):
    """Arc length over ``[u0, u1]`` of the canonical spiral of turn angle θ (adaptive
    Gauss–Legendre, docs/method.md §6); a spiral's is this times its size ``a``."""
    cdef Piece p = spiral_piece(turn_angle_rad)
    return arc_length(&p, u0, u1)
