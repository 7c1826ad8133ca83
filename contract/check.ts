// Type-checked by scripts/contract.sh (`tsc --noEmit --strict`) against the TypeScript types
// that openapi-typescript generates from openapi/openapi.json into a temporary directory,
// next to this file as `openapi.d.ts`. Nothing here runs: it fails to compile when the
// contract stops saying what a client relies on.
//
// - Every request schema gets a value with ONLY its required fields (`RequiredOnly` refuses
//   any optional field too), so a defaulted field marked required fails here.
// - Every response schema has a reader that uses its fields without guards, so a field a
//   client reads that became optional (or changed type) fails here.
// - Every operation sends its request body and reads its responses by media type.
// Adding a schema or an operation to the contract fails here until this file covers it.

import type { components, operations } from "./openapi";

type Schemas = components["schemas"];

/** The keys of `T` that are required (not `?`). */
type RequiredKeys<T> = { [K in keyof T]-?: {} extends Pick<T, K> ? never : K }[keyof T];
/** `T` with its required fields alone: an object literal of this type may hold no other. */
type RequiredOnly<T> = Pick<T, RequiredKeys<T>>;

type RequestName = Extract<keyof Schemas, `${string}Request` | `Spiral${string}`>;
type ResponseName = Extract<keyof Schemas, `${string}Response`>;
/** Every schema is a request or a response schema (else this names the ones that are not). */
type Unclassified = Exclude<keyof Schemas, RequestName | ResponseName>;
const everySchemaClassified: [Unclassified] extends [never] ? true : Unclassified = true;

// -- requests: required fields only ------------------------------------------------------

const spiralParameters: RequiredOnly<Schemas["SpiralParameters"]> = {
  start: [1.5, 3.0],
  start_tangent: [1.0, 0.0],
  turn_angle_deg: 51.34,
  end_curvature: 0.41574,
};
const spiralControlPoints: RequiredOnly<Schemas["SpiralControlPoints"]> = {
  control_points: [
    [0, 0],
    [1, 0],
    [2, 0.5],
    [3, 1.5],
  ],
};
const gcodeRequest: RequiredOnly<Schemas["GcodeRequest"]> = { feed_rate: 1000 };
const line: RequiredOnly<Schemas["LineSegmentRequest"]> = { type: "line", to: [10, 0] };
const quadratic: RequiredOnly<Schemas["QuadraticSegmentRequest"]> = {
  type: "quadratic",
  control: [15, 0],
  to: [15, 5],
};
const cubic: RequiredOnly<Schemas["CubicSegmentRequest"]> = {
  type: "cubic",
  control1: [15, 8],
  control2: [12, 10],
  to: [10, 10],
};
const arc: RequiredOnly<Schemas["ArcSegmentRequest"]> = {
  type: "arc",
  center: [5, 10],
  sweep_deg: 90,
};
const ellipticalArc: RequiredOnly<Schemas["EllipticalArcSegmentRequest"]> = {
  type: "elliptical_arc",
  radii: [5, 3],
  to: [0, 0],
};
const subpath: RequiredOnly<Schemas["SubpathRequest"]> = {
  start: [0, 0],
  segments: [line, quadratic, cubic, arc, ellipticalArc],
};
const pathSegments: RequiredOnly<Schemas["PathSegmentsRequest"]> = { subpaths: [subpath] };
const approximateRequest: RequiredOnly<Schemas["ApproximateRequest"]> = {
  spiral: spiralParameters,
  tolerance: 0.001,
};
const pathRequest: RequiredOnly<Schemas["PathRequest"]> = {
  path: "M 0 0 C 10 0 10 10 20 10",
  tolerance: 0.01,
};
const drawingRequest: RequiredOnly<Schemas["DrawingRequest"]> = {
  document: '<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 L 10 0"/></svg>',
  format: "svg",
  tolerance: 0.01,
};

