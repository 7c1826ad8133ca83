"""Request and response models: the public contract, as the OpenAPI document shows it.

Requests are validated strictly and cheaply here: unknown fields, non-finite numbers, wrong
lengths, out-of-range angles, a zero curvature or tangent, a non-positive tolerance and an
unknown strategy are refused before any work is queued; what only the geometry can decide
(an unreachable tolerance, a spiral too large for double precision) the core reports.

Responses are never built from these models at run time (the worker serialises them
directly, see ``arcspline.worker.jobs.encode``); the models document them, and the tests check
real responses against them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated, Any, Literal, get_args

from pydantic import (
    BaseModel,
    ConfigDict,
    Discriminator,
    Field,
    GetCoreSchemaHandler,
    GetJsonSchemaHandler,
    Tag,
    field_validator,
)
from pydantic.json_schema import JsonSchemaValue
from pydantic_core import CoreSchema, core_schema

from arcspline.geometry import SpiralFromControlPoints, SpiralFromParameters, StrategyName
from arcspline.outputs.gcode import MAX_DECIMALS, MIN_DECIMALS
from arcspline.settings import Settings

#: The paper's example (Walton & Meek 1996, Table 1): 12 arcs at this tolerance.
PAPER_EXAMPLE: dict[str, Any] = {
    "spiral": {
        "start": [1.5, 3.0],
        "start_tangent": [1.0, 0.0],
        "turn_angle_deg": 51.34,
        "end_curvature": 0.41574,
    },
    "tolerance": 0.001,
    "strategy": "subdivide",
}


#: What an approximation is answered with: JSON, or one document alone.
OutputFormat = Literal["json", "gcode", "dxf", "svg"]
OUTPUT_FORMATS: tuple[str, ...] = get_args(OutputFormat)
#: Each output's media type (the server answers with it, the client asks for it).
OUTPUT_MEDIA_TYPES: dict[OutputFormat, str] = {
    "json": "application/json",
    "gcode": "text/x-gcode",
    "dxf": "image/vnd.dxf",
    "svg": "image/svg+xml",
}
#: A streamed batch's answer: one JSON line per job, in order (``Accept`` asks for it).
NDJSON_MEDIA_TYPE = "application/x-ndjson"
#: The default of ``ARCSPLINE_BATCH_MAX_JOBS``: what the schema shows as a batch's
#: ``maxItems`` (the server's configured limit applies, with a 413).
BATCH_MAX_JOBS = Settings.model_fields["batch_max_jobs"].default
#: The default of ``ARCSPLINE_MAX_BODY_BYTES``: the ``maxLength`` the schema shows for a raw
#: document (the server's configured limit applies, with a 413).
MAX_BODY_BYTES = Settings.model_fields["max_body_bytes"].default
OUTPUT_DESCRIPTION = (
    "`json` (default), or one document alone: `gcode` (needs `gcode`), `dxf`, `svg`. "
    "Also chosen by the `output` query parameter, else the Accept header."
)


class RequestModel(BaseModel):
    """Strict JSON input: no unknown fields, no NaN or Infinity, no strings for numbers."""

    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True)


class ResponseModel(BaseModel):
    """Documentation of a response body (exactly these fields)."""

    model_config = ConfigDict(extra="forbid")


Vector = Annotated[list[float], Field(min_length=2, max_length=2, description="[x, y]")]


class SpiralParameters(RequestModel):
    """The paper's five parameters (§1)."""

    start: Vector = Field(description="Start point B0.")
    # Non-zero is checked below; JSON Schema's "not": {"const": [0, 0]} would say it, but
    # test generators (hypothesis-jsonschema) cannot work with it.
    start_tangent: Vector = Field(
        description="Direction of the start tangent T0 (any non-zero length)."
    )
    turn_angle_deg: float = Field(
        gt=0, lt=90, description="Turn angle θ between the end tangents, degrees."
    )
    end_curvature: float = Field(
        description="Curvature c at the end; its sign is the turning direction (+ = left).",
        json_schema_extra={"not": {"const": 0}},
    )

    @field_validator("start_tangent")
    @classmethod
    def _non_zero(cls, value: list[float]) -> list[float]:
        if value[0] == 0.0 and value[1] == 0.0:
            raise ValueError("must be a non-zero vector")
        return value

    @field_validator("end_curvature")
    @classmethod
    def _curved(cls, value: float) -> float:
        if value == 0.0:
            raise ValueError("must be non-zero (its sign is the turning direction)")
        return value

    def spec(self) -> SpiralFromParameters:
        """The core's value for this spiral (built and checked in a worker)."""
        return SpiralFromParameters(
            start=(self.start[0], self.start[1]),
            start_tangent=(self.start_tangent[0], self.start_tangent[1]),
            turn_angle_deg=self.turn_angle_deg,
            end_curvature=self.end_curvature,
        )


