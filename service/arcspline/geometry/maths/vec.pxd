# cython: language_level=3
"""Plane vectors for the compiled kernels: a two-double struct passed by value."""

from libc.math cimport sqrt


cdef struct Vec:
    double x
    double y


cdef inline Vec vec(double x, double y) noexcept nogil:
    cdef Vec v
    v.x = x
    v.y = y
    return v


cdef inline double dot(Vec a, Vec b) noexcept nogil:
    return a.x * b.x + a.y * b.y


cdef inline double cross(Vec a, Vec b) noexcept nogil:
    """``a×b = a_x·b_y − a_y·b_x``: ``‖a‖‖b‖·sin`` of the anticlockwise angle from a to b."""
    return a.x * b.y - a.y * b.x


cdef inline double norm(Vec a) noexcept nogil:
    """``‖a‖`` as ``sqrt(x² + y²)``: the kernels' numbers stay far from squares that
    overflow or underflow (coordinates and sizes are bounded, docs/method.md §1)."""
    return sqrt(a.x * a.x + a.y * a.y)
