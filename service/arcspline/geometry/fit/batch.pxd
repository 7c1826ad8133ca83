# cython: language_level=3
from arcspline.geometry.fit.arcs cimport FitFn


cdef object run(
    frames, tolerances, int max_segments, double min_relative_tolerance, FitFn fit,
    bint shared=*
)
