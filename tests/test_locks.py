"""The lock files agree: the service (runtime.lock: ``make run``, the image) runs the very
versions the tests ran with (dev.lock)."""

from __future__ import annotations

from pathlib import Path

LOCKS = Path(__file__).resolve().parents[1] / "requirements"


def pins(lock: Path) -> dict[str, str]:
    """``name → version`` of a lock file's ``name==version`` lines."""
    result = {}
    for line in lock.read_text().splitlines():
        requirement = line.split("#", 1)[0].strip()
        if "==" in requirement:
            name, version = requirement.split("==", 1)
            result[name.strip().lower()] = version.strip()
    return result


def test_every_runtime_pin_is_the_dev_locks_version() -> None:
    runtime, dev = pins(LOCKS / "runtime.lock"), pins(LOCKS / "dev.lock")
    assert runtime, "runtime.lock pins nothing"
    differing = {name: (v, dev.get(name)) for name, v in runtime.items() if dev.get(name) != v}
    assert not differing, f"runtime.lock vs dev.lock: {differing}"
