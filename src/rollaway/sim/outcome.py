"""Outcome classification of a simulated parked car: ``held``, ``brake_slip`` or ``tyre_skid``.

Criteria (all thresholds [assumed], chosen well clear of the numerical creep, which is
< 1 mm per simulated hour, and of the contact settling at t = 0, < 0.1 mm):

1. **Roll-away** happens when the car's displacement along the slope, measured from where it
   was placed at t = 0, first exceeds :data:`ROLLAWAY_DISPLACEMENT_M` (5 cm).  The roll-away
   time is that instant (linear interpolation between brake updates).  Gating on
   displacement first keeps creep (sub-mm) from ever reading as a skid.  No roll-away
   within the scenario's duration: ``held``.
2. After a roll-away the simulation goes on for a classification window (until
   :data:`POST_ROLLAWAY_S` seconds later or :data:`POST_ROLLAWAY_M` of travel, whichever is
   first).  Over that window the rear-wheel slip ratio

       s = (Δx − R·Δφ) / Δx

   compares the car's travel Δx along the slope with the rolled distance R·Δφ of the rear
   wheels (mean of both, signed so that rolling with the car counts positive).  It is the
   distance form of s = (v − ωR)/v, robust to slow starts.  s ≈ 0: the wheels turn with the
   car, the drum brake slipped (``brake_slip``); s ≈ 1: the rear wheels stay locked and the
   tyres slide on the road (``tyre_skid``).  The boundary is :data:`TYRE_SKID_SLIP` = 0.5,
   applied to the *larger* of the two rear wheels' slip ratios: with a laterally uneven load
   one drum may slip while the other wheel's tyre slides (mean s ≈ 0.5); a tyre gave way, so
   that is a ``tyre_skid``.  ``slip_ratio`` reports the mean of both wheels.
3. ``diverged``: the run failed numerically (:mod:`rollaway.sim.divergence`); no verdict.

The brake **margin** reported is capacity/demand = (frictionloss_RL + frictionloss_RR) / T_req:
the two rear drums' torque for the sense each wheel is driven (eqs. 17b, 18–21) against the
analytic demand T_req = m g sin θ R (eq. 23, same total mass as the MuJoCo car).  ``min_margin``
is its minimum over the simulated time span (up to the end of the run).

``creep_m`` is the largest |travel| before the roll-away while the capacity was ≥ the demand:
the solver's creep for a held car (< 1 mm per hour); for a tyre skid it includes the first
centimetres of the slide.
"""
from __future__ import annotations

import numpy as np

ROLLAWAY_DISPLACEMENT_M = 0.05   # [assumed] travel along the slope that counts as rolling away
POST_ROLLAWAY_S = 8.0            # [assumed] classification window after roll-away (also the video's end)
POST_ROLLAWAY_M = 5.0            # [assumed] ... or this much travel, whichever comes first
TYRE_SKID_SLIP = 0.5             # [assumed] slip ratio above which the rear wheels count as locked
OUTCOMES = ("held", "brake_slip", "tyre_skid", "diverged")   # diverged: a numerical failure, no verdict


def crossing_time(t: np.ndarray, x: np.ndarray, level: float) -> float | None:
    """First time |x| reaches *level*, linearly interpolated; None if never."""
    a = np.abs(np.asarray(x))
    idx = np.nonzero(a >= level)[0]
    if idx.size == 0:
        return None
    i = int(idx[0])
    if i == 0:
        return float(t[0])
    f = (level - a[i - 1]) / (a[i] - a[i - 1])
    return float(t[i - 1] + f * (t[i] - t[i - 1]))


def slip_ratio(displacement_m: np.ndarray, wheel_angle_rad: np.ndarray, wheel_radius_m: float,
               forward_is_downhill: bool, start: int) -> float:
    """Distance slip ratio s = (Δx − R·Δφ)/Δx of the rear wheels from record *start* to the end.

    *wheel_angle_rad* is the mean rear hinge angle (positive = forward rotation).
    """
    dx = float(displacement_m[-1] - displacement_m[start])
    if dx == 0.0:
        return float("nan")
    sgn = 1.0 if forward_is_downhill else -1.0
    rolled = sgn * wheel_radius_m * float(wheel_angle_rad[-1] - wheel_angle_rad[start])
    return (dx - rolled) / dx


def classify(rolled_away: bool, slip: float) -> str:
    """``held`` / ``brake_slip`` / ``tyre_skid`` from the roll-away gate and the slip ratio."""
    if not rolled_away:
        return "held"
    return "tyre_skid" if slip > TYRE_SKID_SLIP else "brake_slip"
