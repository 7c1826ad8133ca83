"""Affine maps of segments: hand-computed images (rotation about a point, a mirror that
reverses an arc, a skewed circle whose axes are the golden ratio and its inverse), and, for
random maps, the image of every arc sampled against the map applied to the arc's own points
(the parametric formula written out here)."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from arcspline.drawings.affine import Affine, SingularMapError, transform_segment
from arcspline.geometry.curves.segments import CircularArc, Cubic, EllipticalArc, Line, Segment

GOLDEN = (1 + math.sqrt(5)) / 2


def _point(segment: Segment, fraction: float) -> tuple[float, float]:
    """The point a fraction of the way along an arc's sweep, by the textbook formula."""
    if isinstance(segment, CircularArc):
        angle = segment.start_angle_rad + fraction * segment.sweep_rad
        return (
            segment.center[0] + segment.radius * math.cos(angle),
            segment.center[1] + segment.radius * math.sin(angle),
        )
    assert isinstance(segment, EllipticalArc)
    phi = segment.start_angle_rad + fraction * segment.sweep_rad
    x, y = segment.rx * math.cos(phi), segment.ry * math.sin(phi)
    c, s = math.cos(segment.rotation_rad), math.sin(segment.rotation_rad)
    return (segment.center[0] + c * x - s * y, segment.center[1] + s * x + c * y)


def test_composition_applies_the_right_map_first() -> None:
    # translate(10, 0) after scale(2): (1, 1) → (2, 2) → (12, 2).
    assert (Affine.translate(10) @ Affine.scale(2)).apply((1, 1)) == (12, 2)
    assert (Affine.scale(2) @ Affine.translate(10)).apply((1, 1)) == (22, 2)


def test_rotation_about_a_point_is_exact_at_quarter_turns() -> None:
    # rotate(90, 5, 5): (10, 5) is 5 right of the centre, goes 5 above it.
    assert Affine.rotate_deg(90, 5, 5).apply((10, 5)) == (5, 10)
    assert Affine.rotate_deg(-270).apply((1, 0)) == (0, 1)
    assert Affine.rotate_deg(30).apply((2, 0)) == pytest.approx((math.sqrt(3), 1), abs=1e-15)


def test_skews() -> None:
    assert Affine.skew_x_deg(45).apply((0, 1)) == pytest.approx((1, 1))
    assert Affine.skew_y_deg(45).apply((1, 0)) == pytest.approx((1, 1))


def test_beziers_map_by_their_control_points() -> None:
    m = Affine(2, 0, 1, 3, 5, 7)  # x' = 2x + y + 5, y' = 3y + 7
    assert transform_segment(Line((0, 0), (1, 1)), m) == Line((5, 7), (8, 10))
    cubic = transform_segment(Cubic((0, 0), (1, 0), (0, 1), (1, 1)), m)
    assert cubic == Cubic((5, 7), (7, 7), (6, 10), (8, 10))


def test_a_mirror_reverses_an_arc() -> None:
    # The upper half of the unit circle, anticlockwise from (1, 0) to (−1, 0), mirrored in
    # the y axis: from (−1, 0) over the top to (1, 0), clockwise.
    arc = CircularArc((1.0, 0.0), (-1.0, 0.0), (0.0, 0.0), 1.0, 0.0, math.pi)
    image = transform_segment(arc, Affine.scale(-1, 1))
    assert isinstance(image, CircularArc)
    assert image.start == (-1, 0)
    assert image.end == (1, 0)
    assert image.sweep_rad == -math.pi
    assert image.radius == 1
    assert _point(image, 0.5) == pytest.approx((0, 1), abs=1e-15)


def test_a_similarity_keeps_a_circular_arc() -> None:
    arc = CircularArc((3.0, 2.0), (2.0, 3.0), (2.0, 2.0), 1.0, 0.0, math.pi / 2)
    image = transform_segment(arc, Affine.rotate_deg(90) @ Affine.scale(2))
    # centre (2, 2) → (4, 4) → (−4, 4); radius 2; start angle 0 → 90°.
    assert isinstance(image, CircularArc)
    assert image.center == pytest.approx((-4, 4))
    assert image.radius == 2
    assert image.start_angle_rad == pytest.approx(math.pi / 2)
    assert image.sweep_rad == pytest.approx(math.pi / 2)


def test_a_skewed_circle_is_an_ellipse_with_golden_axes() -> None:
    # skewX(45°) = [[1, 1], [0, 1]]: its singular values are φ and 1/φ (φ the golden ratio),
    # the major axis at α with tan 2α = 2 (31.72°).
    arc = CircularArc((1.0, 0.0), (-1.0, 0.0), (0.0, 0.0), 1.0, 0.0, math.pi)
    image = transform_segment(arc, Affine.skew_x_deg(45))
    assert isinstance(image, EllipticalArc)
    assert image.rx == pytest.approx(GOLDEN, rel=1e-14)
    assert image.ry == pytest.approx(1 / GOLDEN, rel=1e-14)
    assert math.tan(2 * image.rotation_rad) == pytest.approx(2, rel=1e-12)
    assert image.start == (1, 0)
    assert image.end == (-1, 0)
    assert _point(image, 0.5) == pytest.approx((1, 1), abs=1e-14)  # (0, 1) ↦ (1, 1)


def test_a_map_that_collapses_the_plane_is_refused() -> None:
    with pytest.raises(SingularMapError):
        transform_segment(Line((0, 0), (1, 1)), Affine.scale(1, 0))


finite = st.floats(-5, 5, allow_nan=False)


@settings(max_examples=300, deadline=None)
@given(
    matrix=st.tuples(finite, finite, finite, finite, finite, finite),
    rx=st.floats(0.1, 4),
    ry=st.floats(0.1, 4),
    rotation=st.floats(-4, 4),
    start=st.floats(-4, 4),
    sweep=st.floats(-6.2, 6.2).filter(lambda s: abs(s) > 1e-3),
    circular=st.booleans(),
)
def test_the_image_of_an_arc_is_the_map_of_its_points(
    matrix: tuple[float, ...], rx: float, ry: float, rotation: float, start: float,
    sweep: float, circular: bool,
) -> None:  # fmt: skip
    m = Affine(*matrix)
    if m.is_singular() or abs(m.determinant) < 1e-3:
        return
    arc: Segment
    if circular:
        arc = CircularArc((0.0, 0.0), (0.0, 0.0), (1.0, -2.0), rx, start, sweep)
    else:
        arc = EllipticalArc((0.0, 0.0), (0.0, 0.0), (1.0, -2.0), rx, ry, rotation, start, sweep)
    arc = arc._replace(start=_point(arc, 0.0), end=_point(arc, 1.0))
    image = transform_segment(arc, m)
    scale = max(1.0, *map(abs, matrix)) * 10
    for fraction in (0.0, 0.25, 0.5, 0.75, 1.0):
        expected = m.apply(_point(arc, fraction))
        assert math.dist(_point(image, fraction), expected) <= 1e-12 * scale
    assert image.start == m.apply(arc.start)
    assert image.end == m.apply(arc.end)
