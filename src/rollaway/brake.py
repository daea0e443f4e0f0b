"""The baseline drum parking-brake model: hand force → u_6 → F_l → torque, over the cooling.

This module only orchestrates the pure functions of :mod:`rollaway.physics` for one
parameter set.  Everything broadcasts: pass arrays of time, hand force, direction,
μ_d, gap or T_0 and get arrays back (numpy broadcasting rules).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from rollaway.parameters import BrakeParameters, paper
from rollaway.physics import cooling, drum


@dataclass(frozen=True)
class BrakeSeries:
    """Time series of one drum (arrays broadcast to a common shape)."""

    time_s: np.ndarray
    drum_temp_C: np.ndarray
    normal_force_N: np.ndarray
    torque_Nm: np.ndarray
    self_locked: np.ndarray   # True where l_f − s·μ_d·l_fr ≤ 0 (eqs. 18–21): torque is unbounded

    def columns(self) -> dict[str, np.ndarray]:
        return {"time_s": self.time_s, "drum_temp_C": self.drum_temp_C,
                "normal_force_N": self.normal_force_N, "torque_Nm": self.torque_Nm}


def drum_temperature(params: BrakeParameters, time_s: ArrayLike, initial_temp_C: ArrayLike | None = None,
                     heat_transfer_W_m2K: ArrayLike | None = None) -> np.ndarray:
    """Drum temperature over time, eq. (10), for a parameter set [°C]."""
    t0 = params.initial_drum_temp_C if initial_temp_C is None else initial_temp_C
    h = params.heat_transfer_W_m2K if heat_transfer_W_m2K is None else heat_transfer_W_m2K
    tau = cooling.cooling_time_constant_s(params.drum_density_kg_m3, params.drum_specific_heat_J_kgK,
                                          params.drum_volume_m3, h, params.cooled_area_m2)
    return cooling.drum_temperature_C(time_s, t0, params.ambient_temp_C, tau)


def unenergised_force(params: BrakeParameters, u6_m: ArrayLike, delta_T_K: ArrayLike,
                      gap_m: ArrayLike | None = None) -> np.ndarray:
    """Eq. (16a)/(16b) with the set's material values [N]."""
    return drum.normal_force_unenergised_N(
        u6_m, delta_T_K, drum_area_m2=params.drum_area_m2, drum_modulus_Pa=params.drum_modulus_Pa,
        lining_area_m2=params.lining_area_m2, lining_modulus_Pa=params.lining_modulus_Pa,
        drum_expansion_per_K=params.drum_expansion_per_K, lining_expansion_per_K=params.lining_expansion_per_K,
        drum_thickness_m=params.drum_thickness_m, lining_thickness_m=params.lining_thickness_m,
        gap_m=params.gap_m if gap_m is None else np.asarray(gap_m, float))


def shoe_factor(params: BrakeParameters, direction, mu_drum: ArrayLike | None = None) -> np.ndarray:
    """Self-energising factor of eqs. (18)–(21) for a direction (``inf`` where self-locked)."""
    mu = params.mu_drum if mu_drum is None else mu_drum
    return drum.self_energising_factor(mu, drum.direction_sign(direction), params.shoe_arm_normal_m,
                                       params.shoe_arm_friction_m)


def drum_brake(params: BrakeParameters | None = None, *, time_s: ArrayLike, hand_force_N: ArrayLike,
               direction="downhill", mu_drum: ArrayLike | None = None, gap_m: ArrayLike | None = None,
               initial_temp_C: ArrayLike | None = None) -> BrakeSeries:
    """Run the paper's model (docs/model.md, "Model chain" items 1–7) for one drum.

    Parameters default to the set's values; any of them may be an array.
    """
    p = paper() if params is None else params
    mu = p.mu_drum if mu_drum is None else np.asarray(mu_drum, float)
    t0 = p.initial_drum_temp_C if initial_temp_C is None else np.asarray(initial_temp_C, float)
    temp = drum_temperature(p, time_s, t0)
    dT = cooling.temperature_change_K(temp, t0)
    u6 = drum.lining_displacement_m(hand_force_N, p.u6_slope_m_per_N, p.u6_offset_m)
    f0 = unenergised_force(p, u6, dT, gap_m)
    factor = shoe_factor(p, direction, mu)
    f_l = drum.normal_force_N(f0, factor)
    torque = drum.brake_torque_Nm(mu, f_l, p.drum_radius_m)
    shape = np.broadcast_shapes(np.shape(time_s), np.shape(temp), np.shape(f_l))
    b = lambda a: np.broadcast_to(np.asarray(a, float), shape)  # noqa: E731
    return BrakeSeries(time_s=b(time_s), drum_temp_C=b(temp), normal_force_N=b(f_l), torque_Nm=b(torque),
                       self_locked=np.broadcast_to(np.isinf(factor), shape))
