"""Facing a direction the bench did not test: what the road bands do there.

Held-out tests of one direction rank how the competing effect sets fit it, not how they carry over to the other:
:func:`mixture_parts` moves their weights toward even (:data:`UNTESTED_DIRECTION_SHARE`).  :func:`untested_direction`
says when the held installation gap is drawn too (its split with μ_d decides the torque there,
:func:`rollaway.uncertainty.draws.draw_values` ``marginal``).  And one direction pins the torque scale
μ_d·r_d·A·E (eq. 17b), not the friction coefficient of the self-energising factors (eqs. 18–21) that carry the
tested torque over to the other direction: :func:`untested_direction_factor` and :func:`carry_factor` draw that
coefficient apart from μ_d where :func:`carried_over` says the effective direction was not tested.  Used by
:func:`rollaway.uncertainty.draws.rollaway_risk`, :func:`~rollaway.uncertainty.draws.least_force_band` and the
fleet's car-by-car draws (:mod:`rollaway.risk.limit_state`).
"""
from __future__ import annotations

import numpy as np

from rollaway.model.drum_model import DrumModel

UNTESTED_DIRECTION_SHARE = 0.5   # [assumed] in a direction the bench did not test, the held-out weights (scores of the
                                 # tested direction) keep this share; the rest is split evenly among the sets


def mixture_parts(model: DrumModel, direction: str | None = None) -> list[tuple[float, DrumModel]]:
    """[(weight, model)] of the predictive mixture: the calibrated model (1 − Σ alternatives' weights) and its
    competing effect sets.  Facing a *direction* the bench did not test, the weights move toward even
    (:data:`UNTESTED_DIRECTION_SHARE`): held-out tests of one direction rank how the sets fit it, not how they
    carry over to the other, where they part most (μ_d against the clamp scale, one direction's confounding)."""
    parts = [(1.0 - sum(w for w, _ in model.alternatives), model)] + list(model.alternatives)
    dirs = model.predictive.get("tested_directions")
    if direction and dirs and direction not in dirs and len(parts) > 1:
        s, k = UNTESTED_DIRECTION_SHARE, len(parts)
        parts = [(s * w + (1.0 - s) / k, m) for w, m in parts]
    return parts


def untested_direction(model: DrumModel, direction: str | None) -> bool:
    """True when *model*'s bench tested only the other direction: there the torque's split between μ_d and the
    held installation gap (the same torque in the tested direction, eq. 16b against eqs. 18–21) is drawn too
    (:func:`~rollaway.uncertainty.draws.draw_values` ``marginal``): a gap or a thicker lining than assumed leaves
    μ_d fitted low, and a μ_d too low predicts too much torque the other way."""
    dirs = model.predictive.get("tested_directions")
    return bool(direction and dirs and direction not in dirs)


FRICTION_PRIOR = (0.4, 0.25)    # [assumed] the lining's friction coefficient alone: the set's μ_d with a relative
                                # spread of 25 % (drum linings of 0.3–0.5)
SCALE_REL_SD = 0.3              # [assumed] relative spread of the rest of the torque scale μ_d·r_d·A·E/l (eq. 17b) of
                                # real drums around the set's: radius, lining modulus and thickness, drum stiffness


def untested_direction_factor(model: DrumModel, vals: dict, n: int, sign, seed) -> np.ndarray:
    """Facing a direction the bench did not test: the factor on each of *n* draws' torque that replaces the
    direction ratio of its fitted μ_d by that of a friction coefficient drawn apart from it (*vals*: the draws of
    :func:`~rollaway.uncertainty.draws.draw_values`; *sign*: +1 downhill, −1 uphill, broadcast against the draws).

    Tests in one direction pin the torque scale μ_d·r_d·A·E (eq. 17b), not μ_d itself: a drum with a softer or
    thicker lining, or another radius, is fitted with another μ_d (held-out band campaign 41: a 5 mm lining of
    170 MPa, μ_d fitted 0.15 for a friction coefficient of 0.36, and the uphill band 1.08–1.50 above a truth of
    1.04).  The other direction's torque follows the tested one's through the self-energising factors
    k(μ, s) = l_f / (l_f − s·μ·l_fr) of eqs. (18)–(21), whose μ is the friction coefficient alone.  Each draw's μ is
    drawn from its posterior given the draw's μ_d: log μ and the log of the rest of the scale are independent
    Gaussians a priori (:data:`FRICTION_PRIOR`, :data:`SCALE_REL_SD`) whose sum is log μ_d.  The factor is
    [k(μ, s)/k(μ, −s)] / [k(μ_d, s)/k(μ_d, −s)]: the tested direction's torque is unchanged.  Taken at the fitted
    μ_d, not along a friction effect's change of μ with temperature; 1 where a shoe self-locks."""
    p = model.params
    mu_d = np.asarray(vals.get("mu_drum", np.full(n, p.mu_drum)), float)
    l_f = p.shoe_arm_normal_m
    l_fr = np.asarray(vals["shoe_arm_ratio"], float) * l_f if "shoe_arm_ratio" in vals else p.shoe_arm_friction_m
    z = np.random.default_rng(None if seed is None else (int(seed), 18)).standard_normal(n)
    s = np.asarray(sign, float)
    if s.ndim:                                     # one sign per column (a grade each): draws along the rows
        mu_d, z = mu_d[:, None], z[:, None]
        l_fr = l_fr[:, None] if np.ndim(l_fr) else l_fr
    return carry_factor(mu_d, l_f, l_fr, s, z)


def carry_factor(mu_drum, arm_normal_m, arm_friction_m, sign, z) -> np.ndarray:
    """:func:`untested_direction_factor` for fitted μ_d values *mu_drum*, shoe arms l_f and l_fr [m] and standard
    normal deviates *z* (one per draw: the friction coefficient's place in its posterior), all broadcast."""
    from rollaway.physics.drum import self_energising_factor
    mu_d = np.maximum(np.asarray(mu_drum, float), 1e-6)
    w_mu, w_scale = FRICTION_PRIOR[1] ** -2, SCALE_REL_SD ** -2
    mu = np.exp((w_mu * np.log(FRICTION_PRIOR[0]) + w_scale * np.log(mu_d)) / (w_mu + w_scale)
                + np.asarray(z, float) / np.sqrt(w_mu + w_scale))
    s = np.asarray(sign, float)

    def ratio(m):
        return (self_energising_factor(m, s, arm_normal_m, arm_friction_m)
                / self_energising_factor(m, -s, arm_normal_m, arm_friction_m))
    with np.errstate(invalid="ignore", divide="ignore"):
        f = ratio(mu) / ratio(mu_d)
    return np.where(np.isfinite(f) & (f > 0.0), f, 1.0)


def carried_over(model: DrumModel, sign) -> np.ndarray | bool:
    """True where the effective direction *sign* (+1 downhill, −1 uphill; a grade below zero turns it) is one
    *model*'s bench did not test: the torque there is carried over from the tested one
    (:func:`untested_direction_factor`)."""
    dirs = model.predictive.get("tested_directions")
    if not dirs or len(dirs) > 1:
        return np.zeros(np.shape(sign), bool) if np.ndim(sign) else False
    tested = 1.0 if dirs[0] == "downhill" else -1.0
    return np.asarray(sign, float) != tested if np.ndim(sign) else float(sign) != tested


__all__ = ["FRICTION_PRIOR", "SCALE_REL_SD", "UNTESTED_DIRECTION_SHARE", "carried_over", "carry_factor",
           "mixture_parts", "untested_direction", "untested_direction_factor"]
