"""The options of a G-code program, validated on construction, and the error it raises."""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Literal, get_args

Units = Literal["mm", "inch"]
ArcFormat = Literal["ij", "r"]
UNITS: tuple[str, ...] = get_args(Units)
ARC_FORMATS: tuple[str, ...] = get_args(ArcFormat)

#: Decimals accepted for either unit. 3 is the coarsest that still resolves the common
#: machine resolution (1 µm; 0.001" on hobby machines) and keeps the radius mismatch within
#: LinuxCNC's strictest arc check (0.001 mm); 6 is finer than any controller interpolates
#: (Fanuc IS-C: 0.0001 mm / 0.00001") and keeps every coordinate below
#: :data:`MAX_COORDINATE` within 13 significant digits, exact in double precision.
MIN_DECIMALS = 3
MAX_DECIMALS = 6
#: Decimals when the request gives none: 0.1 µm in mm, 0.25 µm in inch.
DEFAULT_DECIMALS: Mapping[str, int] = {"mm": 4, "inch": 5}
#: Largest magnitude of a coordinate or feed written (X, Y, Z, F): a kilometre in mm;
#: beyond it a number stops being a plausible machine coordinate.
MAX_COORDINATE = 1e6
#: Most depth passes a program may cut (``step_down``): beyond it the step is surely a
#: mistake (a micrometre step into a millimetre).
MAX_PASSES = 1000


class GcodeError(ValueError):
    """The options, or this spline at these options, cannot give a correct program.

    ``field`` is the option's name (``feed_rate``, ``decimals``, ...) or ``"spiral"`` when
    the spiral itself is out of range; ``message`` says why in words.
    """

    def __init__(self, field: str, message: str) -> None:
        super().__init__(f"{field}: {message}")
        self.field = field
        self.message = message

    def __reduce__(self) -> tuple[object, ...]:
        # The default pickling passes the formatted text as the only argument; these errors
        # cross the process-pool boundary.
        return (GcodeError, (self.field, self.message))


def _is_real(value: object) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


