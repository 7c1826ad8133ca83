"""An arc spline as a G-code program that real controllers accept (RS-274/NGC, XY plane).

The program states its modes (``G17 G20|G21 G90 G91.1 G94 F…``), moves rapidly to the
spiral's start (retracting to ``safe_z`` and plunging to ``cut_z`` first, for a 2.5-D cut),
cuts one block per segment of the arc spline and ends with ``M2``.

Rounding, which is where controllers reject programs, follows fixed rules:

* Every coordinate is a whole number of units in the last place, ``q = 10^-decimals``. The
  joints between segments are rounded first, once each, so consecutive blocks meet exactly
  and the path starts and ends at the spiral's rounded end points.
* An arc's centre is chosen for the *rounded* end points: on their perpendicular bisector
  (where start and end radii agree), the point whose circle fits the true arc best
  (minimax over a few points of it, starting from the bisector point nearest the true
  centre); then, of the lattice points within ``q`` of it, one whose start and end radii
  agree within ``q·min(1, √2·sin(|sweep|/2))`` and whose circle fits best. ``I``/``J`` is
  that point minus the rounded start. Every block repeats its G word and carries both ``X``
  and ``Y`` and both ``I`` and ``J`` (or ``R``).
* An arc a controller could take for a full circle is cut as ``G1``: its rounded ends
  coincide, its sweep is below :data:`MIN_SWEEP_RAD`, or its radius is below
  :data:`MIN_RADIUS_ULPS` units in the last place. An arc the precision cannot tell from its
  chord (sagitta below ``q/2``) is cut as ``G1`` too, unless that line would leave the
  bound below while the arc keeps it. ``min_arc_length`` and ``max_radius`` turn further
  arcs into lines, but only where the chord stays within the tolerance of the spiral
  (:func:`chord_deviation`, exact).
* ``R`` form uses ``R`` only away from half circles (:data:`HALF_CIRCLE_MARGIN_DEG`), negative
  beyond 180°; other arcs keep ``I``/``J`` (``G91.1`` is in every preamble for that reason).

Every block is then measured against its piece of the spiral, exactly (the extrema of the
distance are roots of a polynomial in the spiral parameter), and takes the first of its
candidate forms (line or arc, as above; ``R``, then ``I``/``J``, then the chord) whose
read-back path stays within ``tolerance + q`` of the spiral. When none does, or the spiral's
coordinates exceed :data:`MAX_COORDINATE`, :class:`GcodeError` says so (``decimals`` too few
for the tolerance, or ``spiral`` too large). No number that is not finite reaches the text:
every number is formatted from an integer count of units in the last place.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Literal, NamedTuple, get_args

import numpy as np
import numpy.typing as npt

from service.geometry import ArcSpline, SegmentColumns, Spiral

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]
Units = Literal["mm", "inch"]
ArcFormat = Literal["ij", "r"]
UNITS: tuple[str, ...] = get_args(Units)
ARC_FORMATS: tuple[str, ...] = get_args(ArcFormat)

#: Decimals accepted for either unit. 3 is the coarsest that still resolves the common
#: machine resolution (1 µm; 0.001" on hobby machines) and keeps the radius mismatch within
#: LinuxCNC's strictest arc check (0.001 mm); 6 is finer than any controller interpolates
#: (Fanuc IS-C: 0.0001 mm / 0.00001") and keeps every coordinate below
#: :data:`MAX_COORDINATE` within 13 significant digits, exact in double precision.
MIN_DECIMALS = 3
MAX_DECIMALS = 6
#: Decimals when the request gives none: 0.1 µm in mm, 0.25 µm in inch.
DEFAULT_DECIMALS: Mapping[str, int] = {"mm": 4, "inch": 5}
#: Largest magnitude of a coordinate or feed written (X, Y, Z, F): a kilometre in mm;
#: beyond it a number stops being a plausible machine coordinate.
MAX_COORDINATE = 1e6
#: Largest magnitude of a centre offset or radius written (I, J, R). A nearly straight arc
#: of a large spiral has a far centre; up to this bound (15 digits at 6 decimals) its
#: lattice point is still exact in double precision. Farther centres are cut as chords.
MAX_ARC_WORD = 1e9
#: ``R`` is not used for an arc whose sweep is within this of a half circle: there the
#: centre moves by ``δR / cos(sweep/2)`` for a rounding ``δR`` of the radius.
HALF_CIRCLE_MARGIN_DEG = 5.0
#: Sweeps below this are cut as lines: Grbl (single precision) reads a clockwise sweep under
#: 5e-7 rad as a full circle; this leaves a factor of 20.
MIN_SWEEP_RAD = 1e-5
#: Arcs with a radius below this many units in the last place are cut as lines: their
#: rounded centre would carry no information (LinuxCNC rejects radii below 1.27 µm).
MIN_RADIUS_ULPS = 2
#: RS-274/NGC line numbers have at most five digits.
MAX_LINE_NUMBER = 99_999


class GcodeError(ValueError):
    """The options, or this spline at these options, cannot give a correct program.

    ``field`` is the option's name (``feed_rate``, ``decimals``, ...) or ``"spiral"`` when
    the spiral itself is out of range; ``message`` says why in words.
    """

    def __init__(self, field: str, message: str) -> None:
        super().__init__(f"{field}: {message}")
        self.field = field
        self.message = message

    def __reduce__(self) -> tuple[object, ...]:
        # The default pickling passes the formatted text as the only argument; these errors
        # cross the process-pool boundary.
        return (GcodeError, (self.field, self.message))


def _is_real(value: object) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


@dataclass(frozen=True, slots=True)
class GcodeOptions:
    """How to write the program; validated on construction (raises :class:`GcodeError`).

    Lengths are in ``units`` (the spline's coordinates are taken to be in them already),
    feeds in ``units`` per minute. ``decimals`` and ``plunge_feed_rate`` default to
    :data:`DEFAULT_DECIMALS` and ``feed_rate``: see :attr:`resolved_decimals` and
    :attr:`resolved_plunge_feed_rate`.
    """

    feed_rate: float
    units: Units = "mm"
    decimals: int | None = None
    arc_format: ArcFormat = "ij"
    line_numbers: bool = False
    comments: bool = False
    safe_z: float | None = None
    cut_z: float | None = None
    plunge_feed_rate: float | None = None
    min_arc_length: float | None = None
    max_radius: float | None = None

    def __post_init__(self) -> None:
        if self.units not in UNITS:
            raise GcodeError("units", f"must be one of {', '.join(UNITS)}, got {self.units!r}")
        if self.decimals is not None and (
            not isinstance(self.decimals, int) or isinstance(self.decimals, bool)
        ):
            raise GcodeError("decimals", f"must be an integer, got {self.decimals!r}")
        if self.decimals is not None and not MIN_DECIMALS <= self.decimals <= MAX_DECIMALS:
            raise GcodeError(
                "decimals",
                f"must lie between {MIN_DECIMALS} and {MAX_DECIMALS}, got {self.decimals}",
            )
        if self.arc_format not in ARC_FORMATS:
            raise GcodeError(
                "arc_format", f"must be one of {', '.join(ARC_FORMATS)}, got {self.arc_format!r}"
            )
        for name in ("line_numbers", "comments"):
            if not isinstance(getattr(self, name), bool):
                raise GcodeError(name, f"must be true or false, got {getattr(self, name)!r}")
        self._check_feed("feed_rate", self.feed_rate)
        if self.plunge_feed_rate is not None:
            if self.safe_z is None:
                raise GcodeError("plunge_feed_rate", "applies only with safe_z and cut_z")
            self._check_feed("plunge_feed_rate", self.plunge_feed_rate)
        self._check_depths()
        for name in ("min_arc_length", "max_radius"):
            value = getattr(self, name)
            if value is not None and not (_is_real(value) and math.isfinite(value) and value > 0.0):
                raise GcodeError(name, f"must be a finite number > 0, got {value!r}")

    def _check_feed(self, name: str, value: object) -> None:
        if not (_is_real(value) and math.isfinite(value)):  # type: ignore[arg-type]
            raise GcodeError(name, f"must be a finite number, got {value!r}")
        feed = float(value)  # type: ignore[arg-type]
        smallest = 10.0**-self.resolved_decimals
        if not smallest <= feed <= MAX_COORDINATE:
            raise GcodeError(
                name,
                f"must lie between {smallest:g} (one unit in the last of "
                f"{self.resolved_decimals} decimals) and {MAX_COORDINATE:g} {self.units}/min, "
                f"got {feed:g}",
            )

    def _check_depths(self) -> None:
        if (self.safe_z is None) != (self.cut_z is None):
            missing = "cut_z" if self.cut_z is None else "safe_z"
            raise GcodeError(missing, "safe_z and cut_z go together: give both or neither")
        if self.safe_z is None or self.cut_z is None:
            return
        for name in ("safe_z", "cut_z"):
            value = getattr(self, name)
            if not (_is_real(value) and math.isfinite(value) and abs(value) < MAX_COORDINATE):
                raise GcodeError(
                    name, f"must be a finite number of magnitude below {MAX_COORDINATE:g}"
                )
        scale = 10**self.resolved_decimals
        if not round(self.safe_z * scale) > round(self.cut_z * scale):
            raise GcodeError(
                "safe_z",
                f"must lie above cut_z by at least one unit in the last place "
                f"(safe_z {self.safe_z:g}, cut_z {self.cut_z:g})",
            )

    @property
    def resolved_decimals(self) -> int:
        """``decimals``, or the default for ``units``."""
        return DEFAULT_DECIMALS[self.units] if self.decimals is None else self.decimals

    @property
    def resolved_plunge_feed_rate(self) -> float:
        """``plunge_feed_rate``, or ``feed_rate``."""
        return self.feed_rate if self.plunge_feed_rate is None else self.plunge_feed_rate


# -- exact distances from a spiral piece to a line or a circle ---------------------------


class _Monomial(NamedTuple):
    """``Q(u) − origin = c1·u + c2·u² + c3·u³`` (power basis of the Bézier, local frame)."""

    origin: FloatArray
    c1: FloatArray
    c2: FloatArray
    c3: FloatArray


def _monomial(spiral: Spiral) -> _Monomial:
    p = np.asarray(spiral.control_points, dtype=np.float64)
    b = p - p[0]
    return _Monomial(
        origin=p[0],
        c1=3.0 * b[1],
        c2=3.0 * (b[2] - 2.0 * b[1]),
        c3=b[3] - 3.0 * b[2] + 3.0 * b[1],
    )


def _candidates(roots: npt.NDArray[Any], u0: FloatArray, u1: FloatArray) -> FloatArray:
    """Real ``roots`` (rows) inside ``[u0, u1]``, plus both ends; NaN marks no candidate.

    A root is taken as real when its imaginary part is tiny; a spurious candidate is harmless
    (it is a point of the piece, so it cannot raise a maximum above the true one).
    """
    real = np.real(roots)
    ok = (np.abs(np.imag(roots)) <= 1e-7) & (real > u0[:, None]) & (real < u1[:, None])
    inner = np.where(ok, real, np.nan)
    return np.concatenate([u0[:, None], u1[:, None], inner], axis=1)


def _eval(spiral: Spiral, u: FloatArray) -> FloatArray:
    return spiral.eval(np.nan_to_num(u, nan=0.0))


def _line_deviations(
    spiral: Spiral, u0: FloatArray, u1: FloatArray, start: FloatArray, end: FloatArray
) -> FloatArray:
    """Max over ``u ∈ [u0, u1]`` of the distance from ``Q(u)`` to the line ``start→end``.

    With ``n`` the chord's unit normal, ``d(u) = n·(Q(u) − start)`` is a cubic whose
    derivative ``n·Q'(u) = n·c1 + 2(n·c2)u + 3(n·c3)u²`` is a quadratic: its real roots and
    the ends are the only candidates. Rows where ``start == end`` measure the distance to the
    point instead (via :func:`_circle_deviations` with radius 0).
    """
    mono = _monomial(spiral)
    chord = end - start
    length = np.hypot(chord[:, 0], chord[:, 1])
    point = length == 0.0
    safe = np.where(point, 1.0, length)
    normal = np.stack([-chord[:, 1], chord[:, 0]], axis=1) / safe[:, None]
    qa = 3.0 * normal @ mono.c3
    qb = 2.0 * normal @ mono.c2
    qc = normal @ mono.c1
    disc = qb * qb - 4.0 * qa * qc
    sq = np.sqrt(np.where(disc >= 0.0, disc, np.nan))
    # The stable pair of quadratic roots; a vanishing leading coefficient leaves one root.
    big = -0.5 * (qb + np.copysign(sq, qb))
    with np.errstate(divide="ignore", invalid="ignore"):
        r1 = np.where(qa != 0.0, big / qa, np.where(qb != 0.0, -qc / qb, np.nan))
        r2 = np.where(big != 0.0, qc / big, np.nan)
    u = _candidates(np.stack([r1, r2], axis=1).astype(np.complex128), u0, u1)
    q = _eval(spiral, u)
    d = np.abs(np.einsum("nkj,nj->nk", q - start[:, None, :], normal))
    dev = np.nanmax(np.where(np.isnan(u), np.nan, d), axis=1)
    if np.any(point):
        zero = np.zeros(int(point.sum()))
        dev[point] = _circle_deviations(spiral, u0[point], u1[point], start[point], zero, zero)
    return np.asarray(dev, dtype=np.float64)


def _circle_deviations(
    spiral: Spiral,
    u0: FloatArray,
    u1: FloatArray,
    centre: FloatArray,
    r_start: FloatArray,
    r_end: FloatArray,
) -> FloatArray:
    """Max over ``u ∈ [u0, u1]`` of the distance from ``Q(u)`` to a circle about ``centre``.

    A controller given an arc whose start and end radii differ cuts a spiral between the two
    radii (LinuxCNC) or one of them (Grbl); the distance is therefore taken to the farther of
    the two circles, ``max(|ρ − r_start|, |ρ − r_end|)`` with ``ρ(u) = ‖Q(u) − centre‖``. Its
    extrema lie where ``ρ`` is extreme: at the ends or at a root of the quintic
    ``g(u) = (Q(u) − centre)·Q'(u)`` (Walton & Meek's ``g_i``, here without a known root),
    whose roots are the eigenvalues of its companion matrix, for all rows at once.
    """
    mono = _monomial(spiral)
    a0 = mono.origin - centre
    c1, c2, c3 = mono.c1, mono.c2, mono.c3
    coeffs = np.stack(
        [
            a0 @ c1,
            2.0 * a0 @ c2 + c1 @ c1,
            3.0 * a0 @ c3 + np.full(len(a0), 3.0 * c1 @ c2),
            np.full(len(a0), 4.0 * c1 @ c3 + 2.0 * c2 @ c2),
            np.full(len(a0), 5.0 * c2 @ c3),
        ],
        axis=1,
    ) / (3.0 * c3 @ c3)
    companion = np.zeros((len(a0), 5, 5))
    companion[:, np.arange(1, 5), np.arange(4)] = 1.0
    companion[:, :, 4] = -coeffs
    roots = np.linalg.eigvals(companion) if len(a0) else np.zeros((0, 5), np.complex128)
    u = _candidates(roots, u0, u1)
    q = _eval(spiral, u)
    rho = np.hypot(q[..., 0] - centre[:, None, 0], q[..., 1] - centre[:, None, 1])
    far = np.maximum(np.abs(rho - r_start[:, None]), np.abs(rho - r_end[:, None]))
    return np.asarray(np.nanmax(np.where(np.isnan(u), np.nan, far), axis=1), dtype=np.float64)


def chord_deviation(
    spiral: Spiral,
    u_start: float,
    u_end: float,
    start: Sequence[float],
    end: Sequence[float],
) -> float:
    """The largest distance from the spiral piece ``u_start ≤ u ≤ u_end`` to the line
    through ``start`` and ``end`` (to the point, if they coincide).

    Exact up to rounding: the extrema of ``n·(Q(u) − start)`` are the roots of a quadratic.
    When ``start`` and ``end`` are the piece's own end points this is also the distance to the
    segment: the spiral's tangent turns by less than 90° over the piece and passes through
    the chord's direction, so every point of the piece projects inside the chord.
    """
    dev = _line_deviations(
        spiral,
        np.array([float(u_start)]),
        np.array([float(u_end)]),
        np.array([start], dtype=np.float64),
        np.array([end], dtype=np.float64),
    )
    return float(dev[0])


# -- arcs on the lattice of representable numbers -----------------------------------------


class ArcWords(NamedTuple):
    """One arc block as a controller reads it.

    ``offset`` is ``(I, J)``, the centre minus the rounded start, and ``radius`` the signed
    ``R`` word, both in units in the last place (integers); exactly one of them is set.
    ``centre``, ``r_start``, ``r_end`` and ``sweep_rad`` are what a controller computes from
    the words (world units).
    """

    ccw: bool
    offset: tuple[int, int] | None
    radius: int | None
    centre: tuple[float, float]
    r_start: float
    r_end: float
    sweep_rad: float


class _Arcs(NamedTuple):
    """Arcs to encode, one row each: rounded ends (lattice integers), true centre, radius and
    signed sweep."""

    start: IntArray
    end: IntArray
    centre: FloatArray
    radius: FloatArray
    sweep_rad: FloatArray


class _Encoded(NamedTuple):
    """Encoded arcs, one row each; ``ok`` is false where the form does not apply."""

    ok: npt.NDArray[np.bool_]
    words: IntArray  # (n, 2) I, J or (n, 1) R
    centre: FloatArray
    r_start: FloatArray
    r_end: FloatArray
    sweep_rad: FloatArray


#: Points of each arc at which fits are compared (ends included).
_FIT_POINTS = 9
_GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0


def _controller_sweeps(
    start: FloatArray, end: FloatArray, centre: FloatArray, ccw: npt.NDArray[np.bool_]
) -> FloatArray:
    """The sweep a controller cuts from ``start`` to ``end`` about ``centre``, signed, of
    magnitude in ``(0, 2π]``: an end angle not strictly past the start is a full turn."""
    a = np.arctan2(start[:, 1] - centre[:, 1], start[:, 0] - centre[:, 0])
    b = np.arctan2(end[:, 1] - centre[:, 1], end[:, 0] - centre[:, 0])
    turn = 2.0 * np.pi
    up = np.where(b > a, b - a, b - a + turn)
    down = np.where(b < a, b - a, b - a - turn)
    return np.asarray(np.where(ccw, up, down), dtype=np.float64)


def _fit_points(arcs: _Arcs, start: FloatArray) -> FloatArray:
    """Points of each true arc, ``(n, _FIT_POINTS, 2)``, from the rounded start's angle."""
    c = arcs.centre
    a0 = np.arctan2(start[:, 1] - c[:, 1], start[:, 0] - c[:, 0])
    angle = a0[:, None] + arcs.sweep_rad[:, None] * np.linspace(0.0, 1.0, _FIT_POINTS)
    ring = np.stack([np.cos(angle), np.sin(angle)], axis=-1)
    return np.asarray(c[:, None, :] + arcs.radius[:, None, None] * ring, dtype=np.float64)


