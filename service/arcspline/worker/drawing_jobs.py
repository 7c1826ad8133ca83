"""The drawing jobs the worker processes run: a document read, joined, ordered and
approximated (``arcspline.drawings``), its outputs written and its response encoded, all in
the worker; a refusal comes back as a value (docs/drawings.md §6, §7)."""

from __future__ import annotations

from typing import Any, NamedTuple

import orjson

from arcspline.drawings import DocumentError
from arcspline.drawings.approximate import DrawingOptions, DrawingResult, approximate_drawing
from arcspline.drawings.document import DocumentSpec
from arcspline.geometry import GeometryError, Limits
from arcspline.outputs import WRITERS, Part
from arcspline.outputs.gcode import GcodeError

from .jobs import Document, Encoded, Output, finite_body, path_body, write_outputs

DrawingFailure = GeometryError | GcodeError | DocumentError


class DrawingJob(NamedTuple):
    """One document to cut: the document, how to cut it, and the outputs asked for."""

    document: DocumentSpec
    options: DrawingOptions
    outputs: tuple[Output, ...] = ()


def _result(job: DrawingJob, limits: Limits) -> DrawingResult:
    return approximate_drawing(job.document.read(), job.options, limits)


def parts_of(result: DrawingResult) -> list[Part]:
    return [(s.spline, s.curve) for s in result.spline.subpaths]


def _warnings(result: DrawingResult) -> list[dict[str, Any]]:
    return [
        {"element": w.element, "reason": w.reason, "occurrences": w.occurrences}
        for w in result.warnings
    ]


def encode_drawing(result: DrawingResult, outputs: dict[str, str]) -> Encoded | GeometryError:
    """The ``DrawingResponse`` body: the toolpaths in cutting order (each as a path's
    subpath, with the elements it was joined from), the statistics, what the document held
    and what was left out, how the tolerance was spent, the joining and the rapids, and the
    written ``outputs``."""
    subpaths, overall, nulls = path_body(result.spline)
    for sub, toolpath in zip(subpaths, result.toolpaths, strict=True):
        sub["sources"] = list(toolpath.sources)
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
        }
    )
    s = result.spline.stats
    return finite_body(head, nulls, outputs, s.arc_count, s.line_count)


def approximate_drawing_one(job: DrawingJob, limits: Limits) -> Encoded | DrawingFailure:
    """One document: the encoded response, or the refusal naming the element or field."""
    try:
        result = _result(job, limits)
    except (GeometryError, DocumentError) as error:
        return error
    outputs = write_outputs(job.outputs, parts_of(result))
    return outputs if isinstance(outputs, GcodeError) else encode_drawing(result, outputs)


def render_drawing(job: DrawingJob, limits: Limits) -> Document | DrawingFailure:
    """The job's first output as the whole response (a program, a DXF, an SVG, a preview)."""
    try:
        result = _result(job, limits)
        (name, options), *_ = job.outputs
        writer = WRITERS[name]
        text = writer.write(parts_of(result), options)
    except (GeometryError, GcodeError, DocumentError) as error:
        return error
    return Document(body=text.encode(), media_type=writer.media_type)
