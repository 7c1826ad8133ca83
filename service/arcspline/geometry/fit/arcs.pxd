# cython: language_level=3
"""What a fitting strategy hands to the assembly: arcs in a piece's local frame.

A strategy's kernel (:c:type:`FitFn`) turns one curve piece in its local frame
(``curves/piece.pxd``) and a local tolerance into a G1 chain of arcs, in order from ``u = 0``
to ``u = 1``; ``fit/batch.pyx`` maps the chain to world coordinates and measures it.
Strategies are registered in ``fit/__init__.py``.
"""

from libcpp.vector cimport vector

from arcspline.geometry.curves.piece cimport Piece


cdef struct Arc:
    # From (x0, y0) to (x1, y1), leaving with the unit tangent (tx, ty), radius > 0 (inf for
    # a straight piece) and the signed angle it turns through (anticlockwise positive). It
    # answers for the piece over [u0, u1], from which it deviates by at most dev (exactly
    # so, reached at u_dev).
    double x0
    double y0
    double x1
    double y1
    double tx
    double ty
    double radius
    double sweep
    double u0
    double u1
    double dev
    double u_dev


# Why a piece got no arc spline (0: it did); ``batch.STATUS`` names them for Python.
cdef enum Status:
    OK = 0
    SEGMENT_LIMIT = 1    # more segments than the limit
    STUCK = 2            # a piece too short to split in double precision
    OVERFLOW = 3         # a number of the result is not finite
    UNPLACEABLE = 4      # rounding of a centre or radius exceeds what the tolerance leaves
    TOLERANCE_FLOOR = 5  # below the smallest tolerance double precision can deliver
    BAD_TOLERANCE = 6    # not a finite number > 0


ctypedef Status (*FitFn)(
    const Piece* piece, double tolerance, int max_arcs, vector[Arc]* arcs
) noexcept nogil
