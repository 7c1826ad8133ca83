"""How a command ends when something goes wrong: a usage error is typer's (exit 2, with the
usage); anything else is one line on stderr, no traceback (exit 1), unless ``--debug``.

The line says what a user can act on: the service's problem detail with the options its
field paths stand for, the URL that could not be reached, the file that is missing.
"""

from __future__ import annotations

import asyncio
import contextlib
import re
from collections.abc import Coroutine, Iterator
from typing import TYPE_CHECKING, Any, TypeVar

import typer

if TYPE_CHECKING:
    from rich.console import Console

T = TypeVar("T")

#: Exit status of a command whose work failed (typer's own: 0 ok, 2 usage error).
EXIT_FAILED = 1
#: Request fields that are an option of their own, by their path in the request body.
_OPTION_OF_FIELD = {
    "body.tolerance": "--tolerance",
    "body.strategy": "--strategy",
    "body.units": "--units",
    "body.gcode.units": "--units",
    "body.layers": "--layers",
    "body.source_units": "--source-units",
    "body.join_tolerance": "--join-tolerance",
    "body.choose_start": "--choose-start",
    "body.order": "--order",
}


class CommandError(Exception):
    """The work cannot be done, for a reason said in one line (exit 1)."""


class UsageError(Exception):
    """The command line asks for something that cannot be (exit 2, as typer's own usage
    errors); ``option`` names the option or argument at fault."""

    def __init__(self, message: str, option: str | None = None) -> None:
        super().__init__(message)
        self.option = option


def stderr() -> Console:
    """A console on the current stderr (created on use: tests swap the stream), that never
    wraps a line nor reads markup in messages."""
    from rich.console import Console

    return Console(stderr=True, soft_wrap=True, highlight=False)


def run(work: Coroutine[Any, Any, T], debug: bool) -> T:
    """Run a command's work under :func:`guard`."""
    with guard(debug):
        return asyncio.run(work)


@contextlib.contextmanager
def guard(debug: bool) -> Iterator[None]:
    """A failure inside becomes one line and exit 1, or, with ``debug``, the exception
    itself (typer prints its traceback); :class:`UsageError` becomes typer's usage error."""
    try:
        yield
    except UsageError as error:
        raise typer.BadParameter(str(error), param_hint=error.option) from None
    except (typer.Exit, typer.Abort, KeyboardInterrupt):
        raise
    except Exception as error:
        if debug:
            raise
        say_error(describe(error))
        raise typer.Exit(EXIT_FAILED) from None


def say_error(message: str) -> None:
    from rich.text import Text

    stderr().print(Text.assemble(("error: ", "bold red"), message))


def describe(error: BaseException) -> str:
    """One line a user can act on, for any failure."""
    from arcspline.client import ServiceError

    if isinstance(error, ServiceError):
        text = _service_error(error)
    elif isinstance(error, CommandError):
        text = str(error)
    elif isinstance(error, UsageError):
        named = error.option is None or error.option in str(error)
        text = str(error) if named else f"{error} ({error.option})"
    elif _is_transport_error(error):
        text = _transport_error(error)
    elif _is_validation_error(error):
        text = _validation_error(error)
    elif isinstance(error, OSError) and error.strerror:
        text = f"{error.strerror}: {error.filename}" if error.filename else error.strerror
    else:
        text = f"{type(error).__name__}: {error} (--debug shows the traceback)"
    return one_line(text)


def one_line(text: str) -> str:
    return re.sub(r"\s+", " ", text).strip()


def _service_error(error: Any) -> str:
    """The problem's detail (which names the fields), with the options they stand for and
    any field path the detail leaves out."""
    detail: str = error.detail
    paths = [".".join(str(part) for part in item.loc) for item in error.errors]
    missing = [path for path in paths if path and path not in detail]
    if missing:
        detail += f" (at {', '.join(missing)})"
    options = sorted({option for path in paths if (option := option_of(path))})
    if options:
        detail += f" (option {', '.join(options)})"
    return detail


def option_of(path: str) -> str | None:
    """The command-line option that sets the request field at ``path`` (``body.gcode.feed_rate``
    is ``--feed-rate``), if there is one."""
    if path in _OPTION_OF_FIELD:
        return _OPTION_OF_FIELD[path]
    parts = path.split(".")
    if len(parts) == 3 and parts[:2] == ["body", "gcode"]:
        return "--" + parts[2].replace("_", "-")
    from .tooling import option_of as tooling_option

    return tooling_option(path)


def _is_transport_error(error: BaseException) -> bool:
    import httpx

    return isinstance(error, httpx.TransportError)


def _transport_error(error: Any) -> str:
    """Which service could not be reached, and why (the client has tried again already)."""
    import httpx

    try:
        url = error.request.url
        where = f"{url.scheme}://{url.netloc.decode()}"
    except RuntimeError:  # an error raised before any request was made
        where = "the service"
    reason = str(error) or type(error).__name__
    if isinstance(error, httpx.TimeoutException):
        return f"no answer from {where} in time ({reason})"
    return f"could not reach {where} ({reason})"


def _is_validation_error(error: BaseException) -> bool:
    from pydantic import ValidationError

    return isinstance(error, ValidationError)


def _validation_error(error: Any) -> str:
    """The settings of the environment refused (``ARCSPLINE_*``), or an answer this client
    cannot read (a service of another version)."""
    if error.title == "Settings":
        problems = [
            (f"ARCSPLINE_{'_'.join(map(str, e['loc'])).upper()}: " if e["loc"] else "")
            + e["msg"].removeprefix("Value error, ")
            for e in error.errors(include_url=False)
        ]
        return "invalid settings: " + "; ".join(problems)
    return f"an answer this client cannot read ({error.title}): {error}"
