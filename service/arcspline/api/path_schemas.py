"""Request and response models of the path endpoints (``/v1/paths/...``): the public
contract, as the OpenAPI document shows it. A path is SVG path data or the explicit JSON form
(subpaths of typed segments); the worker builds and checks it (``arcspline.paths``), so what
only the geometry can decide (a degenerate segment, an unreachable tolerance) comes back as a
422 naming ``path.subpaths.i.segments.j``.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import (
    ConfigDict,
    Discriminator,
    Field,
    StringConstraints,
    Tag,
    field_validator,
    model_validator,
)

from arcspline.geometry import StrategyName
from arcspline.paths import PathFromData, PathFromSegments, PathSpec
from arcspline.paths.specs import (
    ArcAbout,
    CubicTo,
    EllipticalArcTo,
    LineTo,
    QuadraticTo,
    SegmentForm,
    SubpathForm,
)

from .offset_schemas import (
    BOTH_MESSAGE,
    MACHINING_DESCRIPTION,
    OFFSET_DESCRIPTION,
    MachiningRequest,
    MachiningResponse,
    OffsetRequest,
    OffsetResponse,
)
from .schemas import (
    OUTPUT_DESCRIPTION,
    ArcSegmentResponse,
    BatchErrorResponse,
    GcodeRequest,
    LineSegmentResponse,
    OutputFormat,
    RequestModel,
    ResponseModel,
    ValidatedByRoute,
    Vector,
    batch_jobs,
)

#: Longest SVG path data accepted (characters); the body limit caps it too.
MAX_PATH_DATA = 2_000_000
#: Most subpaths and segments per subpath in the JSON form.
MAX_SUBPATHS = 10_000
MAX_SEGMENTS_PER_SUBPATH = 100_000

PATH_EXAMPLE: dict[str, Any] = {
    "path": "M 0 0 C 10 0 20 10 30 30 L 40 30 A 5 5 0 0 1 50 30 Z",
    "tolerance": 0.01,
    "strategy": "fewest-arcs",
}


def _xy(v: list[float]) -> tuple[float, float]:
    return (v[0], v[1])


class LineSegmentRequest(RequestModel):
    """A straight segment to ``to``."""

    type: Literal["line"]
    to: Vector

    def form(self) -> SegmentForm:
        return LineTo(_xy(self.to))


class QuadraticSegmentRequest(RequestModel):
    """A quadratic Bézier curve."""

    type: Literal["quadratic"]
    control: Vector
    to: Vector

    def form(self) -> SegmentForm:
        return QuadraticTo(_xy(self.control), _xy(self.to))


class CubicSegmentRequest(RequestModel):
    """A cubic Bézier curve (any four points)."""

    type: Literal["cubic"]
    control1: Vector
    control2: Vector
    to: Vector

    def form(self) -> SegmentForm:
        return CubicTo(_xy(self.control1), _xy(self.control2), _xy(self.to))


class ArcSegmentRequest(RequestModel):
    """A circular arc about ``center`` from the current point, turning ``sweep_deg``
    (anticlockwise positive, less than a full turn)."""

    type: Literal["arc"]
    center: Vector
    sweep_deg: float = Field(gt=-360, lt=360, json_schema_extra={"not": {"const": 0}})

    @field_validator("sweep_deg")
    @classmethod
    def _turns(cls, value: float) -> float:
        if value == 0.0:
            raise ValueError("must be non-zero")
        return value

    def form(self) -> SegmentForm:
        return ArcAbout(_xy(self.center), self.sweep_deg)


class EllipticalArcSegmentRequest(RequestModel):
    """An elliptical arc in SVG's endpoint form: radii, rotation of the x radius, which of
    the four arcs (``large_arc``, ``anticlockwise``), and the end point. Radii too small for
    the chord are scaled up, as in SVG."""

    type: Literal["elliptical_arc"]
    radii: Vector = Field(description="[rx, ry], both > 0.")
    rotation_deg: float = 0.0
    large_arc: bool = False
    anticlockwise: bool = True
    to: Vector

    @field_validator("radii")
    @classmethod
    def _positive(cls, value: list[float]) -> list[float]:
        if not (value[0] > 0.0 and value[1] > 0.0):
            raise ValueError("both radii must be > 0")
        return value

    def form(self) -> SegmentForm:
        return EllipticalArcTo(
            _xy(self.radii), self.rotation_deg, self.large_arc, self.anticlockwise, _xy(self.to)
        )


PathSegmentRequest = Annotated[
    LineSegmentRequest
    | QuadraticSegmentRequest
    | CubicSegmentRequest
    | ArcSegmentRequest
    | EllipticalArcSegmentRequest,
    Field(discriminator="type"),
]


class SubpathRequest(RequestModel):
    """Segments end to end from ``start``; ``closed`` adds a closing line where needed."""

    start: Vector
    segments: list[PathSegmentRequest] = Field(min_length=1, max_length=MAX_SEGMENTS_PER_SUBPATH)
    closed: bool = False


class PathSegmentsRequest(RequestModel):
    """The explicit JSON form of a path."""

    subpaths: list[SubpathRequest] = Field(min_length=1, max_length=MAX_SUBPATHS)


#: Tags of the path union and of the segment union; validation paths carry them and the API
#: removes them (a client wrote neither).
PATH_TAGS = ("path-data", "path-segments", "line", "quadratic", "cubic", "arc", "elliptical_arc")


def _path_tag(value: Any) -> str:
    return PATH_TAGS[0] if isinstance(value, str) else PATH_TAGS[1]


PathData = Annotated[str, StringConstraints(max_length=MAX_PATH_DATA)]
PathField = Annotated[
    Annotated[PathData, Tag(PATH_TAGS[0])] | Annotated[PathSegmentsRequest, Tag(PATH_TAGS[1])],
    Discriminator(_path_tag),
]


class PathRequest(RequestModel):
    """One path to approximate by arcs and lines within ``tolerance``: SVG path data
    (all commands, relative forms, S/T reflection, arc-flag shorthand) or the JSON form."""

    model_config = ConfigDict(json_schema_extra={"examples": [PATH_EXAMPLE]})

    path: PathField = Field(
        description="SVG path data (the `d` attribute; at most 2,000,000 characters, and the "
        "server's body limit applies), or subpaths of typed segments."
    )
    tolerance: float = Field(gt=0, description="Largest distance allowed from the path.")
    strategy: StrategyName = Field(
        default="subdivide",
        description="'subdivide': Walton & Meek's subdivision on every piece; "
        "'fewest-arcs': the fewest segments within the tolerance.",
    )
    gcode: GcodeRequest | None = Field(
        default=None,
        description="Also return one G-code program for the whole path (needed for the "
        "`gcode` output); its `units` are those of a `dxf` or `svg` output too (mm without it).",
    )
    output: OutputFormat | None = Field(default=None, description=OUTPUT_DESCRIPTION)
    offset: OffsetRequest | None = Field(default=None, description=OFFSET_DESCRIPTION)
    machining: MachiningRequest | None = Field(default=None, description=MACHINING_DESCRIPTION)

    @model_validator(mode="after")
    def _one_tool(self) -> PathRequest:
        if self.offset is not None and self.machining is not None:
            raise ValueError(BOTH_MESSAGE)
        return self

    def spec(self, max_segments: int) -> PathSpec:
        """The worker's value for this path (built and checked there)."""
        if isinstance(self.path, str):
            return PathFromData(self.path, max_segments)
        return PathFromSegments(
            tuple(
                SubpathForm(_xy(sub.start), tuple(s.form() for s in sub.segments), sub.closed)
                for sub in self.path.subpaths
            ),
            max_segments,
        )


