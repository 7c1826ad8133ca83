"""The vocabulary of offsets: options, notes and results (docs/offsets.md §1).

Lengths are in the drawing's unit; angles in radians, anticlockwise positive; "left" and
"right" are seen along the direction of travel.
"""

from __future__ import annotations

from typing import Literal, NamedTuple

from ..curves.segments import CircularArc, Line, Subpath

Side = Literal["left", "right", "inside", "outside"]
Join = Literal["round", "mitre"]
NoteKind = Literal["split", "vanished", "narrow", "collapsed", "loop", "open"]
#: What an offset chain is made of, in and out: exact lines and circular arcs.
Element = Line | CircularArc


class OffsetOptions(NamedTuple):
    """How to offset (docs/offsets.md §1): ``distance`` > 0 (the tool radius) to ``side``;
    convex corners joined ``round`` (an arc of radius ``distance`` about the corner) or
    ``mitre`` (the two offsets extended to meet, when that point lies within
    ``mitre_limit·distance`` of the corner; round otherwise); result loops narrower, and open
    pieces shorter, than ``sliver`` are dropped."""

    distance: float
    side: Side
    join: Join = "round"
    mitre_limit: float = 2.0
    sliver: float = 0.0


class OffsetNote(NamedTuple):
    """Something the caller should know about one contour's offset (docs/offsets.md §5),
    in words that name no index (the caller says which contour)."""

    kind: NoteKind
    message: str


class SubpathOffset(NamedTuple):
    """One chain's offset: its pieces (closed loops for a closed chain; ``()`` if it
    vanished), each of lines and arcs chained bit for bit, and the notes."""

    subpaths: tuple[Subpath, ...]
    notes: tuple[OffsetNote, ...]