def _gap(
    points: FloatArray, centre: FloatArray, r_start: FloatArray, r_end: FloatArray
) -> FloatArray:
    """Largest distance from ``points`` (``(n, k, 2)``) to the circles of radius ``r_start``
    and ``r_end`` about ``centre`` (``(n, …, 2)``, broadcast)."""
    rho = np.hypot(points[..., 0] - centre[..., 0:1], points[..., 1] - centre[..., 1:2])
    far = np.maximum(np.abs(rho - r_start[..., None]), np.abs(rho - r_end[..., None]))
    return np.asarray(far.max(axis=-1), dtype=np.float64)


def _best_fit_centres(arcs: _Arcs, decimals: int) -> FloatArray:
    """For each arc, the centre on the perpendicular bisector of the rounded ends whose circle
    is nearest the true arc (minimax over :data:`_FIT_POINTS` points, by golden section).

    The search starts from the bisector point nearest the true centre; the window is wide
    where the shape barely depends on the centre (a flat arc) and narrow near half circles.
    """
    scale = 10.0**decimals
    s, e = arcs.start / scale, arcs.end / scale
    mid = 0.5 * (s + e)
    chord = e - s
    half = 0.5 * np.hypot(chord[:, 0], chord[:, 1])
    normal = np.stack([-chord[:, 1], chord[:, 0]], axis=1) / (2.0 * half[:, None])
    t0 = np.einsum("nj,nj->n", arcs.centre - mid, normal)
    bulge = np.maximum(1.0 - np.cos(0.5 * np.abs(arcs.sweep_rad)), 1e-300)
    width = np.clip(4.0 / scale / bulge, 1.0 / scale, 0.5 * arcs.radius)
    points = _fit_points(arcs, s)

    def misfit(t: FloatArray) -> FloatArray:
        centre = mid + t[:, None] * normal
        r = np.hypot(t, half)
        return _gap(points, centre, r, r)

    lo, hi = t0 - width, t0 + width
    x1, x2 = hi - _GOLDEN * (hi - lo), lo + _GOLDEN * (hi - lo)
    f1, f2 = misfit(x1), misfit(x2)
    for _ in range(48):
        left = f1 <= f2
        lo, hi = np.where(left, lo, x1), np.where(left, x2, hi)
        new = np.where(left, hi - _GOLDEN * (hi - lo), lo + _GOLDEN * (hi - lo))
        fn = misfit(new)
        x1, x2 = np.where(left, new, x2), np.where(left, x1, new)
        f1, f2 = np.where(left, fn, f2), np.where(left, f1, fn)
    best = np.where(f1 <= f2, x1, x2)
    # Keep the nearest point unless the fit is clearly better: a flat arc fits many circles
    # about equally, and the one nearest the true centre keeps the true radius.
    better = misfit(best) < misfit(t0) - 0.05 / scale
    best = np.where(better, best, t0)
    return np.asarray(mid + best[:, None] * normal, dtype=np.float64)