@dataclass(frozen=True, slots=True)
class GcodeOptions:
    """How to write the program; validated on construction (raises :class:`GcodeError`).

    Lengths are in ``units`` (the spline's coordinates are taken to be in them already),
    feeds in ``units`` per minute. ``decimals`` and ``plunge_feed_rate`` default to
    :data:`DEFAULT_DECIMALS` and ``feed_rate``: see :attr:`resolved_decimals` and
    :attr:`resolved_plunge_feed_rate`.
    """

    feed_rate: float
    units: Units = "mm"
    decimals: int | None = None
    arc_format: ArcFormat = "ij"
    line_numbers: bool = False
    comments: bool = False
    safe_z: float | None = None
    cut_z: float | None = None
    plunge_feed_rate: float | None = None
    min_arc_length: float | None = None
    max_radius: float | None = None
    step_down: float | None = None

    def __post_init__(self) -> None:
        if self.units not in UNITS:
            raise GcodeError("units", f"must be one of {', '.join(UNITS)}, got {self.units!r}")
        if self.decimals is not None and (
            not isinstance(self.decimals, int) or isinstance(self.decimals, bool)
        ):
            raise GcodeError("decimals", f"must be an integer, got {self.decimals!r}")
        if self.decimals is not None and not MIN_DECIMALS <= self.decimals <= MAX_DECIMALS:
            raise GcodeError(
                "decimals",
                f"must lie between {MIN_DECIMALS} and {MAX_DECIMALS}, got {self.decimals}",
            )
        if self.arc_format not in ARC_FORMATS:
            raise GcodeError(
                "arc_format", f"must be one of {', '.join(ARC_FORMATS)}, got {self.arc_format!r}"
            )
        for name in ("line_numbers", "comments"):
            if not isinstance(getattr(self, name), bool):
                raise GcodeError(name, f"must be true or false, got {getattr(self, name)!r}")
        self._check_feed("feed_rate", self.feed_rate)
        if self.plunge_feed_rate is not None:
            if self.safe_z is None:
                raise GcodeError("plunge_feed_rate", "applies only with safe_z and cut_z")
            self._check_feed("plunge_feed_rate", self.plunge_feed_rate)
        self._check_depths()
        self._check_step_down()
        for name in ("min_arc_length", "max_radius"):
            value = getattr(self, name)
            if value is not None and not (_is_real(value) and math.isfinite(value) and value > 0.0):
                raise GcodeError(name, f"must be a finite number > 0, got {value!r}")

    def _check_feed(self, name: str, value: object) -> None:
        if not (_is_real(value) and math.isfinite(value)):  # type: ignore[arg-type]
            raise GcodeError(name, f"must be a finite number, got {value!r}")
        feed = float(value)  # type: ignore[arg-type]
        smallest = 10.0**-self.resolved_decimals
        if not smallest <= feed <= MAX_COORDINATE:
            raise GcodeError(
                name,
                f"must lie between {smallest:g} (one unit in the last of "
                f"{self.resolved_decimals} decimals) and {MAX_COORDINATE:g} {self.units}/min, "
                f"got {feed:g}",
            )

    def _check_depths(self) -> None:
        if (self.safe_z is None) != (self.cut_z is None):
            missing = "cut_z" if self.cut_z is None else "safe_z"
            raise GcodeError(missing, "safe_z and cut_z go together: give both or neither")
        if self.safe_z is None or self.cut_z is None:
            return
        for name in ("safe_z", "cut_z"):
            value = getattr(self, name)
            if not (_is_real(value) and math.isfinite(value) and abs(value) < MAX_COORDINATE):
                raise GcodeError(
                    name, f"must be a finite number of magnitude below {MAX_COORDINATE:g}"
                )
        scale = 10**self.resolved_decimals
        if not round(self.safe_z * scale) > round(self.cut_z * scale):
            raise GcodeError(
                "safe_z",
                f"must lie above cut_z by at least one unit in the last place "
                f"(safe_z {self.safe_z:g}, cut_z {self.cut_z:g})",
            )

    def _check_step_down(self) -> None:
        step = self.step_down
        if step is None:
            return
        if self.safe_z is None or self.cut_z is None:
            raise GcodeError("step_down", "applies only with safe_z and cut_z")
        if not (_is_real(step) and math.isfinite(step) and 0.0 < step < MAX_COORDINATE):
            raise GcodeError(
                "step_down", f"must be a finite number > 0 and below {MAX_COORDINATE:g}"
            )
        d = self.resolved_decimals
        if self._step_ulps < 1:
            raise GcodeError(
                "step_down", f"must be at least one unit in the last of {d} decimals, got {step:g}"
            )
        if round(self.cut_z * 10**d) >= 0:
            raise GcodeError(
                "cut_z",
                f"must lie below the stock top Z0 when step_down is given, got {self.cut_z:g}",
            )
        if round(self.safe_z * 10**d) <= 0:
            # Rapids run at safe_z: at or below the stock top they would cut through it.
            raise GcodeError(
                "safe_z",
                f"must lie above the stock top Z0 when step_down is given, got {self.safe_z:g}",
            )
        # ceil(-cut_z / step) in units of the last place: counted before any level is made.
        passes = -(round(self.cut_z * 10**d) // self._step_ulps)
        if passes > MAX_PASSES:
            raise GcodeError(
                "step_down",
                f"{step:g} {self.units} down to cut_z {self.cut_z:g} takes {passes} passes, "
                f"more than {MAX_PASSES}",
            )

    @property
    def _step_ulps(self) -> int:
        """``step_down`` in units of the last decimal place, rounded down (a pass is never
        deeper than asked); the inner rounding absorbs binary noise (0.29 · 10⁴ =
        2899.9999999999995)."""
        assert self.step_down is not None
        return math.floor(round(float(self.step_down) * 10.0**self.resolved_decimals, 6))

    @property
    def pass_levels(self) -> tuple[int, ...]:
        """The Z of each cutting pass, in units of the last decimal place (``10^-decimals``):
        ``cut_z`` alone, or with ``step_down`` the stock top Z0 less one step, two steps, ...
        the last exactly ``cut_z`` (docs/gcode.md "Depth passes"). Empty without ``cut_z``."""
        if self.cut_z is None:
            return ()
        scale = 10**self.resolved_decimals
        bottom = round(self.cut_z * scale)
        if self.step_down is None:
            return (bottom,)
        step = self._step_ulps
        # ceil(-bottom / step) passes, in integers; bounded before the tuple is built.
        passes = min(-(bottom // step), MAX_PASSES + 1)
        return (*(-k * step for k in range(1, passes)), bottom)

    @property
    def resolved_decimals(self) -> int:
        """``decimals``, or the default for ``units``."""
        return DEFAULT_DECIMALS[self.units] if self.decimals is None else self.decimals

    @property
    def resolved_plunge_feed_rate(self) -> float:
        """``plunge_feed_rate``, or ``feed_rate``."""
        return self.feed_rate if self.plunge_feed_rate is None else self.plunge_feed_rate