class PathBatchRequest(RequestModel):
    """Many paths at once; each is validated on its own, so one bad path spoils nothing else."""

    model_config = ConfigDict(json_schema_extra={"examples": [{"jobs": [PATH_EXAMPLE]}]})

    jobs: list[Annotated[Any, ValidatedByRoute(PathRequest)]] = batch_jobs("/v1/paths/approximate")


# -- responses ---------------------------------------------------------------------------


class PathArcSegmentResponse(ArcSegmentResponse):
    """An output arc and its source: ``source_segment`` indexes the subpath's input
    segments, and ``u_start``, ``u_end`` and ``u_at_max_deviation`` are that segment's own
    parameter ``t`` (the fraction of the sweep, for arcs)."""

    source_segment: int


class PathLineSegmentResponse(LineSegmentResponse):
    """An output line and its source (as for arcs)."""

    source_segment: int


PathSegmentResponse = Annotated[
    PathArcSegmentResponse | PathLineSegmentResponse, Field(discriminator="type")
]


class PathStatsResponse(ResponseModel):
    """Summary of an approximation; radii are null when it has no arcs."""

    arc_count: int
    line_count: int
    segment_count: int
    max_deviation: float
    deviation_ratio: float = Field(description="max_deviation / tolerance.")
    max_deviation_segment: int = Field(description="Input segment where it is reached.")
    t_at_max_deviation: float
    mean_segment_deviation: float
    curve_length: float
    spline_length: float
    min_radius: float | None
    max_radius: float | None
    tolerance: float
    strategy: StrategyName


class WholePathStatsResponse(PathStatsResponse):
    subpath_count: int
    max_deviation_subpath: int


class SubpathResponse(ResponseModel):
    closed: bool
    segments: list[PathSegmentResponse]
    stats: PathStatsResponse


class PathResponse(ResponseModel):
    """One arc spline per subpath, statistics of each and of the whole path, and one G-code
    program for the whole path if asked for; with ``offset`` or ``machining`` the subpaths are
    the tool-centre paths, and the block of the same name says what was done."""

    subpaths: list[SubpathResponse]
    stats: WholePathStatsResponse
    gcode: str | None
    offset: OffsetResponse | None = None
    machining: MachiningResponse | None = None


class PathBatchOkResponse(ResponseModel):
    status: Literal["ok"]
    result: PathResponse


class PathBatchResponse(ResponseModel):
    """One entry per job, in the order of the jobs."""

    results: list[
        Annotated[PathBatchOkResponse | BatchErrorResponse, Field(discriminator="status")]
    ]
