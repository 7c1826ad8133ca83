# cython: language_level=3, boundscheck=False, wraparound=False, cdivision=True
"""Pieces measured in world coordinates, exactly: points, and the largest distance of a piece
to a line or to a circle (docs/method.md §10), for the outputs (a G-code block read back from
its rounded words, the preview) and the tests.

Each function takes the frame table of the pieces (``fit/batch.pyx``'s ``FRAME_FIELDS``) and,
per query, the row of its piece and a range of the local parameter ``u``. The line or circle
is carried into the piece's local frame (the inverse similarity), measured there by the same
root isolation as the certified deviation, and the distance scaled back.
"""

from libc.math cimport fabs, sqrt

import numpy as np

from arcspline.geometry.curves.piece cimport (
    Piece,
    point,
    relative_numerators,
    tangent_numerators,
)
from arcspline.geometry.deviation cimport line_deviation
from arcspline.geometry.maths.poly cimport MAX_COEFFS, MAX_POINTS, add_product, critical_points
from arcspline.geometry.maths.vec cimport Vec, vec

cdef enum:  # the frame fields used here (fit/batch.pyx)
    X0 = 0
    Y0 = 1
    COS_PHI = 2
    SIN_PHI = 3
    SCALE = 4
    MIRROR = 5
    PX1 = 10
    PW1 = 16
    FRAME_WIDTH = 19


cdef inline Piece piece_of(const double* f) noexcept nogil:
    cdef Piece p
    p.x[0], p.x[1], p.x[2], p.x[3] = 0.0, f[PX1], f[PX1 + 1], f[PX1 + 2]
    p.y[0], p.y[1], p.y[2], p.y[3] = 0.0, f[PX1 + 3], f[PX1 + 4], f[PX1 + 5]
    p.w[0], p.w[1], p.w[2] = 1.0, f[PW1], f[PW1 + 1]
    p.rational = p.w[1] != 0.0 or p.w[2] != 0.0
    return p


cdef inline Vec to_local(const double* f, double x, double y) noexcept nogil:
    cdef double dx = x - f[X0], dy = y - f[Y0]
    return vec((f[COS_PHI] * dx + f[SIN_PHI] * dy) / f[SCALE],
               f[MIRROR] * (f[COS_PHI] * dy - f[SIN_PHI] * dx) / f[SCALE])


cdef inline Vec to_world(const double* f, Vec p) noexcept nogil:
    cdef double y = f[MIRROR] * p.y
    return vec(f[X0] + f[SCALE] * (f[COS_PHI] * p.x - f[SIN_PHI] * y),
               f[Y0] + f[SCALE] * (f[SIN_PHI] * p.x + f[COS_PHI] * y))


cdef double circle_distance(
    const Piece* p, Vec c, double r_start, double r_end, double lo, double hi
) noexcept nogil:
    """Largest ``max(|ρ − r_start|, |ρ − r_end|)`` over ``[lo, hi]``, ``ρ = ‖Q(u) − C‖``:
    at the ends or a root of ``(Q − C)·Q'``, whose numerator is ``(X − C·W)·(X'W − XW')``."""
    cdef double px[4]
    cdef double py[4]
    cdef double dx[5]
    cdef double dy[5]
    cdef double h[MAX_COEFFS]
    cdef int i
    relative_numerators(p, c, px, py)
    tangent_numerators(p, dx, dy)
    for i in range(MAX_COEFFS):
        h[i] = 0.0
    add_product(1.0, px, 3, dx, 4, h)
    add_product(1.0, py, 3, dy, 4, h)
    cdef double points[MAX_POINTS]
    cdef int n = critical_points(h, MAX_COEFFS - 1, lo, hi, points, False, False)
    cdef double worst = 0.0, rho
    cdef Vec q
    for i in range(n):
        q = point(p, points[i])
        rho = sqrt((q.x - c.x) * (q.x - c.x) + (q.y - c.y) * (q.y - c.y))
        worst = max(worst, max(fabs(rho - r_start), fabs(rho - r_end)))
    return worst


def points(frames, pieces, u):
    """World points of the pieces ``pieces[k]`` at local ``u[k]``: shape ``(n, 2)``."""
    cdef const double[:, ::1] f = frames
    cdef const long long[::1] index = np.ascontiguousarray(pieces, dtype=np.int64)
    cdef const double[::1] at = np.ascontiguousarray(u, dtype=np.float64)
    out = np.empty((at.shape[0], 2))
    cdef double[:, ::1] o = out
    cdef Py_ssize_t k
    cdef Piece p
    cdef Vec q
    for k in range(at.shape[0]):
        p = piece_of(&f[index[k], 0])
        q = to_world(&f[index[k], 0], point(&p, at[k]))
        o[k, 0], o[k, 1] = q.x, q.y
    return out


def line_deviations(frames, pieces, lo, hi, starts, ends):
    """Largest distance of each piece range ``[lo[k], hi[k]]`` to the line through
    ``starts[k]`` and ``ends[k]`` (to the point, where they coincide)."""
    cdef const double[:, ::1] f = frames
    cdef const long long[::1] index = np.ascontiguousarray(pieces, dtype=np.int64)
    cdef const double[::1] a = np.ascontiguousarray(lo, dtype=np.float64)
    cdef const double[::1] b = np.ascontiguousarray(hi, dtype=np.float64)
    cdef const double[:, ::1] s = np.ascontiguousarray(starts, dtype=np.float64)
    cdef const double[:, ::1] e = np.ascontiguousarray(ends, dtype=np.float64)
    out = np.empty(a.shape[0])
    cdef double[::1] o = out
    cdef Py_ssize_t k
    cdef Piece p
    cdef Vec ls, le
    for k in range(a.shape[0]):
        p = piece_of(&f[index[k], 0])
        ls = to_local(&f[index[k], 0], s[k, 0], s[k, 1])
        le = to_local(&f[index[k], 0], e[k, 0], e[k, 1])
        if ls.x == le.x and ls.y == le.y:
            o[k] = f[index[k], SCALE] * circle_distance(&p, ls, 0.0, 0.0, a[k], b[k])
        else:
            o[k] = f[index[k], SCALE] * line_deviation(&p, ls, le, a[k], b[k])
    return out


def circle_deviations(frames, pieces, lo, hi, centres, r_start, r_end):
    """Largest distance of each piece range ``[lo[k], hi[k]]`` to the farther of the circles
    of radii ``r_start[k]`` and ``r_end[k]`` about ``centres[k]`` (docs/gcode.md)."""
    cdef const double[:, ::1] f = frames
    cdef const long long[::1] index = np.ascontiguousarray(pieces, dtype=np.int64)
    cdef const double[::1] a = np.ascontiguousarray(lo, dtype=np.float64)
    cdef const double[::1] b = np.ascontiguousarray(hi, dtype=np.float64)
    cdef const double[:, ::1] c = np.ascontiguousarray(centres, dtype=np.float64)
    cdef const double[::1] rs = np.ascontiguousarray(r_start, dtype=np.float64)
    cdef const double[::1] re = np.ascontiguousarray(r_end, dtype=np.float64)
    out = np.empty(a.shape[0])
    cdef double[::1] o = out
    cdef Py_ssize_t k
    cdef Piece p
    cdef double scale
    for k in range(a.shape[0]):
        p = piece_of(&f[index[k], 0])
        scale = f[index[k], SCALE]
        o[k] = scale * circle_distance(
            &p, to_local(&f[index[k], 0], c[k, 0], c[k, 1]), rs[k] / scale, re[k] / scale,
            a[k], b[k]
        )
    return out
