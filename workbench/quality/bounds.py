"""What motion is physically plausible, per object class (docs/data_quality.md says why).

Limits are deliberately wide: a finding means the *data* cannot be right (a real vehicle
cannot move so), not that the driving was unusual. Sources:

- braking: the peak tyre-road friction of dry asphalt is 0.8-0.9 (J. Y. Wong, *Theory of
  Ground Vehicles*, 4th ed., Table 1.4); with downforce-free tyres a car cannot brake much
  beyond mu * g, so 10 m/s² (1.0 g) bounds cars and motorcycles with margin; heavy
  vehicles brake less (8 m/s²), a bicycle is limited by pitching over the front wheel
  (about 0.6-0.7 g: 7 m/s²);
- acceleration: the quickest production cars reach 100 km/h in about 2.5 s (11 m/s² mean
  over the run) — a road car seen in traffic data above 8 m/s² is very unlikely, so 8 m/s²
  for cars (10 for motorcycles, 3 for trucks and buses, 4 for bicycles);
- pedestrians: elite sprinters peak near 9.5 m/s² at the start; 10 m/s² either way;
- jerk: full braking (10 m/s²) takes a brake system at least about 0.2 s to build up, so
  no road vehicle changes its acceleration faster than about 50 m/s³;
- heading against the direction of motion: the kinematic bicycle model (R. Rajamani,
  *Vehicle Dynamics and Control*, 2nd ed., §2.2) gives the slip angle at the centre
  ``beta = atan(l_r tan(delta) / L)``; with the steering stop (about 40°) and the centre
  half-way between the axles ``beta <= atan(tan(40°) / 2) = 23°``: 30° bounds it with
  position noise; pedestrians and unknown objects have no such limit (not checked).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from loaders.records import ObjectClass

__all__ = ["ClassLimits", "QualityBounds"]


@dataclass(frozen=True, slots=True)
class ClassLimits:
    """Physically plausible motion of one object class.

    Attributes:
        accel_mps2: Largest forward acceleration along the path [m/s²].
        brake_mps2: Largest deceleration (a positive number) [m/s²].
        jerk_mps3: Largest rate of change of the acceleration [m/s³].
        slip_rad: Largest angle between heading and direction of motion [rad]; ``None``:
            not checked (pedestrians, unknown objects).
    """

    accel_mps2: float
    brake_mps2: float
    jerk_mps3: float
    slip_rad: float | None


_SLIP = math.radians(30.0)
_LIMITS = {
    ObjectClass.CAR: ClassLimits(8.0, 10.0, 50.0, _SLIP),
    ObjectClass.TRUCK: ClassLimits(3.0, 8.0, 50.0, _SLIP),
    ObjectClass.BUS: ClassLimits(3.0, 8.0, 50.0, _SLIP),
    ObjectClass.MOTORCYCLE: ClassLimits(10.0, 10.0, 50.0, _SLIP),
    ObjectClass.BICYCLE: ClassLimits(4.0, 7.0, 50.0, _SLIP),
    ObjectClass.PEDESTRIAN: ClassLimits(10.0, 10.0, 50.0, None),
    ObjectClass.UNKNOWN: ClassLimits(10.0, 10.0, 50.0, None),
}


@dataclass(frozen=True, slots=True)
class QualityBounds:
    """Every threshold of the data-quality checks (docs/data_quality.md).

    Attributes:
        limits: Per object class.
        chord_span_ns: Each side of the chord over which positions give speed and direction
            of motion (at 10 Hz: the neighbouring samples).
        window_half_ns: Half the window of the acceleration and jerk fits.
        speed_abs_mps: Recorded speed may differ from the chord's by this much plus
            ``speed_rel`` of the speed (position noise, and a chord averaging over its span).
        speed_rel: See ``speed_abs_mps``.
        moving_mps: Heading is checked against the motion only at or above this chord speed.
        position_tol_m: A step may exceed what the speeds allow by this much (box jitter of
            a detector, position noise) before it is a teleport or an id jump.
        max_gap_ns: Speed and heading are checked only where the chord spans at most this
            (sparser tracks say too little about the motion in between).
    """

    limits: dict[ObjectClass, ClassLimits] = field(default_factory=lambda: dict(_LIMITS))
    chord_span_ns: int = 100_000_000
    window_half_ns: int = 250_000_000
    speed_abs_mps: float = 1.0
    speed_rel: float = 0.1
    moving_mps: float = 3.0
    position_tol_m: float = 1.0
    max_gap_ns: int = 1_000_000_000

    def of(self, object_class: int) -> ClassLimits:
        """Limits of a class code (unknown codes: the unknown class's)."""
        try:
            return self.limits[ObjectClass(object_class)]
        except (ValueError, KeyError):
            return self.limits[ObjectClass.UNKNOWN]
