"""Fitting strategies: how a spiral becomes arcs, each a compiled kernel behind one protocol.

A strategy is a module with a ``fit_many`` function (:class:`FitMany`) and one line in
:data:`STRATEGIES`. Every strategy shares the loop of ``batch.pyx`` (tolerance floor,
assembly in world coordinates, placement checks, statistics) and supplies only the kernel
that turns one canonical spiral into arcs (``arcs.pxd``'s ``FitFn``).
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


#: The strategies by the name a request gives.
STRATEGIES: dict[str, FitMany] = {
    "subdivide": subdivide.fit_many,
    "fewest-arcs": fewest_arcs.fit_many,
}

if TYPE_CHECKING:
    StrategyName = str
else:
    #: The strategy names as a type (for the request schema), from the registry.
    StrategyName = Literal[tuple(STRATEGIES)]

__all__ = ["STRATEGIES", "Batch", "FitMany", "StrategyName"]
