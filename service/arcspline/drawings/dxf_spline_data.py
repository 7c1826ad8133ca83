"""A DXF SPLINE entity's curve as a :class:`SplineData` NURBS in the XY plane (docs/drawings.md
§4): its control points, knots and weights, or ezdxf's interpolation of its fit points.

A closed or periodic spline (group 70 bits 1, 2) with ``n`` control points and only ``n + 1``
knots is written as OpenCascade writes periodic curves: the knots span one period. It is
unwrapped into the ordinary NURBS it stands for: the first ``p`` control points (and weights)
repeated at the end, and ``p`` knots added at each end so that the knot spacing repeats with
period ``U[n] − U[0]``; its domain ``[U[0], U[n]]`` is then one turn.

The degree is the one the knot vector implies; a SPLINE without knots gets a clamped uniform
vector. Each departure from the plain reading is said in a note.
"""

from __future__ import annotations

import itertools
from typing import TYPE_CHECKING

from arcspline.geometry.spline import Point

from .dxf_spline import SplineData, SplineRefusedError

if TYPE_CHECKING:
    from ezdxf.entities.spline import Spline

#: SPLINE flags (group 70): closed, periodic.
CLOSED, PERIODIC = 1, 2


def spline_data(entity: Spline) -> tuple[SplineData, tuple[str, ...]]:
    """The curve of a SPLINE entity, projected onto the WCS XY plane (its points are WCS, so
    the projection drops z), with notes on how it was obtained. The degree is the one the
    knot vector implies, ``len(knots) − len(control points) − 1``, noted when the degree field
    says otherwise. A spline given only by fit points is interpolated by ezdxf."""
    notes: list[str] = []
    if len(entity.control_points):
        points = [tuple(p) for p in entity.control_points]
        knots = [float(k) for k in entity.knots]
        weights = [float(w) for w in entity.weights]
        field = int(entity.dxf.degree)
        if not knots:
            notes.append("has no knot vector; a clamped uniform one was taken")
            knots = _clamped_uniform(len(points), field)
        elif _one_period(int(entity.dxf.flags), len(knots), len(points), field):
            notes.append(
                "is periodic with the knots of one period only (as OpenCascade writes it): "
                f"unwrapped by repeating its first {field} control points"
            )
            points, weights, knots = _unwrapped(points, weights, knots, field)
        degree = len(knots) - len(points) - 1
        if degree != field:
            notes.append(
                f"degree field says {field} but {len(knots)} knots and {len(points)} control "
                f"points make degree {degree}; the knots were trusted"
            )
    elif len(entity.fit_points):
        fit = [tuple(p) for p in entity.fit_points]
        if any(p == q for p, q in itertools.pairwise(fit)):
            # ezdxf's chord-length parameters divide by the distance between them
            raise SplineRefusedError("has coincident consecutive fit points: not interpolated")
        try:
            tool = entity.construction_tool()
        except (ValueError, ZeroDivisionError, ArithmeticError, IndexError) as exc:
            raise SplineRefusedError(f"its fit points cannot be interpolated ({exc})") from exc
        notes.append(
            "given by fit points only: interpolated by ezdxf, which may differ from the "
            "CAD program's own interpolation"
        )
        points = [tuple(p) for p in tool.control_points]
        knots = [float(k) for k in tool.knots()]
        weights = [float(w) for w in tool.weights()] if tool.is_rational else []
        degree = tool.degree
    else:
        raise SplineRefusedError("has neither control points nor fit points")
    if any(p[2] != points[0][2] for p in points):
        notes.append("is not parallel to the XY plane; its projection onto XY was taken")
    control = tuple(Point(float(p[0]), float(p[1])) for p in points)
    return SplineData(degree, tuple(knots), control, tuple(weights)), tuple(notes)


def _clamped_uniform(count: int, degree: int) -> list[float]:
    inner = max(count - degree - 1, 0)
    return (
        [0.0] * (degree + 1)
        + [float(i) for i in range(1, inner + 1)]
        + [float(inner + 1)] * (degree + 1)
    )


def _one_period(flags: int, knots: int, count: int, degree: int) -> bool:
    """Whether a spline's knots are one period of a periodic curve (module docstring): it
    is closed or periodic, and has one knot more than control points (an ordinary NURBS has
    ``count + degree + 1``)."""
    return bool(flags & (CLOSED | PERIODIC)) and knots == count + 1 and count >= 2 and degree >= 1


def _unwrapped(
    points: list[tuple[float, ...]], weights: list[float], knots: list[float], degree: int
) -> tuple[list[tuple[float, ...]], list[float], list[float]]:
    """The periodic spline whose ``n + 1`` knots span one period as an ordinary NURBS: ``n +
    p`` control points ``P[i mod n]``, and knots ``U[j mod n] + (j div n)·(U[n] − U[0])`` for
    ``j`` in ``−p … n + p`` (the given ones kept as they are)."""
    n = len(points)
    period = knots[n] - knots[0]
    return (
        [points[i % n] for i in range(n + degree)],
        [weights[i % n] for i in range(n + degree)] if weights else [],
        [
            knots[j] if 0 <= j <= n else knots[j % n] + (j // n) * period
            for j in range(-degree, n + degree + 1)
        ],
    )
