"""A strict parser of SVG path data (the ``d`` attribute) into path segments.

:func:`parse_path_data` reads the grammar of the "Paths" chapter of SVG 1.1 and SVG 2 (every
command ``M L H V C S Q T A Z`` in both its absolute and relative form, implicit repetition of
parameters, SVG's number syntax) and builds the value types of
:mod:`arcspline.geometry.curves.segments`; arcs go from SVG's endpoint form to centre form as
in implementation notes F.6.5 and F.6.6. Coordinates are taken as given (SVG's y-down frame is
not flipped), so a sweep flag of 1, which turns the angle the positive way, reads as
anticlockwise in a y-up frame.

Why not svg.path: it silently drops what it does not understand (``"M 0 0 X 1"`` parses
without an error) and reports no positions. A tool path must not lose a piece of the drawing
without a word, so this parser refuses any path data that is not exactly the grammar, with a
:class:`~arcspline.geometry.errors.GeometryError` (``field="path"``) whose message names the
character offset (0-based) and what was expected there, e.g. ``at character 7: expected a
number for command 'L', found 'X'``. It runs in linear time, without recursion.

Decisions where the grammar or the spec leaves room:

- Strict, not "render up to the first error" (SVG 2's error handling): any error rejects the
  whole path. Empty (or blank) path data is an error, and so is data not beginning with
  ``M``/``m``.
- Separators follow the BNF: whitespace (space, tab, CR, LF, form feed) and at most one comma
  between two numbers or two argument sets. No comma may follow a command letter or precede
  one (``"L,1 2"`` and ``"L1 2, L3 4"`` are errors), and ``"1,,2"`` is an error.
- Numbers: an optional sign, digits with an optional fraction or a fraction alone (``"1."``
  and ``".5"``), an optional exponent. The longest match wins, so ``".5.5"`` is 0.5 0.5,
  ``"-1-2"`` is -1 -2 and ``"1e-3"`` one number; an exponent mark without digits
  (``"1e"``, ``"1e+"``) is an error, not a number followed by a command ``e``. Only ASCII digits
  count. A number whose value is not finite (``1e999``) is an error; one that underflows is
  zero. A relative coordinate or reflected control point whose sum overflows is an error too.
- Arc flags are the single characters ``0`` and ``1`` and need no separator after them:
  ``"a1 1 0 0010 10"`` is rx=1 ry=1 rotation=0 large-arc=0 sweep=0 x=10 y=10.
- ``Z`` takes no parameters; a number after it is an error.
- A relative ``m`` that begins the path is absolute (SVG); its further pairs are relative
  ``l``. Further pairs after ``M`` are ``L``.
- ``S``/``T`` reflect the previous command's second (resp. only) control point about the
  current point only when the previous command was ``C``/``S`` (resp. ``Q``/``T``), an implicit
  repetition counting as the same command; otherwise the control point is the current point.
- Subpaths: one per ``M`` or closed by ``Z``; a command after ``Z`` starts a new subpath at the
  closed one's start point. A subpath without segments is left out (a lone ``M x y``,
  ``M x y Z``, a second ``Z``, a subpath of only omitted arcs). ``Z`` appends a closing
  :class:`Line` when the current point differs from the start and marks the subpath closed.
  Zero-length lines and curves are kept (the geometry drops them later).
- Arcs (F.6.2, in the spec's order): equal end points omit the arc (even with a zero radius);
  otherwise a zero radius makes it a :class:`Line`; radii are taken as absolute values and
  scaled up when too small (F.6.6), in which case the centre is exactly the chord's midpoint.
  Equal radii (after that) give a :class:`CircularArc` (the rotation is then irrelevant and
  ignored), others an :class:`EllipticalArc` whose rotation is the given angle reduced modulo
  360° (sign kept). Arcs keep the given end points exactly. An arc whose sweep rounds to zero
  (end points closer than the radii can resolve) is its chord, a :class:`Line`; a large arc
  whose sweep would round to 2π is kept just below 2π. An arc that cannot be computed in
  floating point (radii or coordinates near the float range's ends) is an error.
"""

