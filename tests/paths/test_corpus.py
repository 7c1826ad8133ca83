"""Every path of the SVG drawings in the shared corpus (real files from real tools, read in
place: ``../shared/corpus/svg``), approximated with both strategies at a thousandth of its
size: within the tolerance, or refused by a GeometryError that names where — never another
exception. Drawings as documents (transforms, units) come with the drawings issue."""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from arcspline import COLUMN, GeometryError, Limits, approximate_path, parse_path_data
from arcspline.geometry import STRATEGIES

ROOT = Path(__file__).resolve().parents[2]
CORPUS = next(
    (p for p in (ROOT.parent / "shared" / "corpus" / "svg", Path("/work/shared/corpus/svg"))
     if p.is_dir()),
    None,
)  # fmt: skip
LIMITS = Limits(max_segments=200_000)
FINITE = [
    COLUMN[name] for name in ("start_x", "start_y", "end_x", "end_y", "length", "max_deviation")
]


def _drawings() -> list[Path]:
    if CORPUS is None:
        if os.environ.get("CI") == "true":
            pytest.fail("the shared corpus (../shared/corpus/svg) is missing in CI")
        pytest.skip("the shared corpus (../shared/corpus/svg) is not beside this checkout")
    return sorted(CORPUS.glob("*.svg"))


def _path_data(drawing: Path) -> list[str]:
    root = ET.parse(drawing).getroot()  # the corpus is trusted test data
    return [e.get("d", "") for e in root.iter() if e.tag.rsplit("}", 1)[-1] == "path"]


def test_the_corpus_is_there() -> None:
    drawings = _drawings()
    assert len(drawings) >= 15
    assert sum(len(_path_data(d)) for d in drawings) >= 1000


@pytest.mark.parametrize("strategy", list(STRATEGIES))
def test_every_corpus_path_is_approximated_or_refused_by_name(strategy: str) -> None:
    done = 0
    refusals: list[tuple[str, GeometryError]] = []
    for drawing in _drawings():
        for d in _path_data(drawing):
            path = parse_path_data(d)
            if not path.subpaths:
                continue
            points = np.array(
                [p for sub in path.subpaths for s in sub.segments for p in (s.start, s.end)]
            )
            tolerance = 1e-3 * float(np.ptp(points, axis=0).max() or 1.0)
            try:
                result = approximate_path(path, tolerance, strategy, LIMITS)
            except GeometryError as error:
                refusals.append((drawing.name, error))
                continue
            done += 1
            assert result.stats.max_deviation <= tolerance, drawing.name
            for sub in result.subpaths:  # (a line's radius is inf by design)
                assert np.isfinite(sub.spline.table[:, FINITE]).all(), drawing.name
    # Near-degenerate drawing (control points 1e-5 apart: fabric.js' car) is refused by
    # name; everything else is approximated.
    for name, error in refusals:
        assert error.field.startswith("path.subpaths["), (name, str(error))
        assert error.kind in ("precision", "invalid_input"), (name, str(error))
    assert done >= 1000
    assert len(refusals) <= 0.02 * (done + len(refusals))