def _encode_ij(arcs: _Arcs, ideal: FloatArray, decimals: int) -> _Encoded:
    """``I``/``J``: of the lattice points within one unit of the ideal centre, those whose
    start and end radii agree within ``q·min(1, √2·sin(|sweep|/2))`` (one always does), and
    of those the one whose circle is nearest the true arc."""
    scale = 10.0**decimals
    s, e = arcs.start / scale, arcs.end / scale
    base = np.rint((ideal - s) * scale)
    steps = np.array([(i, j) for i in (-1, 0, 1) for j in (-1, 0, 1)], dtype=np.float64)
    offset = base[:, None, :] + steps[None, :, :]  # (n, 9, 2), integers held exactly
    centre = s[:, None, :] + offset / scale
    near = np.hypot(*np.moveaxis(centre - ideal[:, None, :], -1, 0)) <= 1.0 / scale
    d = (arcs.end - arcs.start).astype(np.float64)[:, None, :]
    r_s = np.hypot(offset[..., 0], offset[..., 1])
    r_e = np.hypot(offset[..., 0] - d[..., 0], offset[..., 1] - d[..., 1])
    # r_s − r_e = (r_s² − r_e²) / (r_s + r_e) = (2·off − D)·D / (r_s + r_e), in units.
    mismatch = np.abs(np.sum((2.0 * offset - d) * d, axis=-1)) / np.maximum(r_s + r_e, 1.0)
    bound = np.minimum(1.0, math.sqrt(2.0) * np.sin(0.5 * np.abs(arcs.sweep_rad)))
    agree = near & (mismatch <= bound[:, None] * (1.0 + 1e-9))
    allowed = np.where(np.any(agree, axis=1)[:, None], agree, near)
    points = _fit_points(arcs, s)
    gap = _gap(points[:, None, :, :], centre, r_s / scale, r_e / scale)
    pick = np.argmin(np.where(allowed, gap, np.inf), axis=1)
    rows = np.arange(len(pick))
    chosen = centre[rows, pick]
    ccw = arcs.sweep_rad > 0.0
    return _Encoded(
        ok=np.ones(len(pick), dtype=np.bool_),
        words=offset[rows, pick].astype(np.int64),
        centre=chosen,
        r_start=r_s[rows, pick] / scale,
        r_end=r_e[rows, pick] / scale,
        sweep_rad=_controller_sweeps(s, e, chosen, ccw),
    )


