"""The verdict of one parked case: holds or rolls away, and why (:class:`HoldVerdict`).

:func:`analytic_verdict` combines the pieces of :mod:`rollaway.hold.closed_form` (or, for a
model with effects, their numeric versions in :mod:`rollaway.hold.numeric`) into one answer
over [0, duration_s]: least brake margin, slip time, tyre margin, least hand force, outcome.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from rollaway.hold.closed_form import (Model, _params, hold_margin, min_brake_margin, minimum_hand_force_N,
                                       self_locking, time_to_slip_s, tyre_adhesion_margin)

OUTCOMES = ("held", "brake_slip", "tyre_skid", "self_locking")


@dataclass(frozen=True)
class HoldVerdict:
    """Outcome of the analytic check of one parked case over [0, duration_s].

    Attributes
    ----------
    brake_margin_min : float
        Least brake hold margin ``2·T_gen/T_req`` over the duration [–]; ≥ 1 holds.
    tyre_margin : float
        Rear-tyre adhesion margin ``μ_r·N_r / (m g sin θ)`` [–]; ≥ 1 holds.
    time_to_slip_s : float
        When the brake margin first falls below 1 [s]; NaN if the brake holds for the whole duration.
    holds : bool
        True when both margins stay ≥ 1.
    reason : str
        ``"holds"`` or what gives way, in words.
    outcome : str
        One of :data:`OUTCOMES`: ``held``, ``brake_slip``, ``tyre_skid``, ``self_locking``.
    least_hand_force_N : float or None
        Least lever force [N] whose brake margin stays ≥ 1 over the duration; None where no hand
        force can hold (the tyres slide, the shoe self-locks, or μ_d = 0).
    risk : rollaway.uncertainty.draws.Risk or None
        With ``uncertainty=N`` (:func:`rollaway.hold`): the N draws from the model's covariance.
    """

    brake_margin_min: float
    tyre_margin: float
    time_to_slip_s: float     # NaN if the brake holds for the whole duration
    holds: bool
    reason: str
    outcome: str = "held"                      # one of OUTCOMES
    least_hand_force_N: float | None = None    # None where no hand force can hold (tyres, self-locking, μ_d = 0)
    risk: object | None = field(default=None, repr=False, compare=False)   # rollaway.uncertainty.draws.Risk

    @property
    def slip_time_s(self) -> float | None:
        """When the brake first slips [s]; None if it holds for the whole duration."""
        return None if not np.isfinite(self.time_to_slip_s) else float(self.time_to_slip_s)

    @property
    def rollaway_probability(self) -> float | None:
        """Share of the parameter draws that roll away [–] (None without ``uncertainty``)."""
        return None if self.risk is None else self.risk.rollaway_probability

    def _repr_html_(self) -> str:  # notebooks
        from rollaway.display import result_html
        head = "HOLDS" if self.holds else f"ROLLS AWAY ({self.reason})" if self.outcome != "self_locking" \
            else f"SELF-LOCKING: {self.reason}"
        rows = {k: v for k, v in self.as_dict().items() if k not in ("holds", "reason", "uncertainty")}
        if self.risk is not None:
            rows["rollaway_probability"] = self.rollaway_probability
        return result_html(head, rows, self.holds)

    def as_dict(self) -> dict:
        out = {"verdict": self.outcome, "holds": self.holds, "reason": self.reason,
               "brake_margin_min": _finite_or_none(self.brake_margin_min), "slip_time_s": self.slip_time_s,
               "tyre_margin": _finite_or_none(self.tyre_margin), "least_hand_force_N": self.least_hand_force_N}
        if self.risk is not None:
            out["uncertainty"] = self.risk.as_dict()
        return out


def _finite_or_none(x: float):
    return float(x) if np.isfinite(x) else None


def analytic_verdict(params: Model, *, hand_force_N: float, grade_pct: float, direction: str,
                     occupants: int, duration_s: float, initial_temp_C: float | None = None,
                     mu_drum: float | None = None) -> HoldVerdict:
    """Check one case over [0, duration_s]: least brake margin, slip time, tyre margin, least hand force.

    A self-locking shoe (eqs. 18–21) is outside the 1D model: outcome ``self_locking``, not a hold.
    """
    tyre = float(tyre_adhesion_margin(params, grade_pct, direction, occupants))
    if bool(self_locking(params, grade_pct, direction, mu_drum)):
        mu = _params(params).mu_drum if mu_drum is None else mu_drum
        return HoldVerdict(np.inf, tyre, np.nan, False,
                           f"the shoe self-locks (μ_d = {mu:g} ≥ l_f/l_fr, eqs. 18–21): outside the 1D model, "
                           f"no finite torque to check", "self_locking", None)
    t_slip = float(time_to_slip_s(params, hand_force_N, grade_pct, direction, occupants, mu_drum, None,
                                  initial_temp_C, horizon_s=duration_s))
    brake_min = float(min_brake_margin(params, hand_force_N, grade_pct, direction, occupants, duration_s,
                                       mu_drum, None, initial_temp_C))
    fmin = float(minimum_hand_force_N(params, grade_pct, direction, occupants, duration_s, mu_drum, None,
                                      initial_temp_C))
    least_force = fmin if (np.isfinite(fmin) and tyre >= 1.0) else None
    reasons = []
    if brake_min < 1.0:
        reasons.append(f"brake slips at t = {t_slip:.0f} s" if np.isfinite(t_slip) else "brake slips")
    if tyre < 1.0:
        reasons.append("rear tyres skid (adhesion)")
    m_start = float(hold_margin(params, 0.0, hand_force_N, grade_pct, direction, occupants, mu_drum, None,
                                initial_temp_C))
    outcome = "held" if not reasons else ("tyre_skid" if tyre < 1.0 and tyre <= m_start else "brake_slip")
    return HoldVerdict(brake_min, tyre, t_slip, not reasons, "; ".join(reasons) or "holds", outcome, least_force)