const requests: { [K in RequestName]: RequiredOnly<Schemas[K]> } = {
  SpiralParameters: spiralParameters,
  SpiralControlPoints: spiralControlPoints,
  GcodeRequest: gcodeRequest,
  DxfRequest: {},
  LineSegmentRequest: line,
  QuadraticSegmentRequest: quadratic,
  CubicSegmentRequest: cubic,
  ArcSegmentRequest: arc,
  EllipticalArcSegmentRequest: ellipticalArc,
  SubpathRequest: subpath,
  PathSegmentsRequest: pathSegments,
  ApproximateRequest: approximateRequest,
  BatchRequest: { jobs: [approximateRequest, { spiral: spiralControlPoints, tolerance: 0.01 }] },
  PathRequest: pathRequest,
  PathBatchRequest: { jobs: [pathRequest, { path: pathSegments, tolerance: 0.01 }] },
  DrawingRequest: drawingRequest,
  OffsetRequest: { distance: 3, side: "outside" },
  TabsRequest: { count: 4, width: 5, height: 1.5 },
  MachiningRequest: { tool_diameter: 6 },
};

// The optional fields are still accepted where a client sets them.
const withOptions: Schemas["ApproximateRequest"] = {
  ...requests.ApproximateRequest,
  strategy: "fewest-arcs",
  gcode: { ...gcodeRequest, units: "mm", arc_format: "ij" },
};
const drawingWithOptions: Schemas["DrawingRequest"] = {
  ...requests.DrawingRequest,
  output: "gcode",
  gcode: requests.GcodeRequest,
  dxf: requests.DxfRequest,
  layers: null,
  units: "inch",
};
const offsetDrawing: Schemas["DrawingRequest"] = {
  ...requests.DrawingRequest,
  offset: { ...requests.OffsetRequest, join: "mitre", mitre_limit: 2 },
};
const machinedPath: Schemas["PathRequest"] = {
  ...requests.PathRequest,
  machining: {
    ...requests.MachiningRequest,
    cut: "auto",
    direction: "climb",
    lead_radius: null,
    entry: "ramp",
    tabs: requests.TabsRequest,
    compensation: "controller",
    tool_number: 1,
    join: "round",
  },
};

// -- responses: fields read without guards -----------------------------------------------

type Segment = Schemas["ArcSegmentResponse"] | Schemas["LineSegmentResponse"];
type PathSegment = Schemas["PathArcSegmentResponse"] | Schemas["PathLineSegmentResponse"];

function segmentLength(s: Segment | PathSegment): number {
  // The discriminator `type` narrows: only arcs have a radius and a sweep.
  const arcLength = s.type === "arc" ? s.radius * Math.abs(s.sweep_rad) : Math.hypot(
    s.end[0] - s.start[0], s.end[1] - s.start[1]);
  return Math.max(s.length, arcLength) * (s.u_end - s.u_start >= 0 ? 1 : -1);
}

function source(s: PathSegment): number {
  return s.source_segment;
}

