"""SVG's ``transform`` attribute read into one :class:`Affine` (docs/drawings.md §3).

The grammar is SVG 1.1's "The 'transform' attribute" (7.6), which SVG 2 keeps for the
attribute: a list of ``matrix(a b c d e f)``, ``translate(tx [ty])``, ``scale(sx [sy])``,
``rotate(angle [cx cy])``, ``skewX(angle)``, ``skewY(angle)``, separated by whitespace and/or
one comma, each with its numbers separated the same way; angles are degrees. The list
``A B C`` is the product ``A·B·C``: ``C`` applies first. Numbers follow SVG's number syntax
(sign, fraction, exponent), as in path data.

Strict, as the path-data parser is: anything outside the grammar (an unknown name, a wrong
count of numbers, a missing parenthesis, a stray comma, a number that is not finite) raises
:class:`TransformSyntaxError` naming the 0-based character offset and what was expected
there. The document reader turns it into a ``DocumentError`` naming the element.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from typing import Final

from .affine import Affine

__all__ = ["TransformSyntaxError", "parse_transform"]


class TransformSyntaxError(ValueError):
    """A ``transform`` value outside the grammar; the message names the character offset."""


_WSP: Final = re.compile(r"[ \t\n\r\f]*")
_NUMBER: Final = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_NAME: Final = re.compile(r"[A-Za-z]+")


def _rotate(n: list[float]) -> Affine:
    return Affine.rotate_deg(n[0], n[1], n[2]) if len(n) == 3 else Affine.rotate_deg(n[0])


#: Each transform's allowed counts of numbers and its map from them.
_KINDS: Final[dict[str, tuple[tuple[int, ...], Callable[[list[float]], Affine]]]] = {
    "matrix": ((6,), lambda n: Affine(*n)),
    "translate": ((1, 2), lambda n: Affine.translate(*n)),
    "scale": ((1, 2), lambda n: Affine.scale(*n)),
    "rotate": ((1, 3), _rotate),
    "skewX": ((1,), lambda n: Affine.skew_x_deg(n[0])),
    "skewY": ((1,), lambda n: Affine.skew_y_deg(n[0])),
}


def parse_transform(text: str) -> Affine:
    """The map that the transform list ``text`` describes (identity for an empty list).

    >>> parse_transform("translate(10) scale(2)").apply((1.0, 1.0))
    Point(x=12.0, y=2.0)
    """
    return _Reader(text).read()


class _Reader:
    """One pass over the text; ``pos`` is the offset of the next unread character."""

    __slots__ = ("pos", "text")

    def __init__(self, text: str) -> None:
        self.text = text
        self.pos = 0

    def fail(self, expected: str) -> TransformSyntaxError:
        found = repr(self.text[self.pos]) if self.pos < len(self.text) else "the end"
        return TransformSyntaxError(f"at character {self.pos}: expected {expected}, found {found}")

    def skip_wsp(self) -> None:
        match = _WSP.match(self.text, self.pos)
        assert match is not None  # a star pattern always matches
        self.pos = match.end()

    def skip_comma_wsp(self) -> None:
        """Whitespace with at most one comma."""
        self.skip_wsp()
        if self.text.startswith(",", self.pos):
            self.pos += 1
            self.skip_wsp()

    def read(self) -> Affine:
        result = Affine()
        self.skip_wsp()
        if self.pos == len(self.text):
            return result
        while True:
            result = result @ self.one()
            self.skip_wsp()
            comma = self.text.startswith(",", self.pos)
            if comma:
                self.pos += 1
                self.skip_wsp()
            if self.pos == len(self.text):
                if comma:
                    raise self.fail("a transform after ','")
                return result
            # No separator is needed between two transforms ("scale(2)translate(1)"), as
            # browsers and SVG 2's CSS syntax read them.

    def one(self) -> Affine:
        match = _NAME.match(self.text, self.pos)
        if match is None or match.group() not in _KINDS:
            raise self.fail("one of " + ", ".join(_KINDS))
        name = match.group()
        counts, build = _KINDS[name]
        self.pos = match.end()
        self.skip_wsp()
        if not self.text.startswith("(", self.pos):
            raise self.fail(f"'(' after {name}")
        self.pos += 1
        self.skip_wsp()
        numbers: list[float] = []
        while not self.text.startswith(")", self.pos):
            if self.pos == len(self.text):
                raise self.fail(f"a number or ')' in {name}")
            if numbers:  # as in path data, "1-2" needs no separator
                self.skip_comma_wsp()
            numbers.append(self.number(name))
            self.skip_wsp()
        if len(numbers) not in counts:
            allowed = " or ".join(str(c) for c in counts)
            raise self.fail(f"{allowed} numbers in {name}, got {len(numbers)} before ')'")
        self.pos += 1
        return build(numbers)

    def number(self, name: str) -> float:
        match = _NUMBER.match(self.text, self.pos)
        if match is None:
            raise self.fail(f"a number in {name}")
        value = float(match.group())
        if not math.isfinite(value):
            raise self.fail(f"a finite number in {name}")
        self.pos = match.end()
        return value
