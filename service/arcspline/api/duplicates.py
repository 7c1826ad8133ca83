"""A JSON body that names a key twice in one object (docs/http-api.md#request-bodies).

RFC 8259 §4 leaves such a body's meaning open — parsers take the first value, the last, or
refuse — and pydantic-core takes the last without a word, so ``{"tolerance": 0.001,
"tolerance": 1e9}`` would be cut at 1e9 while a proxy or a log reader saw 0.001. The service
refuses it (as RFC 7493, I-JSON, requires), naming the key and where it is.

The check is the standard library's C scanner with an ``object_pairs_hook`` that sees each
object's members before they become a dict (pydantic-core's parser and orjson have no such
option). It runs over the body beside pydantic's own parse; the path of the key is found by a
second, slower parse only for a body that has a duplicate (off the event loop: up to half a
second for a 4 MiB body).
"""

from __future__ import annotations

import json
from collections import Counter
from collections.abc import Iterable
from typing import Any, NamedTuple

Loc = tuple[str | int, ...]


class DuplicateKey(NamedTuple):
    """The first key named more than once in one object (in document order)."""

    loc: Loc  # the object's path, then the key
    times: int  # how many times the object names it


#: The most members one object of a request may have: the largest of the schemas has a few
#: dozen fields. A body of 170,000 unknown fields would otherwise reach pydantic, whose list of
#: one error per field takes half a second to build, holding the interpreter (the event loop
#: included, whatever thread builds it).
MAX_MEMBERS = 256


class TooManyMembersError(Exception):
    """An object of the body has more than :data:`MAX_MEMBERS` members."""

    def __init__(self, members: int) -> None:
        super().__init__(members)
        self.members = members


class _RepeatedKeyError(Exception):
    pass


def _refuse_repeats(pairs: list[tuple[str, Any]]) -> None:
    # None, not a dict: the check keeps nothing of the body.
    if len(pairs) > MAX_MEMBERS:
        raise TooManyMembersError(len(pairs))
    if len(pairs) > 1 and len({key for key, _ in pairs}) != len(pairs):
        raise _RepeatedKeyError


_CHECK = json.JSONDecoder(object_pairs_hook=_refuse_repeats)
#: Objects as tuples of their members, repeats kept (arrays stay lists).
_KEEP = json.JSONDecoder(object_pairs_hook=tuple)


def has_duplicate(raw: bytes) -> bool:
    """Whether ``raw`` names a key twice in one object: False for a body that is not JSON
    at all (pydantic-core says why, in its words); True for one malformed only after it.
    :class:`TooManyMembersError` for an object with more than :data:`MAX_MEMBERS` members."""
    try:
        _CHECK.decode(raw.decode())
    except _RepeatedKeyError:
        return True
    except (ValueError, RecursionError):  # not JSON, not UTF-8, nested too deeply
        return False
    return False


def first_duplicate(raw: bytes) -> DuplicateKey | None:
    """Where ``raw`` first names a key twice in one object (the slow part, for a body that
    :func:`has_duplicate`): None for a body that is malformed after it (that is said)."""
    try:
        tree = _KEEP.decode(raw.decode())
    except (ValueError, RecursionError):
        return None
    return _locate(tree)


def _locate(tree: Any) -> DuplicateKey | None:
    """Depth first, in document order, without recursion (the tree may be deep); only
    containers are visited, each with its parent's entry (the path is built once, at the
    end)."""
    # (node, parent entry, key in parent)
    stack: list[tuple[Any, Any, str | int | None]] = [(tree, None, None)]
    while stack:
        entry = stack.pop()
        node = entry[0]
        if isinstance(node, tuple):
            keys = [key for key, _ in node]
            if len(set(keys)) != len(keys):
                counts = Counter(keys)
                key = next(key for key in keys if counts[key] > 1)  # the first one written
                return DuplicateKey((*_path(entry), key), counts[key])
            items: Iterable[tuple[str | int, Any]] = node
        else:
            items = enumerate(node)
        children = [(v, entry, k) for k, v in items if isinstance(v, (tuple, list))]
        stack.extend(reversed(children))
    return None


def _path(entry: tuple[Any, Any, str | int | None]) -> Loc:
    keys: list[str | int] = []
    while entry[1] is not None:
        keys.append(entry[2])  # type: ignore[arg-type]  # set for every child
        entry = entry[1]
    return tuple(reversed(keys))
