"""Type stubs of the compiled ``piece.pyx``."""

def cubic_length(
    x1: float,
    x2: float,
    x3: float,
    y1: float,
    y2: float,
    y3: float,
    u0: float = 0.0,
    u1: float = 1.0,
) -> float: ...