class SpiralControlPoints(RequestModel):
    """Four Bézier control points of the paper's form.

    That is ``B1 − B0 = B2 − B1`` and ``|B3 − B2| = 1.2·cos θ·|B1 − B0|``, θ the angle between
    ``B1 − B0`` and ``B3 − B2`` (0 < θ < 90°).
    """

    control_points: list[Vector] = Field(min_length=4, max_length=4)

    def spec(self) -> SpiralFromControlPoints:
        """The core's value for this spiral (built and checked in a worker)."""
        return SpiralFromControlPoints(tuple((p[0], p[1]) for p in self.control_points))


#: Tags of the spiral union; they appear in validation paths and the API removes them.
SPIRAL_TAGS = ("spiral-parameters", "spiral-control-points")


def _spiral_tag(value: Any) -> str:
    given_points = isinstance(value, dict) and "control_points" in value
    if given_points or isinstance(value, SpiralControlPoints):
        return SPIRAL_TAGS[1]
    return SPIRAL_TAGS[0]


SpiralRequest = Annotated[
    Annotated[SpiralParameters, Tag(SPIRAL_TAGS[0])]
    | Annotated[SpiralControlPoints, Tag(SPIRAL_TAGS[1])],
    Discriminator(_spiral_tag),
]


class GcodeRequest(RequestModel):
    """Ask for a G-code program (RS-274) of the arc spline."""

    feed_rate: float = Field(gt=0, description="Cutting feed rate F, units per minute.")
    units: Literal["mm", "inch"] = Field(
        default="mm",
        description="G21 (mm) or G20 (inch); also the unit of a `dxf` or `svg` output.",
    )
    decimals: int | None = Field(
        default=None,
        ge=MIN_DECIMALS,
        le=MAX_DECIMALS,
        description="Decimal places of coordinates (default 4 for mm, 5 for inch).",
    )
    arc_format: Literal["ij", "r"] = Field(
        default="ij", description="Arc centres as I/J offsets (G91.1) or as a radius R."
    )
    line_numbers: bool = Field(default=False, description="Number the blocks (N10, N20, ...).")
    comments: bool = Field(
        default=False, description="A header with tolerance, strategy and counts."
    )
    safe_z: float | None = Field(default=None, description="Retract height for a 2.5-D cut.")
    cut_z: float | None = Field(default=None, description="Cutting depth for a 2.5-D cut.")
    plunge_feed_rate: float | None = Field(
        default=None, gt=0, description="Feed rate of the plunge."
    )
    step_down: float | None = Field(
        default=None,
        gt=0,
        description="Cut in passes at most this deep, from the stock top at Z0 down to cut_z "
        "(needs safe_z and cut_z < 0).",
    )
    min_arc_length: float | None = Field(
        default=None, gt=0, description="Arcs shorter than this become G1 where tolerance allows."
    )
    max_radius: float | None = Field(
        default=None, gt=0, description="Arcs flatter than this become G1 where tolerance allows."
    )


class ApproximateRequest(RequestModel):
    """One spiral to approximate by arcs within ``tolerance``."""

    model_config = ConfigDict(json_schema_extra={"examples": [PAPER_EXAMPLE]})

    spiral: SpiralRequest
    tolerance: float = Field(gt=0, description="Largest distance allowed from the spiral.")
    strategy: StrategyName = Field(
        default="subdivide",
        description="'subdivide': the paper's recursive subdivision; "
        "'fewest-arcs': the fewest segments within the tolerance.",
    )
    gcode: GcodeRequest | None = Field(
        default=None,
        description="Also return a G-code program (needed for the `gcode` output); its "
        "`units` are those of a `dxf` or `svg` output too (mm without it).",
    )
    output: OutputFormat | None = Field(default=None, description=OUTPUT_DESCRIPTION)


