"""Fitting strategies: how a curve piece becomes arcs, each a compiled kernel behind one
protocol.

A strategy is a module with a ``fit_many`` function (:class:`FitMany`) and a
``MONOTONE_PIECES`` flag, and one line in ``_MODULES``. Every strategy shares the loop of
``batch.pyx`` (tolerance floor, assembly in world coordinates, placement checks, statistics)
and supplies only the kernel that turns one piece in its local frame into arcs (``arcs.pxd``'s
``FitFn``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Literal, Protocol

import numpy as np
import numpy.typing as npt

from . import fewest_arcs, subdivide

FloatArray = npt.NDArray[np.float64]

#: What a strategy's ``fit_many`` answers (``batch.pyx`` documents it): the segment tables,
#: where each spiral's rows are, the statistics, a status and two numbers per spiral.
Batch = tuple[
    list[FloatArray], npt.NDArray[np.int64], FloatArray, npt.NDArray[np.int32], FloatArray
]


class FitMany(Protocol):
    def __call__(
        self,
        frames: FloatArray,
        tolerances: FloatArray,
        max_segments: int,
        min_relative_tolerance: float,
        shared: bool = False,
        /,
    ) -> Batch: ...


#: The strategy modules by the name a request gives: the one registration line each.
_MODULES = {"subdivide": subdivide, "fewest-arcs": fewest_arcs}
#: The strategies by the name a request gives.
STRATEGIES: dict[str, FitMany] = {name: m.fit_many for name, m in _MODULES.items()}
#: Whether a strategy needs pieces of monotone curvature (``curves/split.pyx``).
MONOTONE_PIECES: dict[str, bool] = {name: m.MONOTONE_PIECES for name, m in _MODULES.items()}

if TYPE_CHECKING:
    StrategyName = str
else:
    #: The strategy names as a type (for the request schema), from the registry.
    StrategyName = Literal[tuple(STRATEGIES)]

__all__ = ["MONOTONE_PIECES", "STRATEGIES", "Batch", "FitMany", "StrategyName"]
