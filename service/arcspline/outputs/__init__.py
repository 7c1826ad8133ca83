"""What an arc spline is turned into: programs and pictures."""
