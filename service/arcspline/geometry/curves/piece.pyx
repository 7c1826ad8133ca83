# cython: language_level=3
"""Python's view of a curve piece's compiled arithmetic (``piece.pxd``)."""


def cubic_length(
    double x1, double x2, double x3, double y1, double y2, double y3,
    double u0=0.0, double u1=1.0,
):
    """Arc length over ``[u0, u1]`` of the polynomial piece ``X = x1·u + x2·u² + x3·u³``,
    ``Y = y1·u + y2·u² + y3·u³`` in its local frame (adaptive Gauss–Legendre, docs/method.md
    §6); a curve's is this times its frame's scale. The coefficients are the frame's own
    (``fit.batch.FRAME_FIELDS``), so the length is that of the curve the kernels fit."""
    cdef Piece p
    p.x[0], p.x[1], p.x[2], p.x[3] = 0.0, x1, x2, x3
    p.y[0], p.y[1], p.y[2], p.y[3] = 0.0, y1, y2, y3
    p.w[0], p.w[1], p.w[2] = 1.0, 0.0, 0.0
    p.rational = False
    return arc_length(&p, u0, u1)