def _encode_r(arcs: _Arcs, ideal: FloatArray, decimals: int) -> _Encoded:
    """``R``: the ideal circle's radius, rounded, negative past a half circle, with the
    centre a controller derives from it (LinuxCNC's ``arc_data_r``). Not used within
    :data:`HALF_CIRCLE_MARGIN_DEG` of a half circle, nor where the rounded radius no longer
    spans the chord."""
    scale = 10.0**decimals
    s, e = arcs.start / scale, arcs.end / scale
    major = np.abs(arcs.sweep_rad) > np.pi
    r_units = np.rint(np.hypot(*(ideal - s).T) * scale)
    abs_r = r_units / scale
    chord = e - s
    half = 0.5 * np.hypot(chord[:, 0], chord[:, 1])
    near_half = np.abs(np.degrees(np.abs(arcs.sweep_rad)) - 180.0) < HALF_CIRCLE_MARGIN_DEG
    ok = ~near_half & (r_units > 0) & (half < abs_r * (1.0 - 1e-9))
    ccw = arcs.sweep_rad > 0.0
    # Left of the chord for a minor anticlockwise arc; a major arc takes the other side.
    side = np.where(ccw != major, 1.0, -1.0)
    normal = side[:, None] * np.stack([-chord[:, 1], chord[:, 0]], axis=1) / (2.0 * half[:, None])
    offset = np.sqrt(np.maximum(abs_r**2 - half**2, 0.0))
    centre = 0.5 * (s + e) + offset[:, None] * normal
    return _Encoded(
        ok=ok,
        words=np.where(major, -r_units, r_units).astype(np.int64)[:, None],
        centre=centre,
        r_start=abs_r,
        r_end=abs_r,
        sweep_rad=_controller_sweeps(s, e, centre, ccw),
    )


