"""A picture of a whole drawing's approximation, for a person to look at.

The toolpaths (parts, in cutting order) are fitted to a canvas of :data:`WIDTH_PX` ×
:data:`HEIGHT_PX` with a margin, y up, under a legend:

* axes along the left and bottom edges of the plot, ticked and labelled at round
  coordinates, and a scale bar of a round length (1, 2 or 5 × 10^k drawing units,
  ``svg.nice_number`` of a quarter of the plot's width) labelled in the drawing's units;
* each toolpath drawn with SVG arcs and lines and numbered at its start; the rapids between
  them (from ``start`` to the first, then from each one's end to the next one's start)
  dashed;
* corners, where consecutive segments of a toolpath meet with a tangent turn above
  :data:`CORNER_DEG` (and the closing joint of a closed toolpath), as small dots;
* per toolpath a deviation view, as in the preview of one curve (``svg.py``): the curve's
  deviation from each segment magnified by a round factor ``M`` chosen for that toolpath's
  own size (so that the band ``±M·tolerance`` is :data:`BAND_FRACTION` of it), inside the
  equally magnified band.

Each toolpath is one ``<g id="toolpath-k">`` with a ``<title>`` (its segments, length and
deviation, its magnification: a tooltip in browsers), and a ``<view id="view-toolpath-k">``
frames it, so ``drawing.svg#view-toolpath-k`` opens zoomed to it. Samples of the deviation
curves are shared out of a total budget (:data:`DEVIATION_SAMPLES`), so the picture's size
grows with the segment count only, never with the samples.

When the toolpaths are tool-centre paths (an offset or a machining plan, docs/http-api.md,
"Offsets and machining"), a :class:`ToolView` adds the part's contours (thin, grey) and the
width the tool sweeps: a translucent band along each tool path, the path stroked with the
tool's diameter in drawing units with round caps and joins — exactly the union of the tool's
discs along the path (a Minkowski sum with a disc).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from arcspline.geometry import Curve, GeometryError
from arcspline.geometry.spline import ArcSpline, FloatArray, Point

from .extents import extents
from .part import Part
from .svg import MEDIA_TYPE, deviation_curves, legend_lines, nice_number

WIDTH_PX = 900.0
HEIGHT_PX = 700.0
HEADER_PX = 50.0
#: Plot margins: left (room for the y labels), right, top, bottom (x labels, scale bar).
MARGIN_PX = (70.0, 20.0, 15.0, 70.0)
#: A joint whose tangent turns by more than this is a corner.
CORNER_DEG = 1.0
#: The magnified tolerance band takes about this fraction of its toolpath's size.
BAND_FRACTION = 0.04
#: Samples of the deviation curves over all toolpaths; each segment gets between
#: :data:`MIN_SAMPLES` and :data:`MAX_SAMPLES`.
DEVIATION_SAMPLES = 20000
MIN_SAMPLES, MAX_SAMPLES = 3, 16
TOOLPATH_COLOURS = ("#1f77b4", "#d62728", "#9467bd", "#8c564b")
CONTOUR_COLOUR = "#999999"
SWEPT_COLOUR, SWEPT_OPACITY = "#1f77b4", 0.18


class ToolView(NamedTuple):
    """What a preview of tool-centre paths adds: the part's ``contours`` (the paths the tool
    was offset from), the ``width`` it sweeps (its diameter, drawing units), and a ``label``
    saying the offset or the tool (``offset 3 outside``)."""

    contours: tuple[ArcSpline, ...]
    width: float
    label: str


class PreviewOptions(NamedTuple):
    """The writer's options: the drawing's unit and, for tool-centre paths, the tool's view."""

    units: str = "mm"
    tool: ToolView | None = None


class Frame(NamedTuple):
    """World (drawing units, y up) to picture (pixels, y down): ``x_px = (x − x0)·scale +
    left``, ``y_px = (y1 − y)·scale + top``."""

    x0: float
    y1: float
    scale: float
    left: float
    top: float

    def xy(self, points: FloatArray) -> FloatArray:
        x = (points[..., 0] - self.x0) * self.scale + self.left
        y = (self.y1 - points[..., 1]) * self.scale + self.top
        return np.stack([x, y], axis=-1)

    def world_x(self, x_px: float) -> float:
        return (x_px - self.left) / self.scale + self.x0

    def world_y(self, y_px: float) -> float:
        return self.y1 - (y_px - self.top) / self.scale


