# cython: language_level=3
from libcpp.vector cimport vector

from arcspline.geometry.curves.canonical cimport Canonical
from arcspline.geometry.fit.arcs cimport Arc, Status


cdef Status subdivide(
    Canonical spiral, double tolerance, int max_arcs, vector[Arc]* arcs
) noexcept nogil
