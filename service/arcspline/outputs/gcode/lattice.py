"""The lattice of representable numbers: coordinates as whole counts of units in the last
place (``q = 10^-decimals``), and those counts as fixed-point text.

Formatting from an integer count is exact and can never write ``-0``, NaN or Infinity.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from .options import GcodeError

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]


def to_lattice(points: FloatArray, decimals: int) -> IntArray:
    """``points`` as whole counts of ``10^-decimals``, rounded half to even."""
    scaled = np.asarray(points, dtype=np.float64) * 10.0**decimals
    if not np.all(np.isfinite(scaled)):
        raise GcodeError("spiral", "has coordinates that are not finite numbers")
    return np.rint(scaled).astype(np.int64)


def fixed_point(units_in_last_place: int, decimals: int) -> str:
    """A lattice integer as fixed-point text: exact, never ``-0``, never NaN."""
    sign = "-" if units_in_last_place < 0 else ""
    whole, frac = divmod(abs(units_in_last_place), 10**decimals)
    return f"{sign}{whole}.{frac:0{decimals}d}"


def feed_word(value: float, decimals: int) -> str:
    """The ``F`` word of a feed rate, rounded to ``decimals``, without trailing zeros."""
    text = fixed_point(round(value * 10**decimals), decimals).rstrip("0").rstrip(".")
    return f"F{text}"
