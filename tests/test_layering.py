"""The pure packages stay pure: the geometry core and the G-code writer import only the
standard library, numpy and each other (house style: api → worker → geometry/gcode)."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "service" / "arcspline"
PURE = [
    *sorted((PACKAGE / "geometry").rglob("*.py")),
    *sorted((PACKAGE / "outputs").rglob("*.py")),
]
ALLOWED_THIRD_PARTY = {"numpy"}


def _imported_roots(path: Path) -> set[str]:
    roots = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            roots.update(alias.name.split(".")[0] for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            roots.add(node.module.split(".")[0])
    return roots


@pytest.mark.parametrize("path", [p for p in PURE if p.exists()], ids=lambda p: p.name)
def test_pure_module_imports_only_stdlib_numpy_and_arcspline(path: Path) -> None:
    foreign = {
        name
        for name in _imported_roots(path)
        if name not in sys.stdlib_module_names
        and name not in ALLOWED_THIRD_PARTY
        and name != "arcspline"
    }
    assert not foreign, f"{path.name} imports {sorted(foreign)}"


def test_importing_the_core_loads_no_web_stack() -> None:
    code = (
        "import sys, arcspline.geometry, arcspline.outputs.gcode; "
        "print(sorted(m for m in sys.modules if m.split('.')[0] in "
        "{'fastapi', 'starlette', 'pydantic', 'uvicorn', 'httpx', 'arcspline'} "
        "and not m.startswith(('arcspline.geometry', 'arcspline.outputs'))"
        " and m != 'arcspline'))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True
    )
    assert out.stdout.strip() == "[]"
