"""Numerical building blocks of the compiled kernels: polynomial roots (``roots.pxd``) and
Gauss–Legendre quadrature (``quadrature.pxd``). Both are header-only Cython (inline
functions cimported by the kernels), described in ``docs/method.md`` §7 "Roots".
"""
