# cython: language_level=3
from arcspline.geometry.curves.piece cimport Piece


cdef struct Triarc:
    # Three G1 arcs from Q(u_a) to Q(1): joints 0…3 (x, y, direction phi, split parameter s),
    # curvatures, and each arc's exact deviation and where it is reached.
    double x[4]
    double y[4]
    double phi[4]
    double s[4]
    double kappa[3]
    double dev[3]
    double u_dev[3]


cdef bint best_triarc(const Piece* s, double ua, double tolerance, Triarc* out) noexcept nogil
