"""An arc spline as a DXF drawing (AutoCAD R2000, ASCII), written with ezdxf.

Each part becomes LINE and ARC entities, one per segment (the default), or one LWPOLYLINE
whose vertices carry bulges (``polyline=True``; closed when the part ends where it starts).
Every number is written as Python's ``repr`` of the double (ezdxf does so), so a reader gets
the spline's own coordinates back:

* a LINE's end points are the segment's end points, exactly;
* an ARC's centre and radius are the segment's; its angles (degrees, anticlockwise, from
  the centre) are the polar angles of the segment's end points about the centre, so its end
  points read back as ``centre + radius·(cos, sin)``, within a few ulps of the radius of the
  segment's own. DXF arcs always run anticlockwise from ``start_angle`` to ``end_angle``: a
  clockwise segment is written from its end to its start (the same points of the plane).
  Where the sweep is so near 0 or 360° that rounding of the end points makes the angles
  say otherwise (equal angles read as a full circle; swapped ones as the complement), the
  sweep decides: a tiny arc is written as its chord (its sweep is at the rounding level,
  ~1e-15 rad, so its sagitta is below 1e-29 of its radius), a near circle as two ARCs
  meeting halfway;
* an LWPOLYLINE vertex carries the bulge ``tan(sweep/4)`` of the segment that starts there
  (positive anticlockwise, DXF reference "LWPOLYLINE"), which with the two vertices fixes
  the arc.

``$INSUNITS`` says the units (4 millimetres, 1 inches) and ``$MEASUREMENT`` the matching
system (1 metric, 0 imperial); ``$EXTMIN``/``$EXTMAX`` bound the drawing. The entities are
on the layer ``ARCSPLINE``, or part ``k`` (from 1, cutting order) on ``TOOLPATH_k`` with
``layer_per_part``. See docs/drawings.md §7.

The same spline gives the same bytes: ezdxf would stamp each file with the time and fresh
GUIDs (``$TDCREATE``, ``$TDUPDATE``, ``$VERSIONGUID``, ``$FINGERPRINTGUID``), and its
``write_fixed_meta_data_for_testing`` option writes fixed ones instead (2000-01-01, a
constant GUID). A program of ours is a function of its request — cached, compared, the
command line's local answer equal to the server's — so the option is on while this module
writes, and as it was otherwise (the option is ezdxf's, process-wide: an application that
imports arcspline and writes DXF of its own keeps its time stamps). ezdxf itself is imported
then too: it takes a quarter of a second, which every process that names a writer (the
client, the command line) would otherwise pay.
"""

from __future__ import annotations

import contextlib
import io
import math
import threading
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal, get_args

import numpy as np

from arcspline.geometry import GeometryError
from arcspline.geometry.spline import ArcSpline, FloatArray

from .extents import check_finite, extents
from .part import Part

if TYPE_CHECKING:
    from ezdxf.document import Drawing
    from ezdxf.layouts.layout import Modelspace

MEDIA_TYPE = "image/vnd.dxf"
DXF_VERSION = "R2000"
Units = Literal["mm", "inch"]
UNITS: tuple[str, ...] = get_args(Units)
#: ``$INSUNITS`` codes (DXF reference, HEADER section).
INSUNITS = {"mm": 4, "inch": 1}
#: ``$MEASUREMENT``: 0 imperial, 1 metric.
MEASUREMENT = {"mm": 1, "inch": 0}
LAYER = "ARCSPLINE"
#: The layer of part ``k`` (from 1) with ``layer_per_part``.
TOOLPATH_LAYER = "TOOLPATH_{}"


@dataclass(frozen=True, slots=True)
class DxfOptions:
    """How to write the drawing; validated on construction (raises :class:`GeometryError`
    naming the option). The spline's coordinates are taken to be in ``units`` already."""

    units: Units = "mm"
    polyline: bool = False
    layer_per_part: bool = False

    def __post_init__(self) -> None:
        if self.units not in UNITS:
            raise GeometryError("units", f"must be one of {', '.join(UNITS)}, got {self.units!r}")
        for name in ("polyline", "layer_per_part"):
            value = getattr(self, name)
            if not isinstance(value, bool):
                raise GeometryError(name, f"must be true or false, got {value!r}")


def _polar_deg(point: FloatArray, centre: FloatArray) -> float:
    """The polar angle of ``point`` about ``centre`` in degrees, in ``[0, 360)``."""
    angle = math.degrees(math.atan2(point[1] - centre[1], point[0] - centre[0]))
    return angle % 360.0