const readers: { [K in ResponseName]: (r: Schemas[K]) => unknown } = {
  HealthResponse: (r) => r.status === "ok",
  ReadyResponse: (r) => r.status === "ready" && r.workers + r.in_flight <= r.queue_capacity,
  ProblemErrorResponse: (r) => [r.loc.join("."), r.msg, r.type, r.element ?? null],
  ProblemResponse: (r) =>
    `${r.type} ${r.title} ${r.status} ${r.detail} ${r.request_id ?? ""} ${r.limit ?? ""}` +
    (r.errors ?? []).map((e) => `${e.loc.join(".")}: ${e.msg}`).join("\n"),
  ArcSegmentResponse: (r) => [r.center[0], r.radius, r.direction === "ccw", r.start_angle_rad],
  LineSegmentResponse: (r) => segmentLength(r) + r.max_deviation + r.u_at_max_deviation,
  StatsResponse: (r) =>
    r.arc_count + r.line_count + r.segment_count + r.max_deviation / r.tolerance +
    r.deviation_ratio + r.mean_segment_deviation + r.spiral_length + r.spline_length +
    r.u_at_max_deviation + (r.min_radius ?? 0) + (r.max_radius ?? 0) + r.strategy.length,
  ApproximateResponse: (r) =>
    r.stats.arc_count + r.segments.map(segmentLength).length + (r.gcode?.length ?? 0),
  BatchOkResponse: (r) => r.status === "ok" && r.result.stats.arc_count,
  BatchErrorResponse: (r) => r.status === "error" && r.error.status,
  BatchResponse: (r) =>
    // The discriminator `status` narrows each entry.
    r.results.map((e) => (e.status === "ok" ? e.result.stats.arc_count : e.error.detail)),
  PathArcSegmentResponse: (r) => source(r) + r.radius + r.sweep_rad + r.center[1],
  PathLineSegmentResponse: (r) => source(r) + segmentLength(r),
  PathStatsResponse: (r) =>
    r.arc_count + r.line_count + r.curve_length + r.max_deviation_segment +
    r.t_at_max_deviation + r.deviation_ratio + r.mean_segment_deviation + r.spline_length +
    r.segment_count + r.max_deviation + r.tolerance + (r.min_radius ?? r.max_radius ?? 0),
  WholePathStatsResponse: (r) =>
    r.subpath_count + r.max_deviation_subpath + r.arc_count + r.curve_length + r.strategy.length,
  SubpathResponse: (r) => r.closed && r.segments.map(segmentLength).length + r.stats.arc_count,
  PathResponse: (r) =>
    r.stats.subpath_count + r.subpaths.map((s) => s.stats.segment_count).length +
    (r.gcode ?? "").length,
  PathBatchOkResponse: (r) => r.status === "ok" && r.result.stats.segment_count,
  PathBatchResponse: (r) =>
    r.results.map((e) => (e.status === "ok" ? e.result.subpaths.length : e.error.title)),
  ToolpathResponse: (r) => r.sources.join(",") + r.closed + r.segments.length + r.stats.arc_count,
  DrawingStatsResponse: (r) => r.toolpath_count + r.max_deviation_toolpath + r.arc_count,
  DrawingWarningResponse: (r) => `${r.element}: ${r.reason} (${r.occurrences})`,
  DocumentSummaryResponse: (r) =>
    r.elements_in === r.elements_read + r.elements_skipped && r.units + r.warnings.length,
  BudgetResponse: (r) => r.fit - (r.tolerance - r.curve_approximation - r.snap_move - r.join_gap),
  JoinResponse: (r) => r.joins + r.tolerance,
  RapidsResponse: (r) => r.after <= r.before,
  DrawingResponse: (r) =>
    r.toolpaths.map((t) => t.sources.length).length + r.stats.toolpath_count +
    r.document.elements_in + r.budget.fit + r.join.joins + r.rapids.after +
    (r.gcode ?? "").length + (r.units === "inch" ? 25.4 : 1) +
    (r.offset?.paths_out ?? 0) + (r.machining?.rapid_length ?? 0),
  OffsetNoteResponse: (r) => `${r.toolpath} ${r.kind}: ${r.message}`,
  OffsetResponse: (r) =>
    r.distance + r.side.length + r.contours_in + r.paths_out + r.origin.length +
    r.source_max_deviation + r.notes.length,
  MachinedContourResponse: (r) => `${r.toolpath} ${r.cut} ${r.direction} ${r.depth}`,
  MachiningWarningResponse: (r) => `${r.toolpath}: ${r.message}`,
  MachiningResponse: (r) =>
    r.tool_diameter + r.contours.length + r.warnings.length + r.rapid_length +
    r.source_max_deviation,
};

// -- operations: request bodies and responses by media type --------------------------------

