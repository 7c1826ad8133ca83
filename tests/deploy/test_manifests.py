"""deploy/ is valid Kubernetes (strict schemas, offline) and says what the issue promises:
probes, resources, the restricted security context, graceful draining, Service, HPA, PDB."""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
import yaml

from arcspline.settings import Settings

DEPLOY = Path(__file__).resolve().parents[2] / "deploy"
Validate = Callable[..., str]  # the `validate` fixture (conftest.py)
# Oldest Kubernetes the manifests target (lifecycle.preStop.sleep is on by default from 1.30)
# and the newest whose schemas kubernetes-validate ships.
K8S_VERSIONS = ("1.30.0", "1.37.0")
MANIFESTS = sorted(p for p in DEPLOY.glob("*.yaml") if p.name != "kustomization.yaml")
KINDS = {"Deployment", "Service", "HorizontalPodAutoscaler", "PodDisruptionBudget"}


def cpu(quantity: str | int | float) -> float:
    text = str(quantity)
    return float(text[:-1]) / 1000 if text.endswith("m") else float(text)


def memory(quantity: str | int) -> int:
    units = {"Ki": 2**10, "Mi": 2**20, "Gi": 2**30, "k": 10**3, "M": 10**6, "G": 10**9}
    match = re.fullmatch(r"(\d+)([A-Za-z]*)", str(quantity))
    assert match, f"unexpected memory quantity {quantity!r}"
    return int(match[1]) * units.get(match[2], 1)


def env_of(container: dict[str, Any]) -> dict[str, str]:
    return {e["name"]: e["value"] for e in container.get("env", [])}


def matches(selector: dict[str, Any], labels: dict[str, str]) -> bool:
    assert set(selector) <= {"matchLabels"}, "only matchLabels selectors are checked here"
    return all(labels.get(k) == v for k, v in selector["matchLabels"].items())


# --- schema validation ------------------------------------------------------------------------


def test_manifest_set_is_what_the_kustomization_lists() -> None:
    kustomization = yaml.safe_load((DEPLOY / "kustomization.yaml").read_text())
    assert sorted(kustomization["resources"]) == [p.name for p in MANIFESTS]


@pytest.mark.parametrize("version", K8S_VERSIONS)
@pytest.mark.parametrize("manifest", MANIFESTS, ids=lambda p: p.name)
def test_each_manifest_validates_strictly(validate: Validate, manifest: Path, version: str) -> None:
    out = validate(manifest, version=version)
    assert out.count(" passed for resource ") == 1, out


@pytest.mark.parametrize("version", K8S_VERSIONS)
def test_kustomize_output_validates_strictly(
    validate: Validate, rendered_text: str, tmp_path: Path, version: str
) -> None:
    path = tmp_path / "rendered.yaml"
    path.write_text(rendered_text)
    out = validate(path, version=version)
    assert out.count(" passed for resource ") == len(KINDS), out


def test_kustomize_renders_each_kind_once(rendered: dict[str, dict[str, Any]]) -> None:
    assert set(rendered) == KINDS
    for obj in rendered.values():
        assert obj["metadata"]["labels"]["app.kubernetes.io/part-of"] == "arcspline"


@pytest.mark.parametrize(
    ("old", "new"),
    [
        ("readOnlyRootFilesystem: true", "readOnlyRootFilesytem: true"),  # unknown field
        ("memory: 512Mi", "memory: [512Mi]"),  # wrong type
        ("apiVersion: apps/v1", "apiVersion: apps/v1beta9"),  # no such schema: only a WARN
    ],
    ids=["unknown-field", "wrong-type", "unknown-api-version"],
)
def test_the_validation_catches_broken_manifests(
    validate: Validate, tmp_path: Path, old: str, new: str
) -> None:
    text = (DEPLOY / "deployment.yaml").read_text()
    assert old in text
    broken = tmp_path / "deployment.yaml"
    broken.write_text(text.replace(old, new, 1))
    with pytest.raises(AssertionError):
        validate(broken, version=K8S_VERSIONS[-1])


