"""Request and response models of the drawing endpoints (``/v1/drawings/...``): a whole SVG
or DXF document, as a JSON body (``document`` text, or base64 for binary DXF) or as the raw
file with the options as query parameters (docs/http-api.md, "Drawings")."""

from __future__ import annotations

import base64
import binascii
from typing import TYPE_CHECKING, Annotated, Any, Literal

from pydantic import ConfigDict, Field, StringConstraints, model_validator

from arcspline.geometry import StrategyName

from .offset_schemas import (
    BOTH_MESSAGE,
    MACHINING_DESCRIPTION,
    OFFSET_DESCRIPTION,
    MachiningRequest,
    MachiningResponse,
    OffsetRequest,
    OffsetResponse,
)
from .path_schemas import PathStatsResponse, SubpathResponse
from .schemas import OUTPUT_DESCRIPTION, GcodeRequest, OutputFormat, RequestModel, ResponseModel

if TYPE_CHECKING:
    # The readers (ezdxf, defusedxml) load where documents are read, not in every process
    # that only names these models (the Python client, the command line's --server mode).
    from arcspline.drawings.approximate import DrawingOptions
    from arcspline.drawings.document import DocumentSpec
    from arcspline.drawings.model import DocumentLimits

#: Longest ``document`` accepted in a JSON body (characters); the body limit caps it too.
MAX_DOCUMENT = 8_000_000
MAX_LAYERS = 1000
#: Longest layer name (AutoCAD's limit since R2000).
MAX_LAYER_NAME = 255
LayerName = Annotated[str, StringConstraints(max_length=MAX_LAYER_NAME)]
SourceUnits = Literal["mm", "cm", "m", "in", "ft", "pt", "pc", "px"]

DRAWING_EXAMPLE: dict[str, Any] = {
    "document": (
        '<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="40mm" '
        'viewBox="0 0 60 40"><path d="M 5 35 C 15 5 45 5 55 35 Z"/>'
        '<circle cx="30" cy="25" r="6"/></svg>'
    ),
    "format": "svg",
    "tolerance": 0.01,
    "strategy": "fewest-arcs",
}


class DxfRequest(RequestModel):
    """How the ``dxf`` output is written."""

    polyline: bool = Field(
        default=False,
        description="One LWPOLYLINE with bulges per toolpath instead of a LINE or ARC per segment.",
    )
    layer_per_toolpath: bool = Field(
        default=False, description="Each toolpath on a layer of its own, TOOLPATH_1, ..."
    )