from __future__ import annotations

import math
import re
from typing import Final, NoReturn

from arcspline.geometry.curves.segments import (
    CircularArc,
    Cubic,
    EllipticalArc,
    Line,
    Path,
    Quadratic,
    Segment,
    Subpath,
)
from arcspline.geometry.errors import GeometryError
from arcspline.geometry.spline import Point

__all__ = ["parse_path_data"]

_WSP: Final = re.compile(r"[ \t\n\r\f]*")
_NUMBER: Final = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_NUMBER_START: Final = frozenset("+-.0123456789")
#: Parameters per argument set, by upper-case command letter.
_ARITY: Final = {"M": 2, "L": 2, "H": 1, "V": 1, "C": 6, "S": 4, "Q": 4, "T": 2, "A": 7, "Z": 0}
_COMMANDS: Final = frozenset(_ARITY) | frozenset(c.lower() for c in _ARITY)


def _argument_set(*tokens: str) -> re.Pattern[str]:
    # Each number is an atomic group: tokens are longest matches (maximal munch, as in the
    # token-by-token reading), never shortened by backtracking to fit ("12" is not "1" "2").
    separator = r"[ \t\n\r\f]*(?:,[ \t\n\r\f]*)?"
    return re.compile(separator.join(f"(?>({token}))" for token in tokens))


_NUM: Final = _NUMBER.pattern
#: A whole well-formed argument set of each command, one group per parameter.
_ARGUMENT_SETS: Final = {
    command: _argument_set(*([_NUM] * arity))
    for command, arity in _ARITY.items()
    if command not in "AZ"
} | {"A": _argument_set(_NUM, _NUM, _NUM, "[01]", "[01]", _NUM, _NUM)}
_TWO_PI: Final = 2.0 * math.pi
_BELOW_TWO_PI: Final = math.nextafter(_TWO_PI, 0.0)


def parse_path_data(d: str, *, max_segments: int | None = None) -> Path:
    """The path that SVG path data ``d`` describes.

    Raises :class:`~arcspline.geometry.errors.GeometryError` (``field="path"``) for anything
    outside the grammar, naming the 0-based character offset; with ``kind="segment_limit"``
    (and ``limit``) when the path has more than ``max_segments`` segments, as soon as the
    parser reaches the first one too many.
    """
    if max_segments is not None and max_segments < 0:
        raise GeometryError("max_segments", f"must be at least 0, got {max_segments}")
    return _Parser(d, max_segments).parse()