def _add_arc(
    msp: Modelspace,
    centre: FloatArray,
    radius: float,
    start: FloatArray,
    end: FloatArray,
    sweep_rad: float,
    attribs: dict[str, str],
) -> None:
    """One ARC from ``start`` to ``end`` (two when needed, or the chord: module docstring)."""
    start_deg, end_deg = _polar_deg(start, centre), _polar_deg(end, centre)
    if sweep_rad < 0.0:  # DXF arcs run anticlockwise
        start_deg, end_deg = end_deg, start_deg
    sweep_deg = math.degrees(abs(sweep_rad))
    ccw_deg = (end_deg - start_deg) % 360.0
    centre_xy = (float(centre[0]), float(centre[1]))
    # Near 0 or 360 degrees, rounding of the end points can swap what the angles say: a
    # sliver for a near circle or the reverse. The sweep decides.
    if ccw_deg != 0.0 and abs(ccw_deg - sweep_deg) <= 180.0:
        msp.add_arc(centre_xy, radius, start_deg, end_deg, dxfattribs=attribs)
    elif sweep_deg > 180.0:
        middle_deg = (start_deg + sweep_deg / 2) % 360.0
        msp.add_arc(centre_xy, radius, start_deg, middle_deg, dxfattribs=attribs)
        msp.add_arc(centre_xy, radius, middle_deg, end_deg, dxfattribs=attribs)
    else:
        msp.add_line(
            (float(start[0]), float(start[1])), (float(end[0]), float(end[1])), dxfattribs=attribs
        )


def _add_segments(msp: Modelspace, spline: ArcSpline, layer: str) -> None:
    """One LINE or ARC per segment."""
    c = spline.columns
    attribs = {"layer": layer}
    for i in range(len(c)):
        start, end, centre = c.start[i], c.end[i], c.center[i]
        if c.is_arc[i]:
            _add_arc(msp, centre, float(c.radius[i]), start, end, float(c.sweep_rad[i]), attribs)
            continue
        msp.add_line(
            (float(start[0]), float(start[1])), (float(end[0]), float(end[1])), dxfattribs=attribs
        )


def _add_polyline(msp: Modelspace, spline: ArcSpline, layer: str) -> None:
    """One LWPOLYLINE for the whole spline, its arcs as bulges."""
    c = spline.columns
    if len(c) == 0:
        return
    bulge = np.where(c.is_arc, np.tan(c.sweep_rad / 4.0), 0.0)
    points = [(float(x), float(y), float(b)) for (x, y), b in zip(c.start, bulge, strict=True)]
    closed = len(c) > 1 and bool((c.end[-1] == c.start[0]).all())
    if not closed:
        points.append((float(c.end[-1, 0]), float(c.end[-1, 1]), 0.0))
    msp.add_lwpolyline(points, format="xyb", close=closed, dxfattribs={"layer": layer})


def _new_document(units: Units) -> Drawing:
    from ezdxf.filemanagement import new

    return new(DXF_VERSION, units=INSUNITS[units])


#: Our writes with the fixed metadata, one at a time (the option is process-wide).
_FIXED_METADATA = threading.Lock()


@contextlib.contextmanager
def _fixed_metadata() -> Iterator[None]:
    """ezdxf's fixed metadata while a document is made and written (see the module
    docstring), and the option as it was afterwards."""
    from ezdxf import options  # type: ignore[attr-defined]  # re-exported, not declared

    with _FIXED_METADATA:
        before = options.write_fixed_meta_data_for_testing
        options.write_fixed_meta_data_for_testing = True
        try:
            yield
        finally:
            options.write_fixed_meta_data_for_testing = before


def write_dxf(parts: Sequence[Part], options: DxfOptions) -> str:
    """The drawing described in the module docstring, as DXF text."""
    with _fixed_metadata():
        return _write(parts, options)


def _write(parts: Sequence[Part], options: DxfOptions) -> str:
    splines = [spline for spline, _ in parts]
    check_finite(splines, "DXF")
    doc = _new_document(options.units)
    doc.header["$MEASUREMENT"] = MEASUREMENT[options.units]
    msp = doc.modelspace()
    # ezdxf copies the model space's extents into $EXTMIN/$EXTMAX when it writes, unless
    # they are both zero vectors (within 1e-12): set both.
    low, high = extents(splines)
    for name, corner in (("extmin", low), ("extmax", high)):
        point = (float(corner[0]), float(corner[1]), 0.0)
        msp.dxf.set(name, point)
        doc.header[f"${name.upper()}"] = point
    layers = (
        [TOOLPATH_LAYER.format(k + 1) for k in range(len(splines))]
        if options.layer_per_part
        else [LAYER]
    )
    for name in layers:
        doc.layers.add(name)
    add = _add_polyline if options.polyline else _add_segments
    for k, spline in enumerate(splines):
        add(msp, spline, layers[k] if options.layer_per_part else LAYER)
    stream = io.StringIO()
    doc.write(stream)
    return stream.getvalue()


class DxfWriter:
    """The DXF drawing as an output writer (options: :class:`DxfOptions`, or None for the
    defaults)."""

    name = "dxf"
    media_type = MEDIA_TYPE

    def write(self, parts: Sequence[Part], options: DxfOptions | None = None) -> str:
        return write_dxf(parts, options if options is not None else DxfOptions())


WRITER = DxfWriter()
