"""The worker processes of a running server, read from /proc (for tests and benchmarks)."""

from __future__ import annotations

from pathlib import Path


def parents() -> dict[int, int]:
    """pid -> parent pid of every process."""
    found = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:
                continue
            # The command name may hold spaces; fields after its closing parenthesis do not.
            found[int(entry.name)] = int(stat.rsplit(")", 1)[1].split()[1])
    return found


def worker_pids(server_pid: int) -> list[int]:
    """The pool's workers: children of the forkserver, itself a child of the server."""
    known = parents()
    children = {pid for pid, parent in known.items() if parent == server_pid}
    return sorted(pid for pid, parent in known.items() if parent in children)
