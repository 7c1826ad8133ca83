"""The Dockerfile keeps the container contract the Deployment and the README rely on.

Offline and static: building and running the image is `make image-test`'s job."""

from __future__ import annotations

import json
import re
import subprocess
from pathlib import Path
from typing import Any

import yaml

ROOT = Path(__file__).resolve().parents[2]
Instructions = list[tuple[str, str]]


def stages(dockerfile: Instructions) -> list[Instructions]:
    out: list[Instructions] = []
    for keyword, args in dockerfile:
        if keyword == "FROM":
            out.append([])
        if out:
            out[-1].append((keyword, args))
    return out


def last(instructions: Instructions, keyword: str) -> str:
    values = [args for kw, args in instructions if kw == keyword]
    assert values, f"no {keyword}"
    return values[-1]


def test_multi_stage_from_debian_bookworm_slim(dockerfile: Instructions) -> None:
    args = dict(a.split("=", 1) for kw, a in dockerfile if kw == "ARG" and "=" in a)
    froms = [a.split()[0] for kw, a in dockerfile if kw == "FROM"]
    first = re.sub(r"\$\{(\w+)\}", lambda m: args[m[1]], froms[0])
    assert first == "debian:bookworm-slim"
    assert len(froms) >= 2
    copies = [a for kw, a in stages(dockerfile)[-1] if kw == "COPY"]
    assert any(a.startswith("--from=") for a in copies), "the final stage copies the venv"


def test_runtime_stage_runs_as_a_numeric_non_root_user(
    dockerfile: Instructions, pod_spec: dict[str, Any]
) -> None:
    user, _, group = last(stages(dockerfile)[-1], "USER").partition(":")
    assert user.isdigit()
    assert int(user) > 0
    assert not group or group.isdigit()
    # The same uid as the Deployment's runAsUser, so file ownership and checks agree.
    assert int(user) == pod_spec["securityContext"]["runAsUser"]


def test_cmd_is_one_server_process_in_exec_form(
    dockerfile: Instructions, container: dict[str, Any]
) -> None:
    runtime = stages(dockerfile)[-1]
    assert json.loads(last(runtime, "CMD")) == [
        "python",
        "-m",
        "arcspline",
        "--host",
        "0.0.0.0",
        "--port",
        "8000",
    ]
    assert not [kw for kw, _ in runtime if kw == "ENTRYPOINT"]
    assert last(runtime, "EXPOSE") == "8000"
    assert [p["containerPort"] for p in container["ports"]] == [8000]


def test_healthcheck_uses_the_standard_library(dockerfile: Instructions) -> None:
    health = last(stages(dockerfile)[-1], "HEALTHCHECK")
    _, _, command = health.partition(" CMD ")
    argv = json.loads(command)
    assert argv[:2] == ["python", "-c"]
    assert "urllib.request" in argv[2]
    assert "/healthz" in argv[2]


def test_read_only_root_filesystem_friendly(dockerfile: Instructions) -> None:
    env = " ".join(a for kw, a in dockerfile if kw == "ENV")
    assert "PYTHONDONTWRITEBYTECODE=1" in env


def test_downloads_can_use_a_proxy_ca_secret(dockerfile: Instructions) -> None:
    downloading = [a for kw, a in dockerfile if kw == "RUN" and re.search(r"\b(pip|apt-get)\b", a)]
    assert downloading
    for run in downloading:
        assert run.startswith("--mount=type=secret,id=ca "), run
        assert "if [ -s /run/secrets/ca ]" in run, "and it still builds without the secret"
        if re.search(r"\bpip install\b", run):
            assert "PIP_CERT=/run/secrets/ca" in run, run
        if "apt-get" in run:
            assert "Acquire::https::CAInfo=/run/secrets/ca" in run, run


def test_dockerignore_lets_in_what_the_build_copies() -> None:
    allowed = {
        line[1:].rstrip("/")
        for line in (ROOT / ".dockerignore").read_text().splitlines()
        if line.startswith("!")
    }
    needed = {"pyproject.toml", "setup.py", "requirements/runtime.lock", "requirements/build.lock"}
    assert {*needed, "service"} <= allowed


def test_image_script_is_valid_bash() -> None:
    for script in [ROOT / "scripts" / "image.sh"]:
        proc = subprocess.run(["bash", "-n", str(script)], capture_output=True, text=True)
        assert proc.returncode == 0, proc.stderr


def test_hadolint_config_says_why_apt_packages_are_not_pinned(dockerfile: Instructions) -> None:
    """DL3008 (pin apt versions) is ignored on purpose, and the file says why."""
    text = (ROOT / ".hadolint.yaml").read_text()
    assert yaml.safe_load(text)["ignored"] == ["DL3008"]
    reason = " ".join(line for line in text.splitlines() if line.lstrip().startswith("#"))
    assert "DL3008" in reason
    assert "security updates" in reason
    # The rule it silences is one the Dockerfile would break: unpinned apt packages.
    installs = [
        m[1]
        for kw, args in dockerfile
        if kw == "RUN"
        for m in re.finditer(r"apt-get \S+ install -y --no-install-recommends ([^;]+);", args)
    ]
    assert installs
    assert not [p for packages in installs for p in packages.split() if "=" in p]
