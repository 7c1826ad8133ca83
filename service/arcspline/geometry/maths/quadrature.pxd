# cython: language_level=3
"""12-point Gauss–Legendre quadrature (docs/method.md §6): nodes ``±NODES[i]`` and weights
``WEIGHTS[i]`` on ``[−1, 1]`` (numpy's ``leggauss(12)``, its positive half)."""

cdef extern from *:
    """
    static const double ARCSPLINE_GL_NODES[6] = {
        0.1252334085114689, 0.3678314989981802, 0.5873179542866175,
        0.7699026741943047, 0.9041172563704748, 0.9815606342467192};
    static const double ARCSPLINE_GL_WEIGHTS[6] = {
        0.2491470458134027, 0.2334925365383546, 0.20316742672306573,
        0.16007832854334642, 0.10693932599531907, 0.04717533638651141};
    """
    const double* NODES "ARCSPLINE_GL_NODES"
    const double* WEIGHTS "ARCSPLINE_GL_WEIGHTS"

cdef enum:
    HALF_NODES = 6