# --- the Deployment ---------------------------------------------------------------------------


def test_selector_matches_the_pod_template(deployment: dict[str, Any]) -> None:
    labels = deployment["spec"]["template"]["metadata"]["labels"]
    assert matches(deployment["spec"]["selector"], labels)


def test_no_fixed_replica_count_the_hpa_owns_it(deployment: dict[str, Any]) -> None:
    assert "replicas" not in deployment["spec"]
    rolling = deployment["spec"]["strategy"]["rollingUpdate"]
    assert rolling["maxUnavailable"] == 0, "rollouts never drop below the current capacity"


def test_probes(container: dict[str, Any]) -> None:
    port_names = {p["name"] for p in container["ports"]}
    port_numbers = {p["containerPort"] for p in container["ports"]}
    expected = {
        "readinessProbe": "/readyz",
        "livenessProbe": "/healthz",
        "startupProbe": "/healthz",
    }
    for probe, path in expected.items():
        get = container[probe]["httpGet"]
        assert get["path"] == path, probe
        assert get["port"] in port_names | port_numbers, probe
    # The startup probe gives a slow start (pool spawning) a minute before liveness kicks in.
    startup = container["startupProbe"]
    assert startup["periodSeconds"] * startup["failureThreshold"] >= 60


def test_resources(container: dict[str, Any]) -> None:
    requests, limits = container["resources"]["requests"], container["resources"]["limits"]
    assert 0 < cpu(requests["cpu"]) <= cpu(limits["cpu"])
    assert 0 < memory(requests["memory"]) <= memory(limits["memory"])
    # numpy plus one interpreter per pool worker: less than this cannot hold the pool.
    assert memory(limits["memory"]) >= 256 * 2**20


def test_pool_size_matches_the_cpu_limit(container: dict[str, Any]) -> None:
    # Inside a container the affinity mask shows the node's CPUs, not the quota: the default
    # pool size would overshoot, so the Deployment sets it to the limit.
    limit = cpu(container["resources"]["limits"]["cpu"])
    assert int(env_of(container)["ARCSPLINE_POOL_SIZE"]) == math.ceil(limit)


def test_environment_holds_only_known_settings(container: dict[str, Any]) -> None:
    # The service warns at start of an unknown ARCSPLINE_ variable (a typo, ignored).
    known = {"ARCSPLINE_" + name.upper() for name in Settings.model_fields}
    assert set(env_of(container)) <= known
    assert "command" not in container, "the image's CMD (one server process) stays in force"


def test_no_service_links_in_the_environment(pod_spec: dict[str, Any]) -> None:
    # A Service named arcspline would otherwise put ARCSPLINE_PORT=tcp://… and
    # ARCSPLINE_SERVICE_HOST into the pod (the service ignores them, settings.py).
    assert pod_spec["enableServiceLinks"] is False


def test_restricted_security_context(pod_spec: dict[str, Any], container: dict[str, Any]) -> None:
    pod = pod_spec["securityContext"]
    ctr = container["securityContext"]
    assert pod["runAsNonRoot"] is True
    assert isinstance(pod["runAsUser"], int)
    assert pod["runAsUser"] > 0
    assert pod["seccompProfile"] == {"type": "RuntimeDefault"}
    assert ctr["allowPrivilegeEscalation"] is False
    assert ctr["capabilities"] == {"drop": ["ALL"]}
    assert ctr["readOnlyRootFilesystem"] is True
    assert ctr.get("runAsNonRoot", True) is True
    assert ctr.get("runAsUser", pod["runAsUser"]) == pod["runAsUser"]
    assert ctr.get("seccompProfile", pod["seccompProfile"]) == {"type": "RuntimeDefault"}
    assert not ctr.get("privileged", False)
    assert pod_spec.get("automountServiceAccountToken") is False


