"""How a failure is said (``arcspline.cli.errors``): one line a user can act on — the
service's detail with the options its fields stand for, the URL not reached, the file
missing — and exit 1; a usage error is typer's (exit 2)."""

from __future__ import annotations

import httpx
import pytest
import typer

from arcspline.api.schemas import ProblemResponse
from arcspline.cli.errors import (
    CommandError,
    UsageError,
    describe,
    guard,
    one_line,
    option_of,
)
from arcspline.client import ServiceError


def _problem(detail: str, *locs: list[str | int]) -> ServiceError:
    errors = [{"loc": loc, "msg": "bad", "type": "value_error"} for loc in locs]
    return ServiceError(
        ProblemResponse.model_validate(
            {"type": "urn:arcspline:problem:validation", "title": "Invalid request",
             "status": 422, "detail": detail, "errors": errors or None}
        )
    )  # fmt: skip


def test_a_service_error_says_its_detail_and_the_options_behind_its_fields() -> None:
    error = _problem("1 invalid field(s): body.gcode.decimals: bad", ["body", "gcode", "decimals"])
    assert describe(error) == "1 invalid field(s): body.gcode.decimals: bad (option --decimals)"
    error = _problem("toolpaths.3.segments.1: cannot\n be cut", ["body", "tolerance"])
    assert describe(error) == (
        "toolpaths.3.segments.1: cannot be cut (at body.tolerance) (option --tolerance)"
    )
    assert describe(_problem("busy")) == "busy"


@pytest.mark.parametrize(
    ("path", "option"),
    [("body.tolerance", "--tolerance"), ("body.gcode.feed_rate", "--feed-rate"),
     ("body.gcode.units", "--units"), ("body.layers", "--layers"), ("body.document", None),
     ("body.spiral.start", None)],
)  # fmt: skip
def test_fields_and_their_options(path: str, option: str | None) -> None:
    assert option_of(path) == option


def test_an_unreachable_service_is_named() -> None:
    request = httpx.Request("POST", "http://127.0.0.1:9/v1/approximate")
    refused = httpx.ConnectError("All connection attempts failed", request=request)
    assert (
        describe(refused) == "could not reach http://127.0.0.1:9 (All connection attempts failed)"
    )
    slow = httpx.ReadTimeout("timed out", request=request)
    assert describe(slow) == "no answer from http://127.0.0.1:9 in time (timed out)"


def test_files_and_the_rest() -> None:
    missing = FileNotFoundError(2, "No such file or directory", "part.svg")
    assert describe(missing) == "No such file or directory: part.svg"
    assert describe(CommandError("no such file: x")) == "no such file: x"
    assert describe(UsageError("required", "--tolerance")) == "required (--tolerance)"
    named = UsageError("a program needs the G-code options: give --feed-rate", "--feed-rate")
    assert describe(named) == "a program needs the G-code options: give --feed-rate"
    assert describe(ValueError("odd\nthing")) == (
        "ValueError: odd thing (--debug shows the traceback)"
    )
    assert one_line(" a\n\tb  c ") == "a b c"


def test_guard_turns_failures_into_exit_codes(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(typer.Exit) as failed, guard(debug=False):
        raise CommandError("no such file: x.svg")
    assert failed.value.exit_code == 1
    assert capsys.readouterr().err == "error: no such file: x.svg\n"
    with pytest.raises(typer.BadParameter) as usage, guard(debug=False):
        raise UsageError("required", "--tolerance")
    assert usage.value.param_hint == "--tolerance"
    with pytest.raises(CommandError), guard(debug=True):
        raise CommandError("kept for its traceback")