class _Parser:
    """One pass over the text; ``pos`` is the offset of the next unread character."""

    __slots__ = (
        "count",
        "cur",
        "d",
        "last_cubic",
        "last_quad",
        "max_segments",
        "n",
        "pos",
        "segments",
        "start",
        "subpaths",
    )

    def __init__(self, d: str, max_segments: int | None) -> None:
        self.d = d
        self.n = len(d)
        self.pos = 0
        self.max_segments = max_segments
        self.count = 0
        self.subpaths: list[Subpath] = []
        self.segments: list[Segment] = []
        self.start: Point | None = None
        self.cur = Point(0.0, 0.0)
        #: The second control point of the previous command if it was C/S, else None.
        self.last_cubic: Point | None = None
        #: The control point of the previous command if it was Q/T, else None.
        self.last_quad: Point | None = None

    # -- reading ---------------------------------------------------------------------------

    def fail(self, pos: int, message: str) -> NoReturn:
        raise GeometryError("path", f"at character {pos}: {message}")

    def found(self, pos: int) -> str:
        return "end of data" if pos >= self.n else repr(self.d[pos])

    def skip_wsp(self) -> None:
        match = _WSP.match(self.d, self.pos)
        assert match is not None  # the pattern matches the empty string
        self.pos = match.end()

    def separator(self) -> bool:
        """Skip ``wsp* (',' wsp*)?``; whether there was a comma."""
        self.skip_wsp()
        if self.pos < self.n and self.d[self.pos] == ",":
            self.pos += 1
            self.skip_wsp()
            return True
        return False

    def number(self, name: str) -> float:
        d, pos = self.d, self.pos
        match = _NUMBER.match(d, pos)
        if match is None:
            self.fail(pos, f"expected a number for command {name!r}, found {self.found(pos)}")
        end = match.end()
        if end < self.n and d[end] in "eE":
            self.fail(
                end,
                f"malformed exponent in a number for command {name!r}: expected digits "
                f"after {d[end]!r}, found {self.found(end + 1)}",
            )
        text = match.group()
        value = float(text)
        if not math.isfinite(value):
            self.fail(pos, f"number {text!r} for command {name!r} is out of range (not finite)")
        self.pos = end
        return value

    def flag(self, name: str) -> float:
        pos = self.pos
        if pos >= self.n or self.d[pos] not in "01":
            self.fail(
                pos, f"expected a flag ('0' or '1') for command {name!r}, found {self.found(pos)}"
            )
        self.pos = pos + 1
        return 1.0 if self.d[pos] == "1" else 0.0

    def arguments(self, name: str, command: str) -> list[float]:
        """One argument set: in one regular-expression match when it is well formed, else
        token by token, which finds the error."""
        d = self.d
        match = _ARGUMENT_SETS[command].match(d, self.pos)
        if match is not None:
            end = match.end()
            if end >= self.n or d[end] not in "eE":
                args = [float(text) for text in match.groups()]
                if all(map(math.isfinite, args)):
                    self.pos = end
                    return args
        args = []
        for i in range(_ARITY[command]):
            if i:
                self.separator()
            args.append(self.flag(name) if command == "A" and i in (3, 4) else self.number(name))
        return args

    # -- the grammar -----------------------------------------------------------------------

    def parse(self) -> Path:
        d, n = self.d, self.n
        self.skip_wsp()
        if self.pos >= n:
            raise GeometryError("path", "the path data is empty")
        if d[self.pos] not in "Mm":
            self.fail(
                self.pos,
                "path data must begin with a moveto command ('M' or 'm'), "
                f"found {self.found(self.pos)}",
            )
        while self.pos < n:
            cmd_pos = self.pos
            name = d[cmd_pos]
            if name not in _COMMANDS:
                if name.isascii() and name.isalpha():
                    self.fail(cmd_pos, f"unknown command {name!r}")
                self.fail(cmd_pos, f"expected a command letter, found {self.found(cmd_pos)}")
            self.pos += 1
            self.skip_wsp()
            command = name.upper()
            if command == "Z":
                self.close(cmd_pos)
                if self.pos < n and (d[self.pos] in _NUMBER_START or d[self.pos] == ","):
                    self.fail(
                        self.pos,
                        f"command {name!r} takes no parameters, found {self.found(self.pos)}",
                    )
                continue
            self.command_sets(name, command)
        self.flush(closed=False)
        return Path(tuple(self.subpaths))

    def command_sets(self, name: str, command: str) -> None:
        """One command's argument sets, the first required, then as many as follow."""
        d, n = self.d, self.n
        relative = name.islower()
        while True:
            set_pos = self.pos
            args = self.arguments(name, command)
            self.apply(command, relative, args, set_pos)
            if command == "M":
                command = "L"  # further pairs are lineto's (relative after 'm')
            comma = self.separator()
            if self.pos < n and d[self.pos] in _NUMBER_START:
                continue
            if comma:
                self.fail(
                    self.pos,
                    f"expected a number for command {name!r} after ',', "
                    f"found {self.found(self.pos)}",
                )
            return

    # -- building segments -----------------------------------------------------------------

    def point(self, x: float, y: float, relative: bool, pos: int) -> Point:
        if not relative:
            return Point(x, y)
        cur = self.cur
        p = Point(cur.x + x, cur.y + y)
        if not (math.isfinite(p.x) and math.isfinite(p.y)):
            self.fail(pos, "a relative coordinate overflows the float range")
        return p

    def reflect(self, control: Point | None, pos: int) -> Point:
        cur = self.cur
        if control is None:
            return cur
        p = Point(2.0 * cur.x - control.x, 2.0 * cur.y - control.y)
        if not (math.isfinite(p.x) and math.isfinite(p.y)):
            self.fail(pos, "the reflected control point overflows the float range")
        return p

    def add(self, segment: Segment, pos: int) -> None:
        limit = self.max_segments
        if limit is not None and self.count >= limit:
            raise GeometryError(
                "path",
                f"at character {pos}: more than {limit} segments",
                kind="segment_limit",
                limit=limit,
            )
        self.count += 1
        self.segments.append(segment)
        self.cur = segment.end

    def flush(self, *, closed: bool) -> None:
        if self.segments:
            self.subpaths.append(Subpath(tuple(self.segments), closed))
            self.segments = []

    def close(self, pos: int) -> None:
        start = self.start
        assert start is not None  # the path begins with a moveto
        if self.segments:
            if self.cur != start:
                self.add(Line(self.cur, start), pos)
            self.flush(closed=True)
        self.cur = start
        self.last_cubic = self.last_quad = None

    def apply(self, command: str, relative: bool, a: list[float], pos: int) -> None:
        cur = self.cur
        last_cubic = last_quad = None
        if command == "M":
            self.flush(closed=False)
            # A relative moveto that begins the path is absolute.
            p = self.point(a[0], a[1], relative and self.start is not None, pos)
            self.start = self.cur = p
        elif command == "L":
            self.add(Line(cur, self.point(a[0], a[1], relative, pos)), pos)
        elif command == "H":
            x = cur.x + a[0] if relative else a[0]
            if not math.isfinite(x):
                self.fail(pos, "a relative coordinate overflows the float range")
            self.add(Line(cur, Point(x, cur.y)), pos)
        elif command == "V":
            y = cur.y + a[0] if relative else a[0]
            if not math.isfinite(y):
                self.fail(pos, "a relative coordinate overflows the float range")
            self.add(Line(cur, Point(cur.x, y)), pos)
        elif command == "C":
            c1 = self.point(a[0], a[1], relative, pos)
            last_cubic = self.point(a[2], a[3], relative, pos)
            self.add(Cubic(cur, c1, last_cubic, self.point(a[4], a[5], relative, pos)), pos)
        elif command == "S":
            c1 = self.reflect(self.last_cubic, pos)
            last_cubic = self.point(a[0], a[1], relative, pos)
            self.add(Cubic(cur, c1, last_cubic, self.point(a[2], a[3], relative, pos)), pos)
        elif command == "Q":
            last_quad = self.point(a[0], a[1], relative, pos)
            self.add(Quadratic(cur, last_quad, self.point(a[2], a[3], relative, pos)), pos)
        elif command == "T":
            last_quad = self.reflect(self.last_quad, pos)
            self.add(Quadratic(cur, last_quad, self.point(a[0], a[1], relative, pos)), pos)
        else:  # "A"
            end = self.point(a[5], a[6], relative, pos)
            try:
                arc = arc_from_endpoints(cur, end, a[0], a[1], a[2], a[3] == 1.0, a[4] == 1.0)
            except UncomputableArcError:
                self.fail(
                    pos,
                    "the arc cannot be computed in floating point "
                    "(radii or coordinates too extreme)",
                )
            if arc is not None:
                self.add(arc, pos)
        self.last_cubic, self.last_quad = last_cubic, last_quad


