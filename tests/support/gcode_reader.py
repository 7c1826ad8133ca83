"""An independent reader of RS-274/NGC programs, to check what ``arcspline.outputs.gcode`` writes.

It shares no code with the writer. It reads a program as a controller would and rebuilds
the tool path:

* blocks: an optional ``N`` number, words (a letter and a number written in plain decimal:
  no ``nan``, ``inf`` or exponent, which no controller reads), ``(...)`` and ``;`` comments;
  only the letters ``N G M F X Y Z I J R``, and other than ``G`` or ``M`` once per block;
* modal state: motion (``G0 G1 G2 G3``), plane (``G17 G18 G19``), units (``G20 G21``),
  distance (``G90 G91``), arc distance (``G90.1 G91.1``), feed mode (``G93 G94 G95``), ``F``;
  an unknown G or M code is an error, not ignored;
* arcs as LinuxCNC's interpreter (``interp_arc.cc``) computes them: centre from ``I``/``J``
  (incremental under ``G91.1``, absolute under ``G90.1``) or from ``R`` (on the chord's
  perpendicular bisector, negative ``R`` for the major arc); the radius to the start and to
  the end; and the sweep, which is a full turn when the end angle equals the start angle.

Only the XY plane and absolute distance mode are supported (the writer uses nothing else);
anything else raises :class:`GcodeSyntaxError` rather than being misread.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

_WORD = re.compile(r"([A-Z])([+-]?(?:\d+\.?\d*|\.\d+))")
_MODAL_GROUPS: dict[float, str] = {
    0: "motion",
    1: "motion",
    2: "motion",
    3: "motion",
    17: "plane",
    18: "plane",
    19: "plane",
    20: "units",
    21: "units",
    90: "distance",
    91: "distance",
    90.1: "arc_distance",
    91.1: "arc_distance",
    93: "feed_mode",
    94: "feed_mode",
    95: "feed_mode",
}
_PROGRAM_END = {2, 30}
#: The words a program of this project may contain; any other is refused, not ignored.
_LETTERS = set("NGMFXYZIJR")


class GcodeSyntaxError(ValueError):
    """A line the reader (and so, presumably, a controller) cannot take."""

    def __init__(self, line: int, text: str, reason: str) -> None:
        super().__init__(f"line {line}: {reason}: {text!r}")
        self.line = line
        self.reason = reason


@dataclass(frozen=True)
class Block:
    """One line of the program, split into its parts."""

    line: int
    text: str
    number: int | None
    g: tuple[float, ...]
    m: tuple[int, ...]
    words: dict[str, float]
    comments: tuple[str, ...]

    def has(self, *letters: str) -> bool:
        return all(letter in self.words for letter in letters)


@dataclass(frozen=True)
class Move:
    """One motion: a rapid (0), a line (1) or an arc (2 clockwise, 3 anticlockwise).

    For arcs, ``centre`` and the radii are what the controller computes from the words and
    ``sweep_rad`` the signed angle it turns through (±2π for a full circle).
    """

    block: Block
    motion: int
    start: tuple[float, float, float]
    end: tuple[float, float, float]
    feed: float | None
    explicit_motion: bool
    centre: tuple[float, float] | None = None
    r_start: float | None = None
    r_end: float | None = None
    sweep_rad: float | None = None

    @property
    def is_cut(self) -> bool:
        """A feed move in the XY plane (a plunge along Z alone is not one)."""
        return self.motion in (1, 2, 3) and ("X" in self.block.words or "Y" in self.block.words)

    @property
    def xy_start(self) -> tuple[float, float]:
        return self.start[0], self.start[1]

    @property
    def xy_end(self) -> tuple[float, float]:
        return self.end[0], self.end[1]


@dataclass
class Program:
    """A read program: its blocks, its moves, and the modes in force before the first move."""

    blocks: list[Block] = field(default_factory=list)
    moves: list[Move] = field(default_factory=list)
    preamble_modes: dict[str, float] = field(default_factory=dict)
    preamble_feed: float | None = None
    ended: bool = False

    @property
    def cuts(self) -> list[Move]:
        return [m for m in self.moves if m.is_cut]

    @property
    def comments(self) -> list[str]:
        return [c for b in self.blocks for c in b.comments]


def _split(line_no: int, raw: str) -> tuple[str, tuple[str, ...]]:
    """The code part of a line (upper case, no blanks) and its comments."""
    code: list[str] = []
    comments: list[str] = []
    rest = raw
    while rest:
        head, sep, tail = rest.partition("(")
        if ";" in head:
            head, _, semi = head.partition(";")
            code.append(head)
            comments.append(semi + sep + tail)
            break
        code.append(head)
        if not sep:
            break
        body, close, rest = tail.partition(")")
        if not close or "(" in body:
            raise GcodeSyntaxError(line_no, raw, "unclosed or nested comment")
        comments.append(body)
    return "".join(code).upper().replace(" ", "").replace("\t", ""), tuple(comments)


def parse_block(line_no: int, raw: str) -> Block:
    """One line as a :class:`Block`."""
    code, comments = _split(line_no, raw)
    pos = 0
    g: list[float] = []
    m: list[int] = []
    words: dict[str, float] = {}
    number: int | None = None
    for match in _WORD.finditer(code):
        if match.start() != pos:
            raise GcodeSyntaxError(line_no, raw, f"cannot read {code[pos : match.start()]!r}")
        pos = match.end()
        letter, text = match.group(1), match.group(2)
        if letter not in _LETTERS:
            raise GcodeSyntaxError(line_no, raw, f"unsupported word {letter}")
        value = float(text)
        if not math.isfinite(value):
            raise GcodeSyntaxError(line_no, raw, "a number that is not finite")
        if letter == "N":
            if number is not None or g or m or words or "." in text or value < 0:
                raise GcodeSyntaxError(line_no, raw, "N must come first, once, as an integer")
            number = int(text)
        elif letter == "G":
            g.append(round(value, 1))
        elif letter == "M":
            if value != int(value):
                raise GcodeSyntaxError(line_no, raw, "M codes are integers")
            m.append(int(value))
        else:
            if letter in words:
                raise GcodeSyntaxError(line_no, raw, f"{letter} twice in one block")
            words[letter] = value
    if pos != len(code):
        raise GcodeSyntaxError(line_no, raw, f"cannot read {code[pos:]!r}")
    return Block(line_no, raw, number, tuple(g), tuple(m), words, comments)


def _turn(start: float, end: float, ccw: bool) -> float:
    """The signed sweep from polar angle ``start`` to ``end``, as LinuxCNC turns: an end
    angle not strictly past the start (in the arc's sense) adds a full turn."""
    if ccw:
        return end - start if end > start else end - start + 2.0 * math.pi
    return end - start if end < start else end - start - 2.0 * math.pi


def _r_centre(
    start: tuple[float, float], end: tuple[float, float], r: float, ccw: bool
) -> tuple[float, float]:
    """LinuxCNC's ``arc_data_r``: the centre on the chord's bisector, left of the chord for
    an anticlockwise minor arc; a negative ``r`` (major arc) takes the other side."""
    if start == end:
        raise ValueError("R form with coinciding end points")
    mid = ((start[0] + end[0]) / 2.0, (start[1] + end[1]) / 2.0)
    half = math.hypot(end[0] - mid[0], end[1] - mid[1])
    if half - abs(r) > 0.0:
        raise ValueError("arc radius too small to reach the end point")
    left = ccw == (r > 0)
    theta = math.atan2(end[1] - start[1], end[0] - start[0]) + (
        math.pi / 2 if left else -math.pi / 2
    )
    offset = abs(r) * math.cos(math.asin(min(1.0, half / abs(r))))
    return mid[0] + offset * math.cos(theta), mid[1] + offset * math.sin(theta)


def read(text: str) -> Program:
    """Read a whole program; raises :class:`GcodeSyntaxError` on anything unreadable."""
    program = Program()
    modes: dict[str, float] = {}
    feed: float | None = None
    position = (0.0, 0.0, 0.0)
    for line_no, raw in enumerate(text.splitlines(), start=1):
        block = parse_block(line_no, raw)
        program.blocks.append(block)
        if program.ended and (block.g or block.m or block.words):
            raise GcodeSyntaxError(line_no, raw, "code after the program end")
        motion_words = [code for code in block.g if _MODAL_GROUPS.get(code) == "motion"]
        for code in block.g:
            if code not in _MODAL_GROUPS:
                raise GcodeSyntaxError(line_no, raw, f"unknown G{code:g}")
        groups = [_MODAL_GROUPS[code] for code in block.g]
        if len(groups) != len(set(groups)):
            raise GcodeSyntaxError(line_no, raw, "two G codes of one modal group")
        for code in block.g:
            modes[_MODAL_GROUPS[code]] = code
        for code in block.m:
            if code not in _PROGRAM_END:
                raise GcodeSyntaxError(line_no, raw, f"unknown M{code}")
            program.ended = True
        if "F" in block.words:
            feed = block.words["F"]
            if not feed > 0.0:
                raise GcodeSyntaxError(line_no, raw, "feed rate must be positive")
        axes = {"X", "Y", "Z"} & block.words.keys()
        if not axes and not motion_words:
            if block.has("I") or block.has("J") or block.has("R"):
                raise GcodeSyntaxError(line_no, raw, "arc words without a motion")
            if not program.moves and feed is not None:
                program.preamble_feed = feed
            if not program.moves:
                program.preamble_modes = dict(modes)
            continue
        if "motion" not in modes:
            raise GcodeSyntaxError(line_no, raw, "axis words with no motion mode")
        if modes.get("distance", 90) != 90 or modes.get("plane", 17) != 17:
            raise GcodeSyntaxError(line_no, raw, "only G17 G90 are supported")
        if not program.moves:
            program.preamble_modes = {k: v for k, v in modes.items() if k != "motion"}
            program.preamble_feed = feed
        motion = int(modes["motion"])
        end = (
            block.words.get("X", position[0]),
            block.words.get("Y", position[1]),
            block.words.get("Z", position[2]),
        )
        if motion in (1, 2, 3) and feed is None:
            raise GcodeSyntaxError(line_no, raw, "feed move with no feed rate")
        move = Move(
            block=block,
            motion=motion,
            start=position,
            end=end,
            feed=feed if motion else None,
            explicit_motion=bool(motion_words),
        )
        if motion in (2, 3):
            move = _arc(move, modes)
        elif {"I", "J", "R"} & block.words.keys():
            raise GcodeSyntaxError(line_no, raw, "I, J or R on a straight move")
        program.moves.append(move)
        position = end
    return program


def _arc(move: Move, modes: dict[str, float]) -> Move:
    block = move.block
    words = block.words
    ccw = move.motion == 3
    s, e = move.xy_start, move.xy_end
    has_r = "R" in words
    has_ij = "I" in words or "J" in words
    if has_r == has_ij:
        raise GcodeSyntaxError(block.line, block.text, "an arc needs either I/J or R")
    if has_r:
        try:
            centre = _r_centre(s, e, words["R"], ccw)
        except ValueError as exc:
            raise GcodeSyntaxError(block.line, block.text, str(exc)) from None
    elif modes.get("arc_distance", 91.1) == 91.1:
        centre = (s[0] + words.get("I", 0.0), s[1] + words.get("J", 0.0))
    else:
        centre = (words.get("I", 0.0), words.get("J", 0.0))
    a = math.atan2(s[1] - centre[1], s[0] - centre[0])
    b = math.atan2(e[1] - centre[1], e[0] - centre[0])
    return Move(
        block=block,
        motion=move.motion,
        start=move.start,
        end=move.end,
        feed=move.feed,
        explicit_motion=move.explicit_motion,
        centre=centre,
        r_start=math.hypot(s[0] - centre[0], s[1] - centre[1]),
        r_end=math.hypot(e[0] - centre[0], e[1] - centre[1]),
        sweep_rad=_turn(a, b, ccw),
    )
