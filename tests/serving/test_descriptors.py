"""The connection cap under the open-file limit (serving/descriptors.py)."""

from __future__ import annotations

import resource
import subprocess
import sys

from arcspline.serving.descriptors import (
    RESERVED_FDS,
    RESERVED_FDS_PER_WORKER,
    connection_cap,
)


def test_the_cap_leaves_the_reserve_below_the_limit() -> None:
    reserve = RESERVED_FDS + 2 * RESERVED_FDS_PER_WORKER
    assert connection_cap(4096, 1024, pool_size=2) == 1024 - reserve
    assert connection_cap(4096, 1 << 20, pool_size=2) == 4096
    assert connection_cap(100, 1024, pool_size=2) == 100
    assert connection_cap(4096, reserve, pool_size=2) == 1


def test_the_soft_limit_is_raised_to_the_hard_limit() -> None:
    """In a child whose soft limit is 256 under a hard one of 512 (containerd sets soft 1024
    under a far higher hard limit)."""
    code = (
        "import resource; from arcspline.serving.descriptors import raise_nofile_limit; "
        "print(raise_nofile_limit(), *resource.getrlimit(resource.RLIMIT_NOFILE))"
    )

    def lower() -> None:
        resource.setrlimit(resource.RLIMIT_NOFILE, (256, 512))

    done = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        check=True,
        preexec_fn=lower,
    )
    assert done.stdout.split() == ["512", "512", "512"]
