"""The one settings object: defaults, environment variables, refusals."""

from __future__ import annotations

import logging
import os

import pytest
from pydantic import ValidationError

from arcspline.geometry import DEFAULT_LIMITS, Limits
from arcspline.settings import Settings, available_cpus, get_settings


@pytest.fixture(autouse=True)
def _clean_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    for name in list(os.environ):
        if name.upper().startswith("ARCSPLINE_"):
            monkeypatch.delenv(name)


def test_defaults() -> None:
    settings = Settings()
    assert settings.pool_size == len(os.sched_getaffinity(0)) == available_cpus()
    assert settings.queue_capacity == 64
    assert settings.batch_max_jobs == 1000
    assert settings.max_body_bytes == 4 * 1024 * 1024
    assert settings.limits == DEFAULT_LIMITS
    assert settings.start_method == "forkserver"
    assert settings.access_log is False
    assert (settings.max_connections, settings.max_header_bytes) == (4096, 64 * 1024)
    assert (settings.header_timeout_s, settings.body_timeout_s) == (10.0, 60.0)
    assert settings.keep_alive_timeout_s == 5


def test_environment_variables_with_the_prefix_are_read(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ARCSPLINE_POOL_SIZE", "3")
    monkeypatch.setenv("ARCSPLINE_QUEUE_CAPACITY", "5")
    monkeypatch.setenv("ARCSPLINE_JOB_TIME_LIMIT_S", "0.5")
    monkeypatch.setenv("ARCSPLINE_MAX_SEGMENTS", "100")
    monkeypatch.setenv("ARCSPLINE_MIN_RELATIVE_TOLERANCE", "1e-8")
    monkeypatch.setenv("ARCSPLINE_LOG_LEVEL", "debug")
    settings = Settings()
    assert (settings.pool_size, settings.queue_capacity, settings.job_time_limit_s) == (3, 5, 0.5)
    assert settings.limits == Limits(max_segments=100, min_relative_tolerance=1e-8)
    assert settings.log_level == "debug"


@pytest.mark.parametrize(
    ("name", "value"),
    [
        ("ARCSPLINE_POOL_SIZE", "0"),
        ("ARCSPLINE_QUEUE_CAPACITY", "-1"),
        ("ARCSPLINE_JOB_TIME_LIMIT_S", "0"),
        ("ARCSPLINE_MAX_BODY_BYTES", "lots"),
        ("ARCSPLINE_LOG_LEVEL", "loud"),
        ("ARCSPLINE_START_METHOD", "fork"),
        ("ARCSPLINE_MAX_SEGMENTS", "3000000000"),
        ("ARCSPLINE_MIN_RELATIVE_TOLERANCE", "1"),
    ],
)
def test_bad_values_are_refused(monkeypatch: pytest.MonkeyPatch, name: str, value: str) -> None:
    monkeypatch.setenv(name, value)
    with pytest.raises(ValidationError, match=name.removeprefix("ARCSPLINE_").lower()):
        Settings()


def test_a_misspelt_variable_is_named_in_one_warning_and_does_not_stop_the_service(
    monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    monkeypatch.setenv("ARCSPLINE_POOL_SIZ", "3")
    monkeypatch.setenv("ARCSPLINE_NOT_A_SETTING", "1")
    with caplog.at_level(logging.DEBUG, logger="arcspline.settings"):
        settings = Settings()
    assert settings.pool_size == available_cpus()
    warnings = [r for r in caplog.records if r.levelno == logging.WARNING]
    assert len(warnings) == 1
    message = warnings[0].getMessage()
    assert "ARCSPLINE_NOT_A_SETTING" in message
    assert "ARCSPLINE_POOL_SIZ (did you mean ARCSPLINE_POOL_SIZE?)" in message


#: What Kubernetes puts in every pod's environment for a Service named ``arcspline`` with a
#: port 8000 named ``http`` (service links).
SERVICE_LINKS = {
    "ARCSPLINE_SERVICE_HOST": "10.0.0.1",
    "ARCSPLINE_SERVICE_PORT": "8000",
    "ARCSPLINE_SERVICE_PORT_HTTP": "8000",
    "ARCSPLINE_PORT": "tcp://10.0.0.1:8000",
    "ARCSPLINE_PORT_8000_TCP": "tcp://10.0.0.1:8000",
    "ARCSPLINE_PORT_8000_TCP_PROTO": "tcp",
    "ARCSPLINE_PORT_8000_TCP_PORT": "8000",
    "ARCSPLINE_PORT_8000_TCP_ADDR": "10.0.0.1",
}


def test_kubernetes_service_links_are_ignored_quietly(
    monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    for name, value in SERVICE_LINKS.items():
        monkeypatch.setenv(name, value)
    monkeypatch.setenv("ARCSPLINE_HOST", "0.0.0.0")
    with caplog.at_level(logging.DEBUG, logger="arcspline.settings"):
        settings = Settings()
    assert (settings.host, settings.port) == ("0.0.0.0", 8000)
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING]
    ignored = " ".join(r.getMessage() for r in caplog.records if r.levelno == logging.DEBUG)
    for name in SERVICE_LINKS:
        assert name in ignored


def test_a_port_is_still_read_beside_service_links(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ARCSPLINE_SERVICE_HOST", "10.0.0.1")
    monkeypatch.setenv("ARCSPLINE_PORT", "9001")
    assert Settings().port == 9001
    monkeypatch.setenv("ARCSPLINE_PORT", "http://10.0.0.1:8000")
    with pytest.raises(ValidationError, match="port"):
        Settings()


def test_settings_are_read_once(monkeypatch: pytest.MonkeyPatch) -> None:
    get_settings.cache_clear()
    try:
        first = get_settings()
        monkeypatch.setenv("ARCSPLINE_QUEUE_CAPACITY", "7")
        assert get_settings() is first
    finally:
        get_settings.cache_clear()