def _encode(arcs: _Arcs, decimals: int, arc_format: ArcFormat) -> list[_Encoded]:
    """The forms to try for each arc, best first: ``R`` (if asked for), then ``I``/``J``."""
    ideal = _best_fit_centres(arcs, decimals)
    forms = [_encode_ij(arcs, ideal, decimals)]
    if arc_format == "r":
        forms.insert(0, _encode_r(arcs, ideal, decimals))
    for form in forms:
        # A far centre (a nearly straight arc) may not be written; the chord is tried instead.
        form.ok[np.any(np.abs(form.words) >= MAX_ARC_WORD * 10.0**decimals, axis=1)] = False
    return forms


def _words(form: _Encoded, i: int, ccw: bool) -> ArcWords:
    w = form.words[i]
    return ArcWords(
        ccw=ccw,
        offset=(int(w[0]), int(w[1])) if len(w) == 2 else None,
        radius=int(w[0]) if len(w) == 1 else None,
        centre=(float(form.centre[i, 0]), float(form.centre[i, 1])),
        r_start=float(form.r_start[i]),
        r_end=float(form.r_end[i]),
        sweep_rad=float(form.sweep_rad[i]),
    )


def encode_arc(
    start: tuple[int, int],
    end: tuple[int, int],
    centre: Sequence[float],
    radius: float,
    sweep_rad: float,
    decimals: int,
    arc_format: ArcFormat = "ij",
) -> ArcWords:
    """The words of one arc from the rounded ``start`` to the rounded ``end`` (lattice
    integers: units in the last place) that best reproduce the arc about ``centre`` of
    ``radius`` turning by ``sweep_rad`` (signed, anticlockwise positive).

    The ideal centre is the point of the rounded ends' perpendicular bisector whose circle
    is nearest the true arc. ``I``/``J``: a lattice point within one unit of it, with start
    and end radii within ``q·min(1, √2·sin(|sweep|/2))`` of each other. ``R`` (when
    ``arc_format`` is ``"r"``): the ideal radius, rounded, negative past a half circle; not
    within :data:`HALF_CIRCLE_MARGIN_DEG` of one, where ``I``/``J`` is returned instead.
    """
    if tuple(start) == tuple(end):
        raise ValueError("an arc needs distinct end points")
    arcs = _Arcs(
        start=np.array([start], dtype=np.int64),
        end=np.array([end], dtype=np.int64),
        centre=np.array([centre], dtype=np.float64),
        radius=np.array([radius], dtype=np.float64),
        sweep_rad=np.array([sweep_rad], dtype=np.float64),
    )
    forms = _encode(arcs, decimals, arc_format)
    form = next((f for f in forms if f.ok[0]), forms[-1])
    return _words(form, 0, sweep_rad > 0.0)