type Responses<Op extends keyof operations> = operations[Op]["responses"];
type Content<R> = R extends { content: infer C } ? C : never;
/** The 200 response's content, by media type. */
type Ok<Op extends keyof operations> = Content<Responses<Op>[200 & keyof Responses<Op>]>;
/** The content of every other response the operation declares. */
type Failure<Op extends keyof operations> = Content<
  Responses<Op>[Exclude<keyof Responses<Op>, 200>]
>;
/** The JSON request body. */
type Json<Op extends keyof operations> = operations[Op] extends {
  requestBody: { content: { "application/json": infer B } };
}
  ? B
  : never;

/** Every failure is a problem (RFC 9457) whose `errors[].loc` names the field. */
function problem(failure: { "application/problem+json": Schemas["ProblemResponse"] }): string[] {
  const r = failure["application/problem+json"];
  readers.ProblemResponse(r);
  return (r.errors ?? []).map((e) => e.loc.join("."));
}

function svg(text: string): boolean {
  return text.startsWith("<svg") || text.startsWith("<?xml");
}

/** The documents an approximation answers with instead of JSON (`output`, or Accept). */
function documents(ok: {
  "text/x-gcode": string;
  "image/svg+xml": string;
  "image/vnd.dxf": string;
}): unknown[] {
  return [ok["text/x-gcode"].split("\n"), svg(ok["image/svg+xml"]), ok["image/vnd.dxf"].length];
}

/** The query string of an operation. */
type Query<Op extends keyof operations> = NonNullable<operations[Op]["parameters"]["query"]>;

const checks: { [Op in keyof operations]: (ok: Ok<Op>, failure: Failure<Op>) => unknown } = {
  healthz: (ok) => readers.HealthResponse(ok["application/json"]),
  metrics: (ok) => ok["text/plain"].split("\n").filter((l) => !l.startsWith("#")),
  readyz: (ok, failure) => [readers.ReadyResponse(ok["application/json"]), problem(failure)],
  approximate: (ok, failure) => {
    const body: Json<"approximate"> = requests.ApproximateRequest;
    const full: Json<"approximate"> = withOptions;
    const query: Query<"approximate"> = { output: "gcode" };
    return [body, full, query, readers.ApproximateResponse(ok["application/json"]),
      documents(ok), problem(failure)];
  },
  approximate_batch: (ok, failure) => {
    const body: Json<"approximate_batch"> = requests.BatchRequest;
    return [body, readers.BatchResponse(ok["application/json"]), problem(failure)];
  },
  preview: (ok, failure) => {
    const body: Json<"preview"> = requests.ApproximateRequest;
    return [body, svg(ok["image/svg+xml"]), problem(failure)];
  },
  approximate_path: (ok, failure) => {
    const body: Json<"approximate_path"> = requests.PathRequest;
    const query: Query<"approximate_path"> = { output: "svg" };
    return [body, query, readers.PathResponse(ok["application/json"]), documents(ok),
      problem(failure)];
  },
  approximate_paths_batch: (ok, failure) => {
    const body: Json<"approximate_paths_batch"> = requests.PathBatchRequest;
    return [body, readers.PathBatchResponse(ok["application/json"]), problem(failure)];
  },
  preview_path: (ok, failure) => {
    const body: Json<"preview_path"> = requests.PathRequest;
    return [body, svg(ok["image/svg+xml"]), problem(failure)];
  },
  approximate_drawing: (ok, failure) => {
    const body: Json<"approximate_drawing"> = requests.DrawingRequest;
    const full: Json<"approximate_drawing"> = drawingWithOptions;
    // A raw document: the options in the query string.
    const query: Query<"approximate_drawing"> = { format: "svg", tolerance: 0.01, decimals: 4, comments: true, layers: ["0"], output: "dxf" };
    return [body, full, query, readers.DrawingResponse(ok["application/json"]), documents(ok),
      problem(failure)];
  },
  preview_drawing: (ok, failure) => {
    const body: Json<"preview_drawing"> = requests.DrawingRequest;
    return [body, svg(ok["image/svg+xml"]), problem(failure)];
  },
};

export { checks, everySchemaClassified };
