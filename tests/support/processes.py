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


def memory_kib(pid: int, field: str) -> int | None:
    """A memory figure of a process in KiB, ``None`` once it is gone: ``VmRSS``, ``VmHWM``
    (the peak RSS) from ``/proc/<pid>/status``, or ``Pss`` (its shared pages split among
    their processes, as a memory cgroup charges them) from ``/proc/<pid>/smaps_rollup``."""
    source = "smaps_rollup" if field == "Pss" else "status"
    try:
        lines = Path(f"/proc/{pid}/{source}").read_text().splitlines()
    except OSError:
        return None
    for line in lines:
        if line.startswith(field + ":"):
            return int(line.split()[1])
    return None