# -- the program ----------------------------------------------------------------------


class _Plan(NamedTuple):
    """The rounded start and one cut move per segment: ``G1`` where ``arcs[i]`` is ``None``."""

    start: tuple[int, int]
    ends: list[tuple[int, int]]
    arcs: list[ArcWords | None]
    deviation: FloatArray


def _lattice(points: FloatArray, decimals: int) -> IntArray:
    scaled = np.asarray(points, dtype=np.float64) * 10.0**decimals
    if not np.all(np.isfinite(scaled)):
        raise GcodeError("spiral", "has coordinates that are not finite numbers")
    return np.rint(scaled).astype(np.int64)


def _number(units_in_last_place: int, decimals: int) -> str:
    """A lattice integer as fixed-point text: exact, never ``-0``, never NaN."""
    sign = "-" if units_in_last_place < 0 else ""
    whole, frac = divmod(abs(units_in_last_place), 10**decimals)
    return f"{sign}{whole}.{frac:0{decimals}d}"


def _feed(value: float, decimals: int) -> str:
    text = _number(round(value * 10**decimals), decimals).rstrip("0").rstrip(".")
    return f"F{text}"


def _must_be_lines(
    cols: SegmentColumns, start: IntArray, end: IntArray, decimals: int
) -> npt.NDArray[np.bool_]:
    """The core's own lines, and arcs a controller could take for a full circle: rounded
    ends that coincide, a sweep below :data:`MIN_SWEEP_RAD`, a radius of a few units in the
    last place."""
    q = 10.0**-decimals
    return np.asarray(
        ~cols.is_arc
        | np.all(start == end, axis=1)
        | (np.abs(cols.sweep_rad) < MIN_SWEEP_RAD)
        | (cols.radius < MIN_RADIUS_ULPS * q),
        dtype=np.bool_,
    )


