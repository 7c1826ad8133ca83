"""Type stubs of the compiled ``batch.pyx`` (see its docstring)."""

import numpy as np
import numpy.typing as npt

FRAME_FIELDS: tuple[str, ...]
FIELDS: tuple[str, ...]
STATS_FIELDS: tuple[str, ...]
STATUS: dict[str, int]
PIECE_KINDS: dict[str, int]

def tolerance_floor(
    chord: float, coordinate_scale: float, min_relative_tolerance: float
) -> float: ...
def frame_table(frames: list[tuple[float, ...]]) -> npt.NDArray[np.float64]: ...