class DrawingRequest(RequestModel):
    """A drawing to cut: an SVG or DXF document, approximated toolpath by toolpath within
    ``tolerance`` (in ``units``), joined and ordered into one program."""

    model_config = ConfigDict(json_schema_extra={"examples": [DRAWING_EXAMPLE]})

    document: str = Field(
        max_length=MAX_DOCUMENT,
        description="The document: SVG or ASCII DXF text, or base64 (see `encoding`); the "
        "server's body limit (ARCSPLINE_MAX_BODY_BYTES, 4 MiB by default) applies first.",
    )
    format: Literal["svg", "dxf"] = Field(description="The document's format.")
    encoding: Literal["text", "base64"] = Field(
        default="text", description="`base64` for binary DXF (or any document as bytes)."
    )
    tolerance: float = Field(gt=0, description="Largest distance allowed from the drawing.")
    strategy: StrategyName = Field(default="subdivide", description="As for paths.")
    units: Literal["mm", "inch"] = Field(
        default="mm", description="The unit of the output and of every length in the request."
    )
    source_units: SourceUnits | None = Field(
        default=None,
        description="The unit of the document's own numbers, overriding what it declares "
        "(DXF `$INSUNITS`; SVG: one user unit).",
    )
    layers: list[LayerName] | None = Field(
        default=None, max_length=MAX_LAYERS, description="DXF: read only these layers."
    )
    join_tolerance: float | None = Field(
        default=None,
        ge=0,
        description="Ends closer than this are joined into one toolpath (default: a tenth of "
        "the tolerance; below half of it); the fit keeps the rest of the tolerance.",
    )
    order: bool = Field(default=True, description="Order toolpaths to shorten the rapids.")
    choose_start: bool = Field(
        default=False, description="Start each closed contour at its vertex nearest the tool."
    )
    output: OutputFormat | None = Field(default=None, description=OUTPUT_DESCRIPTION)
    gcode: GcodeRequest | None = Field(
        default=None, description="G-code options (needed for the `gcode` output)."
    )
    dxf: DxfRequest | None = Field(default=None, description="Options of the `dxf` output.")
    offset: OffsetRequest | None = Field(default=None, description=OFFSET_DESCRIPTION)
    machining: MachiningRequest | None = Field(default=None, description=MACHINING_DESCRIPTION)

    @model_validator(mode="after")
    def _one_tool(self) -> DrawingRequest:
        if self.offset is not None and self.machining is not None:
            raise ValueError(BOTH_MESSAGE)
        return self

    @model_validator(mode="after")
    def _gcode_units(self) -> DrawingRequest:
        gcode = self.gcode
        if gcode is not None and "units" in gcode.model_fields_set and gcode.units != self.units:
            raise ValueError(
                f"gcode.units ({gcode.units}) differs from units ({self.units}); "
                "give units once, at the top"
            )
        return self

    def content(self) -> bytes:
        """The document's bytes (raises ValueError for base64 that does not decode)."""
        if self.encoding == "text":
            return self.document.encode()
        try:
            return base64.b64decode(self.document, validate=True)
        except (binascii.Error, ValueError):
            raise ValueError("is not valid base64") from None

    def spec(self, content: bytes, limits: DocumentLimits) -> DocumentSpec:
        from arcspline.drawings.document import DocumentSpec

        layers = None if self.layers is None else tuple(self.layers)
        curve_tolerance_mm = self.options().curve_tolerance_mm
        return DocumentSpec(
            content, self.format, self.source_units, layers, limits, curve_tolerance_mm
        )

    def options(self) -> DrawingOptions:
        from arcspline.drawings.approximate import DrawingOptions

        return DrawingOptions(
            self.tolerance, self.strategy, self.units, self.join_tolerance, self.order,
            self.choose_start,
        )  # fmt: skip


# -- responses ---------------------------------------------------------------------------


class ToolpathResponse(SubpathResponse):
    """A toolpath in cutting order: joined from the elements named in ``sources`` (a
    tool-centre path: those of the contour it was drawn from)."""

    sources: list[str]


class DrawingStatsResponse(PathStatsResponse):
    """As for a path; ``tolerance`` is what the toolpaths were fitted to (``budget.fit``)."""

    toolpath_count: int
    max_deviation_toolpath: int


class DrawingWarningResponse(ResponseModel):
    element: str
    reason: str
    occurrences: int


class DocumentSummaryResponse(ResponseModel):
    """What the document held: ``elements_in = elements_read + elements_skipped``."""

    units: str = Field(description="The unit its numbers were taken in.")
    elements_in: int
    elements_read: int
    elements_skipped: int
    warnings: list[DrawingWarningResponse]


class BudgetResponse(ResponseModel):
    """How the tolerance is spent, so that every segment stays within ``tolerance`` of the
    drawing as given: ``fit = tolerance − curve_approximation − snap_move − join_gap``."""

    tolerance: float
    curve_approximation: float = Field(
        description="Largest distance of a curve the reader approximated (a rational cubic "
        "spline), certified; 0 when every element is exact."
    )
    snap_move: float = Field(
        description="Largest move of a control point put on its end point (a near cusp)."
    )
    join_gap: float = Field(description="Largest gap closed by joining.")
    fit: float = Field(description="The tolerance the toolpaths were fitted to.")


class JoinResponse(ResponseModel):
    tolerance: float
    joins: int


class RapidsResponse(ResponseModel):
    """Length of the rapid moves from the origin through every toolpath."""

    before: float = Field(description="In the document's order.")
    after: float = Field(description="In cutting order.")


class DrawingResponse(ResponseModel):
    """The toolpaths in cutting order, certified, with the program if asked for."""

    toolpaths: list[ToolpathResponse]
    stats: DrawingStatsResponse
    units: Literal["mm", "inch"]
    document: DocumentSummaryResponse
    budget: BudgetResponse
    join: JoinResponse
    rapids: RapidsResponse
    gcode: str | None
    offset: OffsetResponse | None = Field(
        default=None, description="With an `offset`: the toolpaths are the tool-centre paths."
    )
    machining: MachiningResponse | None = Field(
        default=None, description="With `machining`: the toolpaths are the tool-centre paths."
    )
