"""The connection cap, from the process's file-descriptor limit (docs/deployment.md,
"Connections").

Every accepted connection holds a descriptor; so do the listening socket, the event loop, the
log, the worker pool's pipes and sockets and the files a request opens. Past the limit
``accept`` fails (EMFILE) and new clients wait unanswered in the listen backlog, so the cap
stays below the limit by a reserve for everything that is not a client.
"""

from __future__ import annotations

import logging
import resource

log = logging.getLogger(__name__)

#: Descriptors the serving process holds besides its clients: listening socket, event loop,
#: signal pipes, standard streams, the forkserver, logs and files opened per request.
RESERVED_FDS = 64
#: Descriptors per worker process held in the serving process (its task and result pipes,
#: its sentinel, the pool's wake-up pipes), with room to spare for a worker being replaced.
RESERVED_FDS_PER_WORKER = 8
#: Whatever the hard limit, the soft limit is raised no further than this (the kernel's
#: default ``nr_open``): an "unlimited" hard limit cannot be set as a soft one.
MAX_NOFILE = 1 << 20


def raise_nofile_limit() -> int:
    """Raise the soft RLIMIT_NOFILE to the hard limit (containerd sets soft 1024 under a far
    higher hard limit); return the soft limit now in force."""
    soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    target = MAX_NOFILE if hard == resource.RLIM_INFINITY else min(hard, MAX_NOFILE)
    if soft != resource.RLIM_INFINITY and soft < target:
        try:
            resource.setrlimit(resource.RLIMIT_NOFILE, (target, hard))
            soft = target
        except (ValueError, OSError) as error:  # pragma: no cover - a kernel below MAX_NOFILE
            log.warning("cannot raise the open-file limit from %d to %d: %s", soft, target, error)
    return soft


def connection_cap(max_connections: int, nofile: int, pool_size: int) -> int:
    """Most client connections open at once: ``max_connections``, but never within
    ``RESERVED_FDS + RESERVED_FDS_PER_WORKER × pool_size`` descriptors of ``nofile``."""
    reserve = RESERVED_FDS + RESERVED_FDS_PER_WORKER * pool_size
    return max(1, min(max_connections, nofile - reserve))