# -- arcs: endpoint form to centre form (SVG implementation notes F.6.5, F.6.6) -------------


class UncomputableArcError(Exception):
    """An arc that floating point cannot represent (radii or coordinates too extreme)."""


def _half_sum(a: float, b: float) -> float:
    s = (a + b) / 2.0
    return s if math.isfinite(s) else a / 2.0 + b / 2.0


def _half_difference(a: float, b: float) -> float:
    s = (a - b) / 2.0
    return s if math.isfinite(s) else a / 2.0 - b / 2.0


def _cos_sin_deg(deg: float) -> tuple[float, float]:
    """``cos`` and ``sin`` of ``deg`` degrees, exact at multiples of 90°."""
    quarters, rest = divmod(deg, 90.0)
    if rest == 0.0:
        return ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(quarters) % 4]
    rad = math.radians(deg)
    return math.cos(rad), math.sin(rad)


def arc_from_endpoints(
    p0: Point, p1: Point, rx: float, ry: float, rotation_deg: float, large: bool, sweep: bool
) -> Segment | None:
    """The arc of SVG's ``A`` from ``p0`` to ``p1``; None when it is omitted (equal end
    points). Raises :class:`UncomputableArcError` when floating point cannot represent it."""
    if p0 == p1:
        return None
    rx, ry = abs(rx), abs(ry)
    if rx == 0.0 or ry == 0.0:
        return Line(p0, p1)
    circle = rx == ry
    rotation_deg = 0.0 if circle else math.fmod(rotation_deg, 360.0)
    cos_r, sin_r = _cos_sin_deg(rotation_deg)
    # F.6.5.1: half the chord, p0 relative to the midpoint in the ellipse's axes.
    hx, hy = _half_difference(p0.x, p1.x), _half_difference(p0.y, p1.y)
    x1 = cos_r * hx + sin_r * hy
    y1 = -sin_r * hx + cos_r * hy
    if x1 == 0.0 and y1 == 0.0:
        raise UncomputableArcError  # distinct end points, but closer than the rotation resolves
    # e: the unit direction of (x1 / rx, y1 / ry), scaled so that nothing under/overflows.
    m, big = max(abs(x1), abs(y1)), max(rx, ry)
    ex, ey = (x1 / m) * (ry / big), (y1 / m) * (rx / big)
    norm = math.hypot(ex, ey)
    if norm == 0.0:
        raise UncomputableArcError
    ex, ey = ex / norm, ey / norm
    # lam = sqrt(Λ) of F.6.6: > 1 when the radii are too small for the chord.
    lam = math.hypot(x1 / rx, y1 / ry)
    if lam >= 1.0:
        if lam > 1.0:  # F.6.6: scale the radii up by sqrt(Λ)
            if circle:
                rx = ry = math.hypot(x1, y1)
            else:
                rx, ry = math.hypot(x1, y1 * (rx / ry)), math.hypot(x1 * (ry / rx), y1)
        lam, t = 1.0, 0.0  # the centre is the chord's midpoint
    else:
        t = math.sqrt(max(0.0, (1.0 - lam) * (1.0 + lam)))
    # F.6.5.2: the centre c' = σ·t·(rx·ey, −ry·ex), σ = +1 when the flags differ. In the unit
    # circle of the ellipse's parameter, p0 is at lam·e + σ·t·e⊥ and p1 at −lam·e + σ·t·e⊥
    # (e⊥ = (−ey, ex)), so the lesser sweep between them is 2·atan2(lam, t) ∈ (0, π].
    sigma = 1.0 if large != sweep else -1.0
    cxp, cyp = sigma * t * rx * ey, -sigma * t * ry * ex
    start_angle = math.atan2(lam * ey + sigma * t * ex, lam * ex - sigma * t * ey)
    lesser = 2.0 * math.atan2(lam, t)
    if lesser == 0.0 and not large:
        return Line(p0, p1)  # a sweep that rounds to zero: the arc is its chord
    magnitude = min(_TWO_PI - lesser, _BELOW_TWO_PI) if large else lesser
    sweep_rad = magnitude if sweep else -magnitude
    # F.6.5.3: back to the user frame.
    center = Point(
        cos_r * cxp - sin_r * cyp + _half_sum(p0.x, p1.x),
        sin_r * cxp + cos_r * cyp + _half_sum(p0.y, p1.y),
    )
    if not all(map(math.isfinite, (center.x, center.y, rx, ry, start_angle))):
        raise UncomputableArcError
    if circle:
        return CircularArc(p0, p1, center, rx, start_angle, sweep_rad)
    if rx == ry:  # scaled up into a circle: the polar angle of p0 about the centre
        start_angle = math.atan2(p0.y - center.y, p0.x - center.x)
        return CircularArc(p0, p1, center, rx, start_angle, sweep_rad)
    return EllipticalArc(p0, p1, center, rx, ry, math.radians(rotation_deg), start_angle, sweep_rad)
