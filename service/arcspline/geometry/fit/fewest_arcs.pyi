"""Type stubs of the compiled strategy kernel (see the ``.pyx`` docstring)."""

import numpy as np
import numpy.typing as npt

def fit_many(
    frames: npt.NDArray[np.float64],
    tolerances: npt.NDArray[np.float64],
    max_segments: int,
    min_relative_tolerance: float,
    /,
) -> tuple[
    list[npt.NDArray[np.float64]],
    npt.NDArray[np.int64],
    npt.NDArray[np.float64],
    npt.NDArray[np.int32],
    npt.NDArray[np.float64],
]: ...
