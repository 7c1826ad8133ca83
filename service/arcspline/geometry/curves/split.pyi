"""Type stubs of the compiled ``split.pyx``."""

import numpy as np
import numpy.typing as npt

SEGMENT_FIELDS: tuple[str, ...]
SEGMENT_KINDS: dict[str, int]
PIECE_FIELDS: tuple[str, ...]

def split(
    segments: npt.NDArray[np.float64],
    max_pieces: int,
    extrema: bool = True,
    max_turn_rad: float = ...,
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]] | tuple[None, None]: ...
