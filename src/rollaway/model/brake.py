"""The paper's drum model for one parameter set, as plain functions.

:func:`drum_brake` is :meth:`rollaway.model.drum_model.DrumModel.evaluate` of a model without effects
(the one drum chain lives in :mod:`rollaway.model.drum_model`); the helpers below give the pieces the
closed-form hold check needs.  Everything broadcasts (numpy rules).
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from rollaway.model.drum_model import BrakeSeries, DrumModel, as_model
from rollaway.model.parameters import BrakeParameters, paper
from rollaway.physics import drum


def drum_temperature(params: BrakeParameters, time_s: ArrayLike, initial_temp_C: ArrayLike | None = None,
                     heat_transfer_W_m2K: ArrayLike | None = None) -> np.ndarray:
    """Drum temperature over time, eq. (10), for a parameter set [°C]."""
    return as_model(params).drum_temperature(time_s, initial_temp_C=initial_temp_C,
                                              heat_transfer_W_m2K=heat_transfer_W_m2K)


def unenergised_force(params: BrakeParameters, u6_m: ArrayLike, delta_T_K: ArrayLike,
                      gap_m: ArrayLike | None = None) -> np.ndarray:
    """Eq. (16a)/(16b) with the set's material values [N]."""
    return DrumModel(params).unenergised_force(u6_m, delta_T_K, gap_m=None if gap_m is None else np.asarray(gap_m, float))


def shoe_factor(params: BrakeParameters, direction, mu_drum: ArrayLike | None = None) -> np.ndarray:
    """Self-energising factor of eqs. (18)–(21) for a direction (``inf`` where self-locked)."""
    mu = params.mu_drum if mu_drum is None else mu_drum
    return drum.self_energising_factor(mu, drum.direction_sign(direction), params.shoe_arm_normal_m,
                                       params.shoe_arm_friction_m)


def drum_brake(params: BrakeParameters | None = None, *, time_s: ArrayLike, hand_force_N: ArrayLike,
               direction="downhill", mu_drum: ArrayLike | None = None, gap_m: ArrayLike | None = None,
               initial_temp_C: ArrayLike | None = None) -> BrakeSeries:
    """The paper's model (docs/model.md, the chain) for one drum; any argument may be an array."""
    return as_model(paper() if params is None else params).evaluate(
        time_s, hand_force_N, direction, mu_drum=mu_drum, gap_m=gap_m, initial_temp_C=initial_temp_C)
