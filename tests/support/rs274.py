"""Running LinuxCNC's stand-alone interpreter ``rs274`` on a program, and reading its verdict.

``rs274 -g`` interprets a whole program and prints the canonical machining commands it would
send (``STRAIGHT_FEED(...)``, ``ARC_FEED(...)``, ...). On an error it prints the message
and the offending line to stderr and, in its default "stop" mode, exits 1; in "continue" mode
(``-n 0``) it would print the same error and still exit 0. A program counts as accepted only
when all of these hold: exit code 0, nothing on stderr but the banner ``executing``, and a
``PROGRAM_END()`` in the canonical output.
"""

from __future__ import annotations

import re
import subprocess
import tempfile
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

import pytest

#: LinuxCNC's strictest arc check: start and end radius may differ by at most 0.001 mm
#: (unless by under 0.1 %); the inch setting's floor is 0.00004".
TIGHT_INI = """[RS274NGC]
CENTER_ARC_RADIUS_TOLERANCE_MM = 0.001
CENTER_ARC_RADIUS_TOLERANCE_INCH = 0.00004
"""
TOOL_TABLE = "T1 P1 D0.125 Z0 ;\n"
_CANON = re.compile(r"^\s*\d+\s+N(?:\.+|\d+)\s+([A-Z_]+)\((.*)\)\s*$")


@dataclass(frozen=True)
class Canon:
    """One canonical command: its name and its arguments as text."""

    name: str
    args: tuple[str, ...]

    def numbers(self) -> tuple[float, ...]:
        return tuple(float(a) for a in self.args)


@dataclass(frozen=True)
class Verdict:
    """What ``rs274`` made of one program."""

    returncode: int
    stdout: str
    stderr: str

    @property
    def errors(self) -> list[str]:
        return [line for line in self.stderr.splitlines() if line.strip() not in ("", "executing")]

    @property
    def canon(self) -> list[Canon]:
        found = []
        for line in self.stdout.splitlines():
            match = _CANON.match(line)
            if match:
                args = tuple(a.strip() for a in match.group(2).split(",")) if match.group(2) else ()
                found.append(Canon(match.group(1), args))
        return found

    @property
    def accepted(self) -> bool:
        return (
            self.returncode == 0
            and not self.errors
            and any(c.name == "PROGRAM_END" for c in self.canon)
        )

    def describe(self) -> str:
        tail = "\n".join(self.stdout.splitlines()[-5:])
        return f"exit {self.returncode}; stderr:\n{self.stderr}\nlast output:\n{tail}"


class Rs274:
    """The interpreter unpacked under ``root`` (see ``scripts/fetch-rs274.sh``)."""

    def __init__(self, root: Path) -> None:
        self.root = root.resolve()
        libs = [self.root / "usr" / "lib", self.root / "usr" / "lib" / "x86_64-linux-gnu"]
        self._library_path = ":".join(str(p) for p in libs)

    def run(self, program: str, *, continue_on_error: bool = False) -> Verdict:
        """Interpret ``program`` in batch mode; ``continue_on_error`` is rs274's ``-n 0``."""
        with tempfile.TemporaryDirectory(prefix="rs274-") as scratch:
            home = Path(scratch)
            (home / "tight.ini").write_text(TIGHT_INI)
            (home / "tool.tbl").write_text(TOOL_TABLE)
            (home / "prog.ngc").write_text(program)
            mode = ["-n", "0"] if continue_on_error else []
            done = subprocess.run(
                [
                    str(self.root / "usr" / "bin" / "rs274"),
                    *mode,
                    "-i",
                    "tight.ini",
                    "-t",
                    "tool.tbl",
                    "-g",
                    "prog.ngc",
                ],
                cwd=home,
                env={
                    "HOME": str(home),
                    "LD_LIBRARY_PATH": self._library_path,
                    "PATH": "/usr/bin:/bin",
                },
                capture_output=True,
                text=True,
                timeout=60,
                check=False,
            )
        return Verdict(done.returncode, done.stdout, done.stderr)


#: ``scripts/fetch-rs274.sh``'s exit status when this machine cannot fetch the interpreter
#: (not Debian or Ubuntu, no such package, no network): as opposed to 1, something broken.
UNAVAILABLE_STATUS = 2


def provide(script: Path, *, ci: bool, env: Mapping[str, str] | None = None) -> Rs274:
    """The interpreter that ``script`` fetches (or finds cached). Where this machine cannot
    fetch it, the tests that need it skip, saying why, except in CI (``ci``), where that is
    a failure as much as anything else that goes wrong."""
    done = subprocess.run(
        ["bash", str(script)],
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
        env=None if env is None else dict(env),
    )
    if done.returncode == 0:
        return Rs274(Path(done.stdout.strip().splitlines()[-1]))
    reason = done.stderr.strip().splitlines()[-1] if done.stderr.strip() else "no message"
    if done.returncode == UNAVAILABLE_STATUS and not ci:
        pytest.skip(f"rs274 cannot be fetched on this machine ({reason}); in CI this fails")
    pytest.fail(f"{script.name} could not provide rs274:\n{done.stderr}", pytrace=False)