def _flat_arcs(cols: SegmentColumns, decimals: int) -> npt.NDArray[np.bool_]:
    """Arcs whose sagitta ``2r·sin²(sweep/4)`` is below half a unit in the last place: the
    precision cannot tell them from their chord."""
    radius = np.where(cols.is_arc, cols.radius, 0.0)  # lines carry an infinite radius
    sagitta = 2.0 * radius * np.sin(0.25 * np.abs(cols.sweep_rad)) ** 2
    return np.asarray(cols.is_arc & (sagitta < 0.5 * 10.0**-decimals), dtype=np.bool_)


def _optional_lines(
    spline: ArcSpline, spiral: Spiral, options: GcodeOptions
) -> npt.NDArray[np.bool_]:
    """Arcs that ``min_arc_length``/``max_radius`` ask for as lines, where the chord keeps
    within the tolerance (measured before rounding, like the arcs themselves)."""
    cols = spline.columns
    wanted = np.zeros(len(cols), dtype=np.bool_)
    if options.min_arc_length is not None:
        wanted |= cols.length < options.min_arc_length
    if options.max_radius is not None:
        wanted |= cols.radius > options.max_radius
    wanted &= cols.is_arc
    rows = np.flatnonzero(wanted)
    if len(rows):
        dev = _line_deviations(
            spiral, cols.u_start[rows], cols.u_end[rows], cols.start[rows], cols.end[rows]
        )
        wanted[rows[dev > spline.tolerance]] = False
    return wanted


def _measure(
    spiral: Spiral,
    cols: SegmentColumns,
    rounded: FloatArray,
    rows: IntArray,
    arcs: Sequence[ArcWords | None],
) -> FloatArray:
    """The deviation of each block ``rows[k]`` (written as ``arcs[k]``) from its spiral piece;
    infinite for an arc that a controller would cut the long way round."""
    dev = np.empty(len(rows))
    u0, u1 = cols.u_start[rows], cols.u_end[rows]
    is_line = np.array([w is None for w in arcs], dtype=np.bool_)
    if np.any(is_line):
        r = rows[is_line]
        dev[is_line] = _line_deviations(
            spiral, u0[is_line], u1[is_line], rounded[r], rounded[r + 1]
        )
    words = [w for w in arcs if w is not None]
    if words:
        on = ~is_line
        dev[on] = _circle_deviations(
            spiral,
            u0[on],
            u1[on],
            np.array([w.centre for w in words], dtype=np.float64),
            np.array([w.r_start for w in words]),
            np.array([w.r_end for w in words]),
        )
        wrong_way = np.abs(np.array([w.sweep_rad for w in words]) - cols.sweep_rad[rows[on]])
        dev[on] = np.where(wrong_way > 0.5 * math.pi, np.inf, dev[on])
    return dev


def _plan(spline: ArcSpline, spiral: Spiral, options: GcodeOptions) -> _Plan:
    """One block per segment: the first of its choices whose read-back path stays within
    ``tolerance + q`` of its spiral piece, measuring all segments at once per round."""
    d = options.resolved_decimals
    cols = spline.columns
    n = len(cols)
    control = np.asarray(spiral.control_points, dtype=np.float64)
    if not np.all(np.abs(control) < MAX_COORDINATE):
        raise GcodeError(
            "spiral", f"has coordinates beyond ±{MAX_COORDINATE:g}, too large to write"
        )
    # Joints are rounded once each, so consecutive blocks meet exactly; the ends are the
    # spiral's own B0 and B3.
    joints = np.concatenate([control[:1], cols.start[1:], control[3:]], axis=0)
    lattice = _lattice(joints, d)
    rounded = lattice / 10.0**d
    start, end = lattice[:-1], lattice[1:]
    limit = spline.tolerance + 10.0**-d
    must = _must_be_lines(cols, start, end, d)
    prefer = _flat_arcs(cols, d) | _optional_lines(spline, spiral, options)
    choices: list[list[ArcWords | None]] = [[None] for _ in range(n)]
    rows = np.flatnonzero(~must)
    if len(rows):
        arcs = _Arcs(
            start[rows], end[rows], cols.center[rows], cols.radius[rows], cols.sweep_rad[rows]
        )
        forms = _encode(arcs, d, options.arc_format)
        for k, i in enumerate(rows.tolist()):
            ccw = bool(cols.sweep_rad[i] > 0.0)
            words: list[ArcWords | None] = [_words(f, k, ccw) for f in forms if f.ok[k]]
            choices[i] = [None, *words] if prefer[i] else [*words, None]
    chosen: list[ArcWords | None] = [c[0] for c in choices]
    deviation = np.full(n, np.inf)
    rank = np.zeros(n, dtype=np.int64)
    rows = np.arange(n)
    while len(rows):
        deviation[rows] = _measure(spiral, cols, rounded, rows, [chosen[i] for i in rows])
        over = rows[deviation[rows] > limit]
        rows = np.array([i for i in over if rank[i] + 1 < len(choices[i])], dtype=np.int64)
        for i in rows.tolist():
            rank[i] += 1
            chosen[i] = choices[i][rank[i]]
    worst = int(np.argmax(deviation))
    if not deviation[worst] <= limit:
        if not must[worst] and len(choices[worst]) == 1:
            raise GcodeError(
                "spiral",
                f"segment {worst} is an arc of radius {cols.radius[worst]:.6g} {options.units}, "
                f"too large to write (I, J and R are bounded by {MAX_ARC_WORD:g}), and its "
                f"chord would deviate from the spiral by {deviation[worst]:.3g}, more than "
                f"tolerance + 10^-{d} = {limit:.3g}; a smaller tolerance gives smaller arcs",
            )
        raise GcodeError(
            "decimals",
            f"{d} decimals are too few for tolerance {spline.tolerance:g}: segment {worst} "
            f"would deviate from the spiral by {deviation[worst]:.3g} {options.units}, more "
            f"than tolerance + 10^-{d} = {limit:.3g}; use more decimals or a larger tolerance",
        )
    return _Plan(
        start=(int(lattice[0, 0]), int(lattice[0, 1])),
        ends=[(int(x), int(y)) for x, y in end],
        arcs=chosen,
        deviation=deviation,
    )


