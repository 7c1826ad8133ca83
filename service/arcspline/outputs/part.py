"""What every writer takes: arc splines, each with the curve it approximates, in order (a
spiral is one part; a path has one part per subpath)."""

from __future__ import annotations

from arcspline.geometry import ArcSpline, Curve

Part = tuple[ArcSpline, Curve]