@dataclass(frozen=True)
class ValidatedByRoute:
    """A batch's job: taken as any JSON value here and validated by the route, one job at a
    time, so that a bad job becomes its own error entry rather than failing the batch. The
    schema still says what each job must be: a ``$ref`` to ``model`` (not the model inlined,
    which is what ``SkipValidation`` gives)."""

    model: type[BaseModel]

    def __get_pydantic_core_schema__(
        self, _source: Any, _handler: GetCoreSchemaHandler
    ) -> CoreSchema:
        return core_schema.any_schema()

    def __get_pydantic_json_schema__(
        self, _schema: CoreSchema, handler: GetJsonSchemaHandler
    ) -> JsonSchemaValue:
        return handler(self.model.__pydantic_core_schema__)


def batch_jobs(endpoint: str) -> Any:
    """The ``jobs`` field of a batch of bodies of ``endpoint``."""
    return Field(
        min_length=1,
        description=f"Bodies of {endpoint}, answered as JSON (`output` `json` or none). At "
        f"most {BATCH_MAX_JOBS} by default: the server's ARCSPLINE_BATCH_MAX_JOBS applies (413).",
        json_schema_extra={"maxItems": BATCH_MAX_JOBS},
    )


class BatchRequest(RequestModel):
    """Many jobs at once; each is validated on its own, so one bad job spoils nothing else."""

    model_config = ConfigDict(json_schema_extra={"examples": [{"jobs": [PAPER_EXAMPLE]}]})

    jobs: list[Annotated[Any, ValidatedByRoute(ApproximateRequest)]] = batch_jobs("/v1/approximate")


# -- responses ---------------------------------------------------------------------------


class ArcSegmentResponse(ResponseModel):
    """A circular arc; ``sweep_rad`` is signed (anticlockwise positive)."""

    type: Literal["arc"]
    start: Vector
    end: Vector
    center: Vector
    radius: float
    direction: Literal["ccw", "cw"]
    start_angle_rad: float
    sweep_rad: float
    length: float
    u_start: float
    u_end: float
    max_deviation: float
    u_at_max_deviation: float


class LineSegmentResponse(ResponseModel):
    """A straight segment (where an arc would be numerically flat)."""

    type: Literal["line"]
    start: Vector
    end: Vector
    length: float
    u_start: float
    u_end: float
    max_deviation: float
    u_at_max_deviation: float


SegmentResponse = Annotated[ArcSegmentResponse | LineSegmentResponse, Field(discriminator="type")]


class StatsResponse(ResponseModel):
    """Summary of the arc spline; radii are null when it has no arcs."""

    arc_count: int
    line_count: int
    segment_count: int
    max_deviation: float
    u_at_max_deviation: float
    deviation_ratio: float = Field(description="max_deviation / tolerance.")
    mean_segment_deviation: float
    spiral_length: float
    spline_length: float
    min_radius: float | None
    max_radius: float | None
    tolerance: float
    strategy: StrategyName


class ApproximateResponse(ResponseModel):
    """The arc spline in path order, its statistics, and the G-code program if asked for."""

    segments: list[SegmentResponse]
    stats: StatsResponse
    gcode: str | None


class ProblemErrorResponse(ResponseModel):
    """One reason a request was refused: where (``loc``) and why."""

    loc: list[str | int] = Field(description="Path of the field, e.g. ['body', 'tolerance'].")
    msg: str
    type: str
    element: str | None = Field(
        default=None,
        description="For a drawing: the element of the document (`path#p`, `rect (line 12)`, "
        "`INSERT #2F`) or `document`.",
    )


class ProblemResponse(ResponseModel):
    """RFC 9457 problem details (``application/problem+json``)."""

    type: str = Field(description="URI of the kind of problem.")
    title: str
    status: int
    detail: str
    request_id: str | None = None
    errors: list[ProblemErrorResponse] | None = None
    errors_omitted: int | None = Field(
        default=None,
        description="How many errors were left out: `errors` lists the first 50 (each name "
        "and message cut to 200 characters).",
    )
    limit: float | None = Field(default=None, description="The limit that was crossed, if any.")


class BatchOkResponse(ResponseModel):
    status: Literal["ok"]
    result: ApproximateResponse


class BatchErrorResponse(ResponseModel):
    status: Literal["error"]
    error: ProblemResponse


class BatchResponse(ResponseModel):
    """One entry per job, in the order of the jobs."""

    results: list[Annotated[BatchOkResponse | BatchErrorResponse, Field(discriminator="status")]]


class HealthResponse(ResponseModel):
    status: Literal["ok"]


class ReadyResponse(ResponseModel):
    status: Literal["ready"]
    workers: int
    in_flight: int
    queue_capacity: int