def _text(plan: _Plan, spline: ArcSpline, options: GcodeOptions) -> Iterator[str]:
    """The program's lines, without line numbers."""
    d = options.resolved_decimals
    units = options.units
    feed = _feed(options.feed_rate, d)
    if options.comments:
        stats = spline.stats
        arcs = sum(w is not None for w in plan.arcs)
        moves = len(plan.arcs)
        yield "(arcspline: cubic Bezier spiral as circular arcs, Walton and Meek 1996)"
        yield f"(tolerance {spline.tolerance:.6g} {units}, strategy {spline.strategy})"
        yield (
            f"(arc spline: {stats.arc_count} arcs, {stats.line_count} lines, "
            f"max deviation {stats.max_deviation:.6g} {units})"
        )
        yield f"(program: {moves} moves, {arcs} arcs G2 G3, {moves - arcs} lines G1)"
        yield (
            f"(measured max deviation of the program from the spiral "
            f"{float(plan.deviation.max()):.6g} {units}, {d} decimals)"
        )
    yield f"G17 {'G21' if units == 'mm' else 'G20'} G90 G91.1 G94 {feed}"
    x0, y0 = _number(plan.start[0], d), _number(plan.start[1], d)
    restore = ""
    if options.safe_z is not None and options.cut_z is not None:
        safe = _number(round(options.safe_z * 10**d), d)
        cut = _number(round(options.cut_z * 10**d), d)
        plunge = _feed(options.resolved_plunge_feed_rate, d)
        yield f"G0 Z{safe}"
        yield f"G0 X{x0} Y{y0}"
        if plunge == feed:
            yield f"G1 Z{cut}"
        else:
            yield f"G1 Z{cut} {plunge}"
            restore = f" {feed}"
    else:
        yield f"G0 X{x0} Y{y0}"
    for k, (end, arc) in enumerate(zip(plan.ends, plan.arcs, strict=True)):
        words = f"X{_number(end[0], d)} Y{_number(end[1], d)}"
        if arc is not None:
            if arc.radius is not None:
                words += f" R{_number(arc.radius, d)}"
            else:
                assert arc.offset is not None
                words += f" I{_number(arc.offset[0], d)} J{_number(arc.offset[1], d)}"
        code = "G1" if arc is None else "G3" if arc.ccw else "G2"
        yield f"{code} {words}{restore if k == 0 else ''}"
    if options.safe_z is not None:
        yield f"G0 Z{_number(round(options.safe_z * 10**d), d)}"
    yield "M2"


def write_program(spline: ArcSpline, spiral: Spiral, options: GcodeOptions) -> str:
    """The G-code program cutting ``spline``, an approximation of ``spiral``.

    Raises :class:`GcodeError` when the spiral's coordinates are too large to write
    (``spiral``), or when ``options.decimals`` are too coarse for the spline's tolerance: the
    path read back from the program would leave ``tolerance + 10^-decimals`` of the spiral.
    """
    if len(spline) == 0:
        raise GcodeError("spiral", "the arc spline has no segments")
    lines = list(_text(_plan(spline, spiral, options), spline, options))
    if options.line_numbers:
        coded = [k for k, text in enumerate(lines) if not text.startswith("(")]
        step = 10 if 10 * len(coded) <= MAX_LINE_NUMBER else 1
        if step * len(coded) > MAX_LINE_NUMBER:
            raise GcodeError(
                "line_numbers", f"a program of {len(coded)} blocks exceeds N{MAX_LINE_NUMBER}"
            )
        for n, k in enumerate(coded, start=1):
            lines[k] = f"N{n * step} {lines[k]}"
    return "\n".join(lines) + "\n"
