"""Small single jobs computed in the serving process, without the trip to a worker
(docs/performance.md "Small requests fast (issue 19)").

A worker round trip (pickle, socket, wake-up, answer) costs a lone request more than the
paper's spiral at 1e-3 takes to compute (tens of microseconds), so, when
``inline_max_segments`` is set (off by default), a single ``/v1/approximate`` job that is
provably tiny runs on the event loop. Provably: the core
runs it with ``max_segments`` lowered to ``inline_max_segments``, and the subdivision stops
as soon as the segments kept plus those pending would pass that count (fit/subdivide.pyx),
so the work is bounded by the count before it starts; a job that would pass it is refused
by the core there and goes to the pool with the configured limits. Below the count the
subdivision runs step for step as with the configured limits (the limit only stops it), so
every answer and every error is the one the pool gives, byte for byte.

Only a share of the serving process's time (:data:`SHARE`) goes to inline jobs: under load
that process is itself the bottleneck, and a job that shares a worker task with others (see
``Coalescer``) costs it less than computing the job here (measured: always inline, wrk at
32 connections answered 0.47× /healthz against 0.64× through the pool). The fast path cuts
the latency of requests that come one at a time, not the cost of many.

What stays in the pool: other strategies (``fewest-arcs``, whose search costs more a segment)
and jobs with outputs (the G-code writer alone takes milliseconds), whose cost is not
bounded by the segment count cheaply.
"""

from __future__ import annotations

import time
from functools import lru_cache

from arcspline.geometry import GeometryError, Limits
from arcspline.settings import Settings
from arcspline.worker.jobs import Job, JobResult, approximate_one
from arcspline.worker.pool import WorkerPool

#: The strategies whose work is bounded by the segment count (one biarc per step).
INLINE_STRATEGIES = frozenset({"subdivide"})
#: Below this job time limit nothing runs inline: an inline job cannot be stopped, and its
#: bound (about a millisecond at the default count, docs/performance.md) must sit far
#: inside the limit it is exempt from.
MIN_TIME_LIMIT_S = 0.1
#: The share of the serving process's time that inline jobs may take, and the most they may
#: take at once after a quiet spell (a token bucket, in seconds of computing).
SHARE = 0.1
BURST_S = 0.005


class Allowance:
    """A token bucket of computing time: refilled at ``share`` of the time that passes, up to
    ``burst_s``; a job may start while it is not empty, and takes what it used."""

    def __init__(
        self, share: float = SHARE, burst_s: float = BURST_S, now: float | None = None
    ) -> None:
        self.share, self.burst_s = share, burst_s
        self.left_s = burst_s
        self._at = time.perf_counter() if now is None else now

    def open(self, now: float) -> bool:
        """Whether a job may start at ``now`` (``time.perf_counter``)."""
        self.left_s = min(self.burst_s, self.left_s + (now - self._at) * self.share)
        self._at = now
        return self.left_s > 0.0

    def take(self, used_s: float) -> None:
        self.left_s -= used_s


@lru_cache(maxsize=16)
def inline_limits(settings: Settings) -> Limits | None:
    """The core's limits for an inline job, or ``None`` when the fast path is off."""
    count = min(settings.inline_max_segments, settings.max_segments)
    if count == 0 or settings.job_time_limit_s < MIN_TIME_LIMIT_S:
        return None
    return Limits(max_segments=count, min_relative_tolerance=settings.min_relative_tolerance)


def is_inline_candidate(job: Job) -> bool:
    """Whether ``job``'s cost is bounded by its segment count alone."""
    return not job.outputs and job.strategy in INLINE_STRATEGIES


def run_inline(
    job: Job, settings: Settings, pool: WorkerPool, allowance: Allowance
) -> JobResult | None:
    """``job``'s result computed here, or ``None`` to send it to the pool: if it is not
    provably tiny, or inline jobs have taken their share of late (``allowance``: the app's,
    ``Runtime.inline_allowance``). Admitted by ``pool`` as a pool job is, so a full queue
    or a stopped service answers as it would (503)."""
    limits = inline_limits(settings)
    if limits is None or not is_inline_candidate(job):
        return None
    began = time.perf_counter()
    if not allowance.open(began):
        return None  # under load: the pool's coalesced tasks cost this process less
    with pool.admit():
        result = approximate_one(job, limits)
    allowance.take(time.perf_counter() - began)
    if (
        isinstance(result, GeometryError)
        and result.kind == "segment_limit"
        and limits.max_segments < settings.max_segments
    ):
        return None  # over the inline count, not over the configured limit
    return result
