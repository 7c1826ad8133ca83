"""Path input: SVG path data (and, later, documents)."""

from .svg_data import parse_path_data

__all__ = ["parse_path_data"]
