"""``python -m arcspline [--host H] [--port P]``: serve the API with uvicorn (``arcspline
serve`` is the same :func:`serve`).

One uvicorn process (the approximation itself runs in the worker pool) on uvloop and
httptools, its connections bounded by :mod:`arcspline.serving.protocol` (header size and
time, body time, a connection cap under the open-file limit, which is raised to the hard
limit), without an access log unless ``ARCSPLINE_ACCESS_LOG=true``. SIGTERM or SIGINT
stops accepting connections, lets in-flight requests finish (up to
``ARCSPLINE_DRAIN_TIMEOUT_S``), stops the workers and exits 0.
"""

from __future__ import annotations

import argparse
import gc
import signal
from types import FrameType
from typing import Any


def log_config(level: str) -> dict[str, Any]:
    """Uvicorn's loggers and ours, each line tagged with the request id."""
    fmt = "%(asctime)s %(levelname)s %(name)s [%(correlation_id)s] %(message)s"
    return {
        "version": 1,
        "disable_existing_loggers": False,
        "filters": {
            "request_id": {
                "()": "asgi_correlation_id.CorrelationIdFilter",
                "uuid_length": 32,
                "default_value": "-",
            }
        },
        "formatters": {"default": {"format": fmt}},
        "handlers": {
            "default": {
                "class": "logging.StreamHandler",
                "formatter": "default",
                "filters": ["request_id"],
                "stream": "ext://sys.stderr",
            }
        },
        "loggers": {
            "": {"handlers": ["default"], "level": level.upper()},
            "uvicorn": {"handlers": [], "level": level.upper(), "propagate": True},
            "uvicorn.error": {"handlers": [], "level": level.upper(), "propagate": True},
            "uvicorn.access": {"handlers": [], "level": level.upper(), "propagate": True},
        },
    }


#: The server process's collector thresholds. With CPython's default (700, 10, 10) a young
#: collection runs every ~1.5 requests and walks every object that the requests waiting on
#: the pool hold; measured over HTTP (wrk, pool of 2, paper spiral at 1e-3), these give
#: ``POST /v1/approximate`` 10–25 % more requests/s and leave ``GET /healthz`` unchanged.
#: Memory is not at stake: reference counting frees almost everything, and the cycles left
#: (exceptions with their tracebacks) wait at most 50 000 allocations.
GC_THRESHOLDS = (50_000, 20, 100)

#: Seconds uvicorn waits past the drain for the requests the app has cut to finish answering.
DRAIN_BACKSTOP_S = 5


def tune_gc() -> None:
    """Collect less often in the server process (the workers keep the defaults)."""
    gc.set_threshold(*GC_THRESHOLDS)


def _exit_cleanly(signum: int, frame: FrameType | None) -> None:
    raise SystemExit(0)


def serve(host: str | None = None, port: int | None = None) -> None:
    """Serve the API until SIGTERM or SIGINT, with the settings of the environment
    (``ARCSPLINE_*``); ``host`` and ``port`` override theirs. ``python -m arcspline`` and
    ``arcspline serve`` both come here, so they serve alike."""
    import uvicorn

    from arcspline.serving.descriptors import connection_cap, raise_nofile_limit
    from arcspline.serving.protocol import ConnectionLimits, bounded_protocol
    from arcspline.settings import get_settings

    settings = get_settings()
    limits = ConnectionLimits(
        max_connections=connection_cap(
            settings.max_connections, raise_nofile_limit(), settings.pool_size
        ),
        max_header_bytes=settings.max_header_bytes,
        header_timeout_s=settings.header_timeout_s,
        body_timeout_s=settings.body_timeout_s,
        send_timeout_s=settings.send_timeout_s,
        retry_after_s=settings.retry_after_s,
    )
    # Uvicorn drains on SIGTERM, then raises the signal again under the handler it found at
    # start, so that the exit status says "terminated". A drained server has nothing to
    # report: with this handler it exits 0.
    signal.signal(signal.SIGTERM, _exit_cleanly)
    tune_gc()
    uvicorn.run(
        "arcspline.api.app:create_app",
        factory=True,
        host=settings.host if host is None else host,
        port=settings.port if port is None else port,
        loop="uvloop",
        http=bounded_protocol(limits),
        timeout_keep_alive=settings.keep_alive_timeout_s,
        lifespan="on",
        access_log=settings.access_log,
        log_level=settings.log_level,
        log_config=log_config(settings.log_level),
        # The app ends the drain itself at drain_timeout_s (api/lifecycle.py), answering 503;
        # uvicorn's own cut (an ERROR line, text/plain 500s) is only a backstop.
        timeout_graceful_shutdown=settings.drain_timeout_s + DRAIN_BACKSTOP_S,
        server_header=False,
    )


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="python -m arcspline", description=__doc__)
    parser.add_argument("--host", help="address (default: ARCSPLINE_HOST, else 127.0.0.1)")
    parser.add_argument("--port", type=int, help="port (default: ARCSPLINE_PORT, else 8000)")
    args = parser.parse_args(argv)
    serve(args.host, args.port)


if __name__ == "__main__":
    main()
