"""Raw sockets to talk to a real server (``tests.support.server.running_server``): the
attacks of the connection tests are not HTTP that a client library would send."""

from __future__ import annotations

import socket
from typing import Any

import orjson

from tests.support.processes import memory_kib
from tests.support.server import Server

#: Hang guard of every socket read: far beyond any answer's time.
READ_TIMEOUT_S = 30.0


def connect(server: Server) -> socket.socket:
    host, port = server.url.removeprefix("http://").split(":")
    return socket.create_connection((host, int(port)), timeout=READ_TIMEOUT_S)


def read_until_closed(sock: socket.socket) -> bytes:
    """Everything the server sends until it closes the connection (a reset counts as
    closed: what arrived before it is kept)."""
    chunks = []
    while True:
        try:
            chunk = sock.recv(65536)
        except ConnectionResetError:
            break
        if not chunk:
            break
        chunks.append(chunk)
    return b"".join(chunks)


def parse_response(raw: bytes) -> tuple[int, dict[str, str], bytes]:
    """Status, headers (lower-case names) and body of one HTTP/1.1 response."""
    head, _, body = raw.partition(b"\r\n\r\n")
    lines = head.decode("latin-1").split("\r\n")
    status = int(lines[0].split()[1])
    headers = {}
    for line in lines[1:]:
        name, _, value = line.partition(":")
        headers[name.strip().lower()] = value.strip()
    return status, headers, body


def problem_of(raw: bytes) -> tuple[int, dict[str, str], dict[str, Any]]:
    """A problem response: status, headers and its parsed body (asserted to be one)."""
    status, headers, body = parse_response(raw)
    assert headers.get("content-type") == "application/problem+json", raw[:300]
    parsed: dict[str, Any] = orjson.loads(body)
    assert parsed["status"] == status
    return status, headers, parsed


def vm_kib(pid: int, field: str) -> int:
    """``VmRSS`` or ``VmHWM`` (peak) of a live process, in KiB."""
    kib = memory_kib(pid, field)
    assert kib is not None, f"no {field} for {pid}"
    return kib
