"""Build of the compiled geometry kernels (Cython, C++): every ``.pyx`` under
``service/arcspline`` becomes an extension module of the same dotted name. Everything else
about the package is in pyproject.toml."""

from pathlib import Path

from Cython.Build import cythonize
from setuptools import Extension, setup

SOURCE_ROOT = Path("service")
#: IEEE results on every machine: no fused multiply-add contraction (gcc's default on
#: aarch64), no fast-math; -O3 for the kernels' loops.
COMPILE_ARGS = ["-O3", "-ffp-contract=off", "-fno-math-errno"]
DIRECTIVES = {
    "language_level": 3,
    "boundscheck": False,
    "wraparound": False,
    "cdivision": True,
    "initializedcheck": False,
    "embedsignature": True,
}


def extensions() -> list[Extension]:
    modules = []
    for pyx in sorted(SOURCE_ROOT.rglob("*.pyx")):
        name = ".".join(pyx.relative_to(SOURCE_ROOT).with_suffix("").parts)
        modules.append(
            Extension(name, [str(pyx)], language="c++", extra_compile_args=COMPILE_ARGS)
        )
    return modules


setup(
    ext_modules=cythonize(
        extensions(),
        compiler_directives=DIRECTIVES,
        include_path=[str(SOURCE_ROOT)],
        quiet=True,
    )
)
