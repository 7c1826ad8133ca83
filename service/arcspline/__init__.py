"""arcspline: arc-spline approximation of cubic Bézier spirals for CNC tool paths."""
