"""An SVG picture of an approximation, for a person to look at (``POST /v1/preview``).

It shows the curve (thin black), the arcs in alternating colours with a dot at each centre,
and the deviation magnified: for each segment the curve ``P(u) + M·e(u)·n(u)``, where ``P``
is the curve's point projected onto the segment, ``e`` its signed distance from the segment
and ``n`` the segment's normal there, drawn inside the equally magnified tolerance band
``±M·tolerance``. ``M`` is a round number chosen so that the band is a few per cent of the
picture.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from arcspline.geometry import ArcSpline, Curve, GeometryError
from arcspline.geometry.spline import FloatArray

from .part import Part

MEDIA_TYPE = "image/svg+xml"
WIDTH_PX = 900
#: The magnified tolerance band takes about this fraction of the picture's size.
BAND_FRACTION = 0.04
#: Samples of the deviation curve, over all segments together (at least 8 per segment).
DEVIATION_SAMPLES = 4000
COLOURS = ("#1f77b4", "#d62728")
#: Room above the drawing for the legend.
HEADER_PX = 50


def nice_number(x: float) -> float:
    """The largest of 1, 2, 5 × 10^k not above ``x`` (for a readable magnification).

    ``x`` is first clamped to [1e-300, 1e300], so that extreme scales still draw.
    """
    x = min(max(x, 1e-300), 1e300) if math.isfinite(x) else 1e300
    exponent = math.floor(math.log10(x))
    mantissa = x / 10.0**exponent
    step = 5.0 if mantissa >= 5 else 2.0 if mantissa >= 2 else 1.0
    return step * 10.0**exponent


def _segment_samples(spline: ArcSpline, per: int) -> tuple[FloatArray, npt.NDArray[np.intp]]:
    """Parameters ``u`` sampled within every segment (``per`` each), and each sample's
    segment index."""
    c = spline.columns
    n = len(c)
    t = np.linspace(0.0, 1.0, per)
    u = c.u_start[:, None] + (c.u_end - c.u_start)[:, None] * t[None, :]
    index = np.repeat(np.arange(n), per).reshape(n, per)
    return u, index


def deviation_curves(
    curve: Curve, spline: ArcSpline, magnify: float, per: int
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Per segment (rows): the magnified deviation curve and both band edges, ``(n, per, 2)``."""
    c = spline.columns
    u, index = _segment_samples(spline, per)
    q = curve.eval(u)
    # Lines: project onto the chord, normal to its left.
    chord = c.end - c.start
    tangent = chord / np.maximum(np.hypot(chord[:, 0], chord[:, 1]), 1e-300)[:, None]
    normal_line = np.stack([-tangent[:, 1], tangent[:, 0]], axis=-1)
    rel = q - c.start[index]
    along = np.einsum("nki,nki->nk", rel, tangent[index])
    foot_line = c.start[index] + along[..., None] * tangent[index]
    e_line = np.einsum("nki,nki->nk", rel, normal_line[index])
    # Arcs: radial from the centre, outward.
    radial = q - c.center[index]
    dist = np.hypot(radial[..., 0], radial[..., 1])
    out = radial / np.maximum(dist, 1e-300)[..., None]
    radius = np.where(c.is_arc, c.radius, 0.0)[index]
    foot_arc = c.center[index] + radius[..., None] * out
    e_arc = dist - radius

    is_arc = c.is_arc[index][..., None]
    foot = np.where(is_arc, foot_arc, foot_line)
    direction = np.where(is_arc, out, normal_line[index])
    e = np.where(is_arc[..., 0], e_arc, e_line)
    band = magnify * spline.tolerance
    magnified = foot + (magnify * e)[..., None] * direction
    return magnified, foot + band * direction, foot - band * direction


