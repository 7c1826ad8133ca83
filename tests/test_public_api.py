"""The public Python API (``arcspline/__init__.py``): its documented example runs, and
importing it loads no web stack."""

from __future__ import annotations

import doctest
import subprocess
import sys

import arcspline


def test_the_documented_example_runs() -> None:
    result = doctest.testmod(arcspline, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted >= 4
    assert result.failed == 0


def test_the_drawings_example_runs() -> None:
    import arcspline.drawings

    result = doctest.testmod(arcspline.drawings, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted >= 4
    assert result.failed == 0


def test_every_public_name_is_documented_and_exported() -> None:
    for name in arcspline.__all__:
        value = getattr(arcspline, name)
        if callable(value) and not isinstance(value, type(arcspline.COLUMN)):
            assert value.__doc__, f"{name} has no docstring"
    assert arcspline.approximate.__module__.startswith("arcspline.geometry")


def test_importing_the_package_loads_no_web_stack() -> None:
    code = (
        "import sys, arcspline; print(sorted(m for m in sys.modules if m.split('.')[0] in "
        "{'fastapi', 'starlette', 'pydantic', 'uvicorn', 'httpx', 'orjson'}))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
