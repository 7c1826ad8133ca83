"""What an arc spline is turned into: each output a writer behind one protocol.

A writer is a module with a ``WRITER`` (:class:`Writer`) and one line in :data:`WRITERS`:
``gcode`` (an RS-274 program, ``gcode/``), ``svg`` (a picture of the approximation,
``svg.py``), ``dxf`` (an R2000 DXF of lines and arcs, ``dxf.py``), ``svg-document`` (the
toolpaths as an SVG document in mm, ``svg_document.py``) and ``drawing-preview`` (a whole
drawing in cutting order, ``drawing_preview.py``). Writers are pure: parts (arc splines and
the curves they approximate: a spiral is one part, a path one per subpath) and the writer's
options in, text out; what they refuse
they raise as their own error (:class:`~.gcode.GcodeError`) or a
:class:`~arcspline.geometry.GeometryError`.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol

from . import drawing_preview, dxf, gcode, svg, svg_document
from .part import Part


class Writer(Protocol):
    """Turns an approximation into a document of one format."""

    @property
    def name(self) -> str:
        """The output's name in requests and responses."""

    @property
    def media_type(self) -> str:
        """The document's media type."""

    def write(self, parts: Sequence[Part], options: Any) -> str:
        """The document of ``parts`` (arc splines and the curves they approximate)."""


#: The writers by name.
WRITERS: dict[str, Writer] = {
    writer.name: writer
    for writer in (
        gcode.WRITER,
        svg.WRITER,
        dxf.WRITER,
        svg_document.WRITER,
        drawing_preview.WRITER,
    )
}

__all__ = ["WRITERS", "Part", "Writer"]
