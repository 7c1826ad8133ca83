"""Type stubs of the compiled ``deviation.pyx``."""

def deviation_of_arc(
    k: float,
    m: float,
    jx: float,
    jy: float,
    phi_rad: float,
    kappa: float,
    ex: float,
    ey: float,
    lo: float,
    hi: float,
    tolerance: float,
) -> tuple[float, float]: ...
