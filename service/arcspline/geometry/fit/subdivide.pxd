# cython: language_level=3
from libcpp.vector cimport vector

from arcspline.geometry.curves.piece cimport Piece
from arcspline.geometry.fit.arcs cimport Arc, Status


cdef Status subdivide(
    const Piece* piece, double tolerance, int max_arcs, vector[Arc]* arcs
) noexcept nogil