def _frame(splines: Sequence[ArcSpline], start: Point) -> Frame:
    """Fit the toolpaths and the start point into the plot, keeping the aspect ratio."""
    low, high = extents(splines)
    low, high = np.minimum(low, start), np.maximum(high, start)
    size = float(max(high[0] - low[0], high[1] - low[1]))
    pad = 0.08 * size if size > 0.0 else 1.0
    low, high = low - pad, high + pad
    left, right, top, bottom = MARGIN_PX
    plot_w, plot_h = WIDTH_PX - left - right, HEIGHT_PX - HEADER_PX - top - bottom
    with np.errstate(all="ignore"):
        scale = min(plot_w / (high[0] - low[0]), plot_h / (high[1] - low[1]))
    # Centre the drawing in the plot.
    x0 = float(low[0]) - (plot_w / scale - float(high[0] - low[0])) / 2
    y1 = float(high[1]) + (plot_h / scale - float(high[1] - low[1])) / 2
    frame = Frame(x0, y1, float(scale), left, HEADER_PX + top)
    if not all(map(math.isfinite, frame)) or frame.scale <= 0.0:
        raise GeometryError(
            "parts",
            "the drawing's coordinates are too large to draw (they overflow)",
            kind="precision",
        )
    return frame


def _f(value: float) -> str:
    return f"{value:.3f}"


def _points(points: FloatArray) -> str:
    return " ".join(f"{x:.3f},{y:.3f}" for x, y in points.tolist())


def _path_data(spline: ArcSpline, frame: Frame) -> str:
    """The toolpath in picture coordinates (SVG arcs for arcs; y flipped, so an
    anticlockwise arc has sweep-flag 0)."""
    c = spline.columns
    start, end = frame.xy(c.start).tolist(), frame.xy(c.end).tolist()
    radii = (np.where(c.is_arc, c.radius, 0.0) * frame.scale).tolist()
    sweeps, is_arc = c.sweep_rad.tolist(), c.is_arc.tolist()
    out = [f"M{_f(start[0][0])},{_f(start[0][1])}"]
    for i, (x, y) in enumerate(end):
        if is_arc[i]:
            large, flag = int(abs(sweeps[i]) > math.pi), int(sweeps[i] < 0.0)
            r = f"{radii[i]:.6g}"
            out.append(f"A{r},{r} 0 {large} {flag} {_f(x)},{_f(y)}")
        else:
            out.append(f"L{_f(x)},{_f(y)}")
    return " ".join(out)


def _tangents(spline: ArcSpline, at: str) -> FloatArray:
    """Unit direction of travel of every segment at its ``"start"`` or ``"end"``."""
    c = spline.columns
    point = c.start if at == "start" else c.end
    chord = c.end - c.start
    radial = point - c.center
    # An arc's tangent is its radius turned a quarter in the direction of travel.
    turn = np.sign(c.sweep_rad)[:, None]
    arc = turn * np.stack([-radial[:, 1], radial[:, 0]], axis=-1)
    direction = np.where(c.is_arc[:, None], arc, chord)
    norm = np.hypot(direction[:, 0], direction[:, 1])
    return direction / np.maximum(norm, 1e-300)[:, None]


def corners(spline: ArcSpline, min_turn_deg: float = CORNER_DEG) -> FloatArray:
    """The joints of ``spline`` where the direction of travel turns by more than
    ``min_turn_deg`` (the angle between one segment's end tangent and the next one's start
    tangent), ``(k, 2)``; a closed spline's closing joint counts, at its start point."""
    c = spline.columns
    if len(c) == 0:
        return np.zeros((0, 2))
    t_end, t_start = _tangents(spline, "end"), _tangents(spline, "start")
    closed = len(c) > 1 and bool((c.end[-1] == c.start[0]).all())
    nxt = np.roll(t_start, -1, axis=0) if closed else t_start[1:]
    ends = t_end if closed else t_end[:-1]
    cross = ends[:, 0] * nxt[:, 1] - ends[:, 1] * nxt[:, 0]
    dot = np.einsum("ij,ij->i", ends, nxt)
    turn_deg = np.degrees(np.abs(np.arctan2(cross, dot)))
    joints = c.end if closed else c.end[:-1]
    found: FloatArray = joints[turn_deg > min_turn_deg]
    return found


