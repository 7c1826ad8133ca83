"""Duplicate keys in a JSON body: found, and where (``api/duplicates.py``)."""

from __future__ import annotations

import json

import pytest

from arcspline.api.duplicates import DuplicateKey, first_duplicate, has_duplicate


@pytest.mark.parametrize(
    ("raw", "found"),
    [
        (b'{"a": 1, "b": {"a": 1}, "c": [{"a": 1}, {"a": 2}]}', None),
        (b'{"a": 1, "a": 1}', DuplicateKey(("a",), 2)),
        (b'[0, {"x": [{"y": 1, "z": 0, "y": 2, "y": 3}]}]', DuplicateKey((1, "x", 0, "y"), 3)),
        # The first in document order: the outer object's key comes before the inner one's.
        (b'{"k": {"i": 1, "i": 2}, "k": 0}', DuplicateKey(("k",), 2)),
        (b'{"p": {"q": 1}, "r": {"s": 1, "t": 2, "s": 3}}', DuplicateKey(("r", "s"), 2)),
    ],
)
def test_the_first_key_named_twice_and_its_path(raw: bytes, found: DuplicateKey | None) -> None:
    assert has_duplicate(raw) is (found is not None)
    if found is not None:
        assert first_duplicate(raw) == found


def test_a_deep_body_is_searched_without_recursion() -> None:
    depth = 900
    raw = '{"a": ' * depth + '{"k": 1, "k": 2}' + "}" * depth
    assert first_duplicate(raw.encode()) == DuplicateKey(("a",) * depth + ("k",), 2)
    assert json.loads(raw)  # (the body is JSON)


@pytest.mark.parametrize(
    "raw",
    [b"{", b'{"a": 1,}', b"\xff\xfe{}", b"[" * 100_000 + b"]" * 100_000],
)
def test_a_body_that_is_not_json_is_left_to_pydantic(raw: bytes) -> None:
    assert not has_duplicate(raw)


def test_a_body_malformed_after_a_duplicate_is_left_to_pydantic() -> None:
    raw = b'{"k": 1, "k": 2} x'
    assert has_duplicate(raw)  # seen before the end
    assert first_duplicate(raw) is None
