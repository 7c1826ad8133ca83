"""Type stubs of the compiled ``measure.pyx``."""

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]

def points(frames: FloatArray, pieces: npt.ArrayLike, u: npt.ArrayLike) -> FloatArray: ...
def line_deviations(
    frames: FloatArray,
    pieces: npt.ArrayLike,
    lo: npt.ArrayLike,
    hi: npt.ArrayLike,
    starts: npt.ArrayLike,
    ends: npt.ArrayLike,
) -> FloatArray: ...
def circle_deviations(
    frames: FloatArray,
    pieces: npt.ArrayLike,
    lo: npt.ArrayLike,
    hi: npt.ArrayLike,
    centres: npt.ArrayLike,
    r_start: npt.ArrayLike,
    r_end: npt.ArrayLike,
) -> FloatArray: ...
