"""What the connections' bounds refused, by problem kind (``serving/protocol.py``), for the
app's ``/metrics`` (``arcspline_connections_refused_total``). The protocol exists before the
app and outside it, so the count is the serving process's own, kept here."""

from __future__ import annotations

from collections import Counter

#: The problem kinds a connection may be refused with, and ``send_timeout`` (dropped, an
#: answer left unread: nothing can be answered then).
KINDS = (
    "headers_too_large",
    "request_timeout",
    "malformed_http",
    "too_many_connections",
    "send_timeout",
)

REFUSED: Counter[str] = Counter(dict.fromkeys(KINDS, 0))


def refuse(kind: str) -> None:
    """Count one connection refused (or dropped) as ``kind``."""
    REFUSED[kind] += 1
