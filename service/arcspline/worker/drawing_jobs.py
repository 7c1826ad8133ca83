"""The drawing jobs the worker processes run: a document read, joined, ordered and
approximated (``arcspline.drawings``), its outputs written and its response encoded, all in
the worker; a refusal comes back as a value (docs/drawings.md §6, §7)."""

from __future__ import annotations

from typing import Any, NamedTuple

import orjson

from arcspline.drawings import DocumentError
from arcspline.drawings.approximate import (
    DrawingOptions,
    DrawingResult,
    _drawn_by,
    _named,
    approximate_drawing,
)
from arcspline.drawings.document import DocumentSpec
from arcspline.geometry import GeometryError, Limits
from arcspline.outputs import WRITERS, Part
from arcspline.outputs.gcode import GcodeError

from .jobs import Document, Encoded, Output, finite_body, path_body, write_outputs
from .tooling import Tooled, Tooling, tool, write

DrawingFailure = GeometryError | GcodeError | DocumentError


class DrawingJob(NamedTuple):
    """One document to cut: the document, how to cut it, the outputs asked for, and the
    offset or machining that turns its toolpaths into tool-centre paths, if any."""

    document: DocumentSpec
    options: DrawingOptions
    outputs: tuple[Output, ...] = ()
    tooling: Tooling | None = None


class _Cut(NamedTuple):
    """A drawing's approximation, and its tool-centre paths when asked for."""

    result: DrawingResult
    tooled: Tooled | None

    def parts(self) -> list[Part]:
        if self.tooled is not None:
            return self.tooled.parts()
        return [(s.spline, s.curve) for s in self.result.spline.subpaths]


def _result(job: DrawingJob, limits: Limits) -> _Cut:
    """The drawing approximated, and offset or machined if asked: the core's refusals of a
    contour name ``toolpaths[i]`` and the elements it was drawn by (as the fit's)."""
    result = approximate_drawing(job.document.read(), job.options, limits)
    if job.tooling is None:
        return _Cut(result, None)
    toolpaths = result.toolpaths

    def name(i: int) -> str:
        return f"toolpaths[{i}] (drawn by {_drawn_by(toolpaths[i])})"

    try:
        return _Cut(result, tool(result.spline, job.tooling, limits, name))
    except GeometryError as error:
        raise _named(error, toolpaths) from None


def _warnings(result: DrawingResult) -> list[dict[str, Any]]:
    return [
        {"element": w.element, "reason": w.reason, "occurrences": w.occurrences}
        for w in result.warnings
    ]


def encode_drawing(
    result: DrawingResult, outputs: dict[str, str], tooled: Tooled | None = None
) -> Encoded | GeometryError:
    """The ``DrawingResponse`` body: the toolpaths in cutting order (each as a path's
    subpath, with the elements it was joined from), the statistics, what the document held
    and what was left out, how the tolerance was spent, the joining and the rapids, and the
    written ``outputs``; with ``tooled``, the toolpaths are the tool-centre paths (each with
    the sources of its contour) and the ``offset`` or ``machining`` block says how."""
    spline = result.spline if tooled is None else tooled.spline
    origin = range(len(result.toolpaths)) if tooled is None else tooled.origin
    subpaths, overall, nulls = path_body(spline)
    for sub, i in zip(subpaths, origin, strict=True):
        sub["sources"] = list(result.toolpaths[i].sources)
    overall["toolpath_count"] = overall.pop("subpath_count")
    overall["max_deviation_toolpath"] = overall.pop("max_deviation_subpath")
    budget = result.budget
    head = orjson.dumps(
        {
            "toolpaths": subpaths,
            "stats": overall,
            "units": result.units,
            "document": {
                "units": result.drawing.units,
                "elements_in": result.drawing.elements_in,
                "elements_read": result.elements_read,
                "elements_skipped": sum(w.occurrences for w in result.warnings),
                "warnings": _warnings(result),
            },
            "budget": {
                "tolerance": budget.tolerance,
                "curve_approximation": budget.curve_approximation,
                "snap_move": budget.snap_move,
                "join_gap": budget.join_gap,
                "fit": budget.fit,
            },
            "join": {"tolerance": result.join_tolerance, "joins": result.joins},
            "rapids": {"before": result.rapid_before, "after": result.rapid_after},
            **({} if tooled is None else tooled.block),
        }
    )
    s = spline.stats
    return finite_body(head, nulls, outputs, s.arc_count, s.line_count)


def approximate_drawing_one(job: DrawingJob, limits: Limits) -> Encoded | DrawingFailure:
    """One document: the encoded response, or the refusal naming the element or field."""
    try:
        cut = _result(job, limits)
    except (GeometryError, DocumentError) as error:
        return error
    outputs = write_outputs(job.outputs, cut.parts(), cut.tooled)
    if isinstance(outputs, GcodeError):
        return outputs
    return encode_drawing(cut.result, outputs, cut.tooled)


def render_drawing(job: DrawingJob, limits: Limits) -> Document | DrawingFailure:
    """The job's first output as the whole response (a program, a DXF, an SVG, a preview)."""
    try:
        cut = _result(job, limits)
        (name, options), *_ = job.outputs
        writer = WRITERS[name]
        text = write(name, options, cut.parts(), cut.tooled)
    except (GeometryError, GcodeError, DocumentError) as error:
        return error
    return Document(body=text.encode(), media_type=writer.media_type)
