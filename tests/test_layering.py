"""The layers stay apart (house style: api → worker → outputs/paths → geometry, never the
other way): the geometry core, the outputs and the path input import only the standard
library, numpy, the C libraries of their compiled kernels and the layers below them."""

from __future__ import annotations

import ast
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "service" / "arcspline"
#: Each pure layer and the package prefixes it may import from.
LAYERS = {
    "geometry": ("arcspline.geometry",),
    "outputs": ("arcspline.geometry", "arcspline.outputs"),
    "paths": ("arcspline.geometry", "arcspline.paths"),
    "drawings": ("arcspline.geometry", "arcspline.paths", "arcspline.drawings"),
    "machining": ("arcspline.geometry", "arcspline.outputs", "arcspline.machining"),
}
ALLOWED_THIRD_PARTY = {"numpy"}
#: The document libraries, each allowed only in the layer that reads or writes documents.
LAYER_THIRD_PARTY = {"drawings": {"defusedxml", "ezdxf"}, "outputs": {"ezdxf"}}
#: What Cython sources cimport from the compiler's own declarations.
CYTHON_BUILTINS = {"libc", "libcpp", "cython", "cpython"}
SOURCES = [
    (layer, path)
    for layer in LAYERS
    for pattern in ("*.py", "*.pyx", "*.pxd")
    for path in sorted((PACKAGE / layer).rglob(pattern))
]
_CYTHON_IMPORT = re.compile(r"^\s*(?:from\s+(\S+)\s+c?import|c?import\s+(\S+))", re.MULTILINE)


def _imported(path: Path) -> set[str]:
    """Absolute module names imported (and, for Cython, cimported) by ``path``."""
    text = path.read_text()
    if path.suffix != ".py":
        return {m for pair in _CYTHON_IMPORT.findall(text) for m in pair if m and m != "."}
    names = set()
    for node in ast.walk(ast.parse(text, str(path))):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names.add(node.module)
    return names


@pytest.mark.parametrize(
    ("layer", "path"), SOURCES, ids=[str(p.relative_to(PACKAGE)) for _, p in SOURCES]
)
def test_pure_layers_import_only_below_them(layer: str, path: Path) -> None:
    foreign = set()
    for name in _imported(path):
        root = name.split(".")[0]
        if root == "arcspline":
            if not name.startswith(LAYERS[layer]):
                foreign.add(name)
        elif root not in (
            sys.stdlib_module_names
            | ALLOWED_THIRD_PARTY
            | LAYER_THIRD_PARTY.get(layer, set())
            | CYTHON_BUILTINS
        ):
            foreign.add(name)
    assert not foreign, f"{path.name} imports {sorted(foreign)}"


def test_importing_the_core_loads_no_web_stack() -> None:
    code = (
        "import sys, arcspline.geometry, arcspline.outputs.gcode; "
        "print(sorted(m for m in sys.modules if m.split('.')[0] in "
        "{'fastapi', 'starlette', 'pydantic', 'uvicorn', 'httpx', 'arcspline'} "
        # The package's public API (arcspline/__init__.py) also loads the pure path input.
        "and not m.startswith(('arcspline.geometry', 'arcspline.outputs', 'arcspline.paths'))"
        " and m != 'arcspline'))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True
    )
    assert out.stdout.strip() == "[]"