def test_tmp_is_a_writable_empty_dir(pod_spec: dict[str, Any], container: dict[str, Any]) -> None:
    mounts = {m["mountPath"]: m for m in container["volumeMounts"]}
    assert "/tmp" in mounts, "read-only root: the worker pool needs a writable /tmp"
    assert not mounts["/tmp"].get("readOnly", False)
    volumes = {v["name"]: v for v in pod_spec["volumes"]}
    assert "emptyDir" in volumes[mounts["/tmp"]["name"]]


def test_shutdown_drains_in_flight_work(
    pod_spec: dict[str, Any], container: dict[str, Any]
) -> None:
    pre_stop = container["lifecycle"]["preStop"]
    if "sleep" in pre_stop:
        pause = pre_stop["sleep"]["seconds"]
    else:  # exec of a python sleep (no `sleep` binary needed)
        command = " ".join(pre_stop["exec"]["command"])
        pause = int(re.search(r"sleep\((\d+)\)", command)[1])  # type: ignore[index]
    assert pause >= 3, "endpoints need a few seconds to stop routing to the pod"
    drain = float(
        env_of(container).get(
            "ARCSPLINE_DRAIN_TIMEOUT_S", Settings.model_fields["drain_timeout_s"].default
        )
    )
    # Kubernetes sends SIGTERM after preStop; the grace period covers both, with a margin.
    assert pod_spec["terminationGracePeriodSeconds"] >= pause + drain + 5


def test_image_is_set_by_the_kustomization(container: dict[str, Any]) -> None:
    assert re.fullmatch(r"[\w./:-]*arcspline:[\w.-]+", container["image"]), container["image"]
    assert container["imagePullPolicy"] in {"IfNotPresent", "Always"}


# --- Service, HPA, PDB ------------------------------------------------------------------------


def test_service_routes_to_the_pods(
    rendered: dict[str, dict[str, Any]], deployment: dict[str, Any], container: dict[str, Any]
) -> None:
    service = rendered["Service"]
    labels = deployment["spec"]["template"]["metadata"]["labels"]
    assert service["spec"]["selector"].items() <= labels.items()
    named = {p["name"]: p["containerPort"] for p in container["ports"]}
    for port in service["spec"]["ports"]:
        target = port["targetPort"]
        assert target in named or target in named.values(), target


def test_hpa_scales_the_deployment_on_cpu(
    rendered: dict[str, dict[str, Any]], deployment: dict[str, Any], container: dict[str, Any]
) -> None:
    hpa = rendered["HorizontalPodAutoscaler"]
    assert hpa["apiVersion"] == "autoscaling/v2"
    target = hpa["spec"]["scaleTargetRef"]
    assert (target["apiVersion"], target["kind"], target["name"]) == (
        deployment["apiVersion"],
        "Deployment",
        deployment["metadata"]["name"],
    )
    assert 2 <= hpa["spec"]["minReplicas"] < hpa["spec"]["maxReplicas"]
    cpu_metrics = [
        m["resource"]["target"]
        for m in hpa["spec"]["metrics"]
        if m["type"] == "Resource" and m["resource"]["name"] == "cpu"
    ]
    assert cpu_metrics
    assert cpu_metrics[0]["type"] == "Utilization"
    assert 0 < cpu_metrics[0]["averageUtilization"] <= 100
    assert "cpu" in container["resources"]["requests"], "utilization is relative to requests"


def test_pdb_protects_the_pods_without_blocking_drains(
    rendered: dict[str, dict[str, Any]], deployment: dict[str, Any]
) -> None:
    pdb, hpa = rendered["PodDisruptionBudget"], rendered["HorizontalPodAutoscaler"]
    assert pdb["apiVersion"] == "policy/v1"
    labels = deployment["spec"]["template"]["metadata"]["labels"]
    assert matches(pdb["spec"]["selector"], labels)
    spec = pdb["spec"]
    if "maxUnavailable" in spec:
        assert 1 <= spec["maxUnavailable"] < hpa["spec"]["minReplicas"]
    else:
        assert 1 <= spec["minAvailable"] < hpa["spec"]["minReplicas"]
