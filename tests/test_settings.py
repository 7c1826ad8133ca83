"""The one settings object: defaults, environment variables, refusals."""

from __future__ import annotations

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


def test_a_misspelt_variable_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ARCSPLINE_POOL_SIZ", "3")
    with pytest.raises(ValidationError, match="ARCSPLINE_POOL_SIZ"):
        Settings()


def test_settings_are_read_once(monkeypatch: pytest.MonkeyPatch) -> None:
    get_settings.cache_clear()
    try:
        first = get_settings()
        monkeypatch.setenv("ARCSPLINE_QUEUE_CAPACITY", "7")
        assert get_settings() is first
    finally:
        get_settings.cache_clear()