def _axes(frame: Frame, units: str) -> list[str]:
    """Axes along the plot's left and bottom edges, ticked at round coordinates, and the
    scale bar."""
    left, right, top, bottom = MARGIN_PX
    x_lo, x_hi = left, WIDTH_PX - right
    y_lo, y_hi = HEADER_PX + top, HEIGHT_PX - bottom
    out = [
        '<g class="axes" stroke="#444444" stroke-width="1" font-size="11" fill="#444444">',
        f'<path d="M{_f(x_lo)},{_f(y_lo)} V{_f(y_hi)} H{_f(x_hi)}" fill="none"/>',
    ]
    w0, w1 = frame.world_x(x_lo), frame.world_x(x_hi)
    step = nice_number((w1 - w0) / 5)
    for k in range(math.ceil(w0 / step), math.floor(w1 / step) + 1):
        x = (k * step - frame.x0) * frame.scale + frame.left
        out.append(f'<line x1="{_f(x)}" y1="{_f(y_hi)}" x2="{_f(x)}" y2="{_f(y_hi + 5)}"/>')
        out.append(
            f'<text x="{_f(x)}" y="{_f(y_hi + 18)}" text-anchor="middle" stroke="none">'
            f"{k * step:g}</text>"
        )
    v0, v1 = frame.world_y(y_hi), frame.world_y(y_lo)
    for k in range(math.ceil(v0 / step), math.floor(v1 / step) + 1):
        y = (frame.y1 - k * step) * frame.scale + frame.top
        out.append(f'<line x1="{_f(x_lo - 5)}" y1="{_f(y)}" x2="{_f(x_lo)}" y2="{_f(y)}"/>')
        out.append(
            f'<text x="{_f(x_lo - 8)}" y="{_f(y + 4)}" text-anchor="end" stroke="none">'
            f"{k * step:g}</text>"
        )
    out.append("</g>")
    bar = nice_number((w1 - w0) / 4)
    bar_px = bar * frame.scale
    bx, by = x_hi - bar_px, HEIGHT_PX - 22
    out.extend(
        [
            '<g class="scale-bar" stroke="black" stroke-width="2">',
            f'<path d="M{_f(bx)},{_f(by - 5)} V{_f(by)} H{_f(x_hi)} V{_f(by - 5)}" fill="none"/>',
            f'<text x="{_f(bx + bar_px / 2)}" y="{_f(by - 8)}" text-anchor="middle" '
            f'stroke="none" font-size="12">{bar:g} {units}</text>',
            "</g>",
        ]
    )
    return out


def _toolpath(
    k: int, spline: ArcSpline, curve: Curve, frame: Frame, per: int
) -> tuple[list[str], str]:
    """Toolpath ``k``'s group, and its ``<view>`` (its frame in the picture)."""
    c = spline.columns
    low, high = extents([spline])
    size = float(max(high[0] - low[0], high[1] - low[1], 1e-300))
    magnify = nice_number(BAND_FRACTION * size / spline.tolerance)
    colour = TOOLPATH_COLOURS[(k - 1) % len(TOOLPATH_COLOURS)]
    s = spline.stats
    title = (
        f"toolpath {k}: {s.arc_count} arcs, {s.line_count} lines, length "
        f"{s.spline_length:.6g}; max deviation {s.max_deviation:.3g} (tolerance "
        f"{spline.tolerance:.3g}); deviation ×{magnify:g}"
    )
    out = [f'<g id="toolpath-{k}" class="toolpath">', f"<title>{title}</title>"]
    with np.errstate(all="ignore"):
        deviation, band_out, band_in = (
            frame.xy(a) for a in deviation_curves(curve, spline, magnify, per)
        )
    if np.isfinite(deviation).all() and np.isfinite(band_out).all() and np.isfinite(band_in).all():
        out.append('<g class="band" fill="#eeeeee" stroke="none">')
        out.extend(
            f'<polygon points="{_points(np.concatenate([o, i[::-1]]))}"/>'
            for o, i in zip(band_out, band_in, strict=True)
        )
        out.append('</g><g class="deviation" fill="none" stroke="#2ca02c" stroke-width="0.8">')
        out.extend(f'<polyline points="{_points(d)}"/>' for d in deviation)
        out.append("</g>")
    out.append(
        f'<path class="cut" d="{_path_data(spline, frame)}" fill="none" stroke="{colour}" '
        'stroke-width="1.5"/>'
    )
    out.append('<g class="corners" fill="black">')
    out.extend(
        f'<circle cx="{_f(x)}" cy="{_f(y)}" r="2.5"/>'
        for x, y in frame.xy(corners(spline)).tolist()
    )
    out.append("</g>")
    ((sx, sy),) = frame.xy(c.start[:1]).tolist()
    out.append(
        f'<text class="number" x="{_f(sx + 4)}" y="{_f(sy - 4)}" font-size="13" '
        f'font-weight="bold" fill="{colour}">{k}</text>'
    )
    out.append("</g>")
    (x0, y0), (x1, y1) = frame.xy(np.stack([low, high])).tolist()
    pad = 0.1 * max(x1 - x0, y0 - y1, 1.0) + magnify * spline.tolerance * frame.scale
    view = (
        f'<view id="view-toolpath-{k}" viewBox="{_f(x0 - pad)} {_f(y1 - pad)} '
        f'{_f(x1 - x0 + 2 * pad)} {_f(y0 - y1 + 2 * pad)}"/>'
    )
    return out, view