@dataclass(frozen=True)
class Layout:
    """Everything to draw, in picture coordinates (pixels, y down)."""

    width_px: float
    height_px: float
    magnify: float
    paths: list[FloatArray]  # (k, 2) each curve
    starts: FloatArray  # (n, 2)
    ends: FloatArray  # (n, 2)
    centres: FloatArray  # (n, 2), meaningful for arcs
    radii: FloatArray  # (n,), meaningful for arcs
    curve: FloatArray  # (n, m, 2) the magnified deviation
    band_out: FloatArray  # (n, m, 2)
    band_in: FloatArray  # (n, m, 2)


def _joined(splines: Sequence[ArcSpline]) -> ArcSpline:
    """The parts' splines as one (for drawing: the segments in order)."""
    if len(splines) == 1:
        return splines[0]
    first = splines[0]
    table = np.concatenate([s.table for s in splines])
    worst = max(splines, key=lambda s: s.stats.max_deviation).stats
    return ArcSpline(table, worst, first.tolerance, first.strategy)


def layout(parts: Sequence[Part]) -> Layout:
    """Place the picture; a curve whose numbers overflow on the way cannot be drawn.

    Raises :class:`GeometryError` (kind ``precision``) when any coordinate of the picture is
    not finite, as near the largest floating-point numbers.
    """
    spline = _joined([s for s, _ in parts])
    c = spline.columns
    with np.errstate(all="ignore"):
        paths = [
            curve.eval(
                np.linspace(*curve.domain, 400 + 16 * int(curve.domain[1] - curve.domain[0]))
            )
            for _, curve in parts
        ]
        every = np.concatenate(paths)
        low, high = every.min(axis=0), every.max(axis=0)
        extent = float(max(high[0] - low[0], high[1] - low[1], 1e-300))
        # Centres near the curve join the picture; far ones (flat arcs) show by their spokes.
        centres = c.center[c.is_arc]
        near = np.all((centres >= low - extent) & (centres <= high + extent), axis=1)
        if near.any():
            low = np.minimum(low, centres[near].min(axis=0))
            high = np.maximum(high, centres[near].max(axis=0))
        extent = float(max(high[0] - low[0], high[1] - low[1], 1e-300))
        magnify = nice_number(BAND_FRACTION * extent / spline.tolerance)
        margin = 0.08 * extent + magnify * spline.tolerance
        x0, y1 = low[0] - margin, high[1] + margin
        scale = WIDTH_PX / (high[0] - low[0] + 2 * margin)
        height_px = max(200.0, float((high[1] - low[1] + 2 * margin) * scale)) + HEADER_PX

        def xy(points: FloatArray) -> FloatArray:
            # World (y up) to picture (y down) coordinates.
            x = (points[..., 0] - x0) * scale
            y = (y1 - points[..., 1]) * scale + HEADER_PX
            return np.stack([x, y], axis=-1)

        per = max(8, DEVIATION_SAMPLES // max(len(c), 1))
        curves = [deviation_curves(curve, part, magnify, per) for part, curve in parts]
        deviation, band_out, band_in = (np.concatenate(a) for a in zip(*curves, strict=True))
        result = Layout(
            width_px=WIDTH_PX,
            height_px=height_px,
            magnify=magnify,
            paths=[xy(path) for path in paths],
            starts=xy(c.start),
            ends=xy(c.end),
            centres=xy(c.center),
            radii=np.where(c.is_arc, c.radius, 0.0) * scale,
            curve=xy(deviation),
            band_out=xy(band_out),
            band_in=xy(band_in),
        )
    arrays = (*result.paths, result.starts, result.ends, result.curve, result.band_out)
    finite = all(bool(np.isfinite(a).all()) for a in (*arrays, result.band_in))
    arcs = c.is_arc
    finite = finite and bool(np.isfinite(result.centres[arcs]).all())
    finite = finite and bool(np.isfinite(result.radii).all()) and math.isfinite(height_px)
    if not finite:
        raise GeometryError(
            "spiral", "its coordinates are too large to draw (they overflow)", kind="precision"
        )
    return result


def _points(points: FloatArray) -> str:
    return " ".join(f"{x:.2f},{y:.2f}" for x, y in points.tolist())


def render_svg(parts: Sequence[Part]) -> str:
    """The picture described in the module docstring, as an SVG document."""
    spline = _joined([s for s, _ in parts])
    c = spline.columns
    picture = layout(parts)
    width, height, magnify = picture.width_px, picture.height_px, picture.magnify
    stroke = max(1.0, width / 600)
    out: list[str] = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0f}" height="{height:.0f}" '
        f'viewBox="0 0 {width:.0f} {height:.2f}" font-family="sans-serif" font-size="13">',
        "<title>arcspline preview</title>",
        f'<rect width="{width:.0f}" height="{height:.2f}" fill="white"/>',
        '<g fill="#eeeeee" stroke="none">',
    ]
    for outer, inner in zip(picture.band_out, picture.band_in, strict=True):
        out.append(f'<polygon points="{_points(np.concatenate([outer, inner[::-1]]))}"/>')
    out.append("</g>")
    out.extend(
        f'<polyline points="{_points(path)}" fill="none" stroke="black" '
        f'stroke-width="{stroke * 0.6:.2f}"/>'
        for path in picture.paths
    )
    starts, ends = picture.starts.tolist(), picture.ends.tolist()
    centres, radii = picture.centres.tolist(), picture.radii.tolist()
    for i in range(len(c)):
        colour = COLOURS[i % 2]
        (sx, sy), (ex, ey) = starts[i], ends[i]
        if c.is_arc[i]:
            sweep = float(c.sweep_rad[i])
            large = 1 if abs(sweep) > math.pi else 0
            # y is flipped, so an anticlockwise arc is drawn with SVG's sweep-flag 0.
            flag = 0 if sweep > 0 else 1
            r = radii[i]
            d = f"M{sx:.2f},{sy:.2f} A{r:.6g},{r:.6g} 0 {large} {flag} {ex:.2f},{ey:.2f}"
            cx, cy = centres[i]
            out.append(
                f'<path d="M{sx:.2f},{sy:.2f} L{cx:.2f},{cy:.2f} L{ex:.2f},{ey:.2f}" '
                f'fill="none" stroke="{colour}" stroke-width="{stroke * 0.5:.2f}" '
                'stroke-opacity="0.3"/>'
            )
            out.append(
                f'<circle cx="{cx:.2f}" cy="{cy:.2f}" r="{stroke * 2.5:.2f}" fill="{colour}"/>'
            )
        else:
            d = f"M{sx:.2f},{sy:.2f} L{ex:.2f},{ey:.2f}"
        out.append(
            f'<path d="{d}" fill="none" stroke="{colour}" stroke-width="{stroke * 2:.2f}" '
            'stroke-opacity="0.7"/>'
        )
    out.append(f'<g fill="none" stroke="#2ca02c" stroke-width="{stroke:.2f}">')
    out.extend(f'<polyline points="{_points(segment)}"/>' for segment in picture.curve)
    out.append("</g>")
    s = spline.stats
    arc_count = int(c.is_arc.sum())
    legend = [
        f"{arc_count} arcs, {len(c) - arc_count} lines ({spline.strategy}); "
        f"tolerance {spline.tolerance:.3g}, max deviation {s.max_deviation:.3g} "
        f"(ratio {s.deviation_ratio:.2f})",
        f"green: deviation ×{magnify:g} inside the grey band ±tolerance ×{magnify:g}; "
        "dots: arc centres, with spokes to each arc's ends",
    ]
    out.extend(legend_lines(legend))
    out.append("</svg>")
    return "\n".join(out)


def legend_lines(texts: Sequence[str]) -> list[str]:
    """A legend's lines of text at the picture's top left, one below the other."""
    return [f'<text x="10" y="{20 + 18 * k}">{text}</text>' for k, text in enumerate(texts)]


class SvgWriter:
    """The preview as an output writer (it takes no options)."""

    name = "svg"
    media_type = MEDIA_TYPE

    def write(self, parts: Sequence[Part], options: Any = None) -> str:
        return render_svg(parts)


WRITER = SvgWriter()