def _rapids(
    splines: Sequence[ArcSpline], start: tuple[float, float], frame: Frame
) -> tuple[list[str], float]:
    """Dashed lines from ``start`` to the first toolpath and between consecutive ones, and
    their total length (drawing units)."""
    here = np.asarray(start, dtype=np.float64)
    out = ['<g class="rapids" stroke="#777777" stroke-width="1" stroke-dasharray="6 4">']
    total = 0.0
    for k, spline in enumerate(splines, start=1):
        c = spline.columns
        (x0, y0), (x1, y1) = frame.xy(np.stack([here, c.start[0]])).tolist()
        length = float(np.hypot(*(c.start[0] - here)))
        total += length
        out.append(
            f'<line class="rapid" x1="{_f(x0)}" y1="{_f(y0)}" x2="{_f(x1)}" y2="{_f(y1)}">'
            f"<title>rapid to toolpath {k}: {length:.6g}</title></line>"
        )
        here = c.end[-1]
    out.append("</g>")
    return out, total


def _tool_view(tool: ToolView, splines: Sequence[ArcSpline], frame: Frame) -> list[str]:
    """The contours (thin, grey) and the swept band along each tool path (see the module
    docstring)."""
    width_px = tool.width * frame.scale
    out = [f'<g class="contours" fill="none" stroke="{CONTOUR_COLOUR}" stroke-width="0.8">']
    out.extend(
        f'<path class="contour" d="{_path_data(c, frame)}"/>' for c in tool.contours if len(c)
    )
    out.append(
        f'</g><g class="swept" fill="none" stroke="{SWEPT_COLOUR}" '
        f'stroke-opacity="{SWEPT_OPACITY:g}" stroke-width="{width_px:.6g}" '
        'stroke-linecap="round" stroke-linejoin="round">'
    )
    out.extend(f'<path class="band" d="{_path_data(s, frame)}"/>' for s in splines)
    out.append("</g>")
    return out


def render_drawing(
    parts: Sequence[Part],
    *,
    units: str = "mm",
    start: tuple[float, float] = (0.0, 0.0),
    tool: ToolView | None = None,
) -> str:
    """The picture described in the module docstring, as an SVG document. ``units`` names
    the drawing's units in the labels; ``start`` is where the tool is before the first
    rapid; ``tool`` adds the contours and the swept width of tool-centre paths."""
    parts = [part for part in parts if len(part[0])]
    splines = [spline for spline, _ in parts]
    framed = splines if tool is None else [*splines, *(c for c in tool.contours if len(c))]
    frame = _frame(framed, Point(*start))
    segments = sum(len(s) for s in splines)
    per = max(MIN_SAMPLES, min(MAX_SAMPLES, DEVIATION_SAMPLES // max(segments, 1)))
    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH_PX:.0f}" '
        f'height="{HEIGHT_PX:.0f}" viewBox="0 0 {WIDTH_PX:.0f} {HEIGHT_PX:.0f}" '
        'font-family="sans-serif" font-size="13">',
        "<title>arcspline drawing preview</title>",
        f'<rect width="{WIDTH_PX:.0f}" height="{HEIGHT_PX:.0f}" fill="white"/>',
    ]
    views: list[str] = []
    body: list[str] = []
    for k, part in enumerate(parts, start=1):
        group, view = _toolpath(k, part[0], part[1], frame, per)
        body.extend(group)
        views.append(view)
    rapids, rapid_length = _rapids(splines, start, frame) if splines else ([], 0.0)
    out.extend(views)
    out.extend(_axes(frame, units))
    if tool is not None:
        out.extend(_tool_view(tool, splines, frame))
    out.extend(rapids)
    out.extend(body)
    legend = [
        f"{len(parts)} toolpaths, {segments} segments, numbered in cutting order; "
        f"rapids dashed ({rapid_length:.6g} {units}); corners (turn > {CORNER_DEG:g}°) dotted",
        "green: deviation magnified per toolpath (hover for ×M) inside the grey band "
        "±tolerance ×M; open #view-toolpath-k to zoom to toolpath k",
    ]
    if tool is not None:
        legend.append(
            f"tool-centre paths ({tool.label}); grey: the part's contours; blue band: the "
            f"swept width {tool.width:g} {units}"
        )
    out.extend(legend_lines(legend))
    out.append("</svg>")
    return "\n".join(out)


class DrawingPreviewWriter:
    """The preview as an output writer; its options are the name of the drawing's unit, or
    :class:`PreviewOptions`."""

    name = "drawing-preview"
    media_type = MEDIA_TYPE

    def write(self, parts: Sequence[Part], options: str | PreviewOptions | None) -> str:
        if isinstance(options, PreviewOptions):
            return render_drawing(parts, units=options.units, tool=options.tool)
        return render_drawing(parts, units=options or "mm")


WRITER = DrawingPreviewWriter()
