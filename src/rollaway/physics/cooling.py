"""Lumped convective cooling of the drum (paper eqs. 1/9 and 2/10).

Ishak et al. (2018) assume convection dominates (after Wolff 2010), giving Newton's
law of cooling for a lumped drum of mass ρV and heat capacity c_p.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike


def cooling_time_constant_s(density_kg_m3: ArrayLike, specific_heat_J_kgK: ArrayLike,
                            volume_m3: ArrayLike, heat_transfer_W_m2K: ArrayLike,
                            cooled_area_m2: ArrayLike) -> np.ndarray:
    """Time constant τ = ρ c_p V / (h A) of the lumped drum [s] (exponent of eq. 10)."""
    return (np.asarray(density_kg_m3, float) * specific_heat_J_kgK * volume_m3
            / (np.asarray(heat_transfer_W_m2K, float) * cooled_area_m2))


def drum_temperature_C(time_s: ArrayLike, initial_temp_C: ArrayLike, ambient_temp_C: ArrayLike,
                       time_constant_s: ArrayLike) -> np.ndarray:
    """Drum temperature after *time_s* of cooling, eq. (2)/(10) [°C].

    ``T(t) = (T_0 − T_amb)·exp(−t/τ) + T_amb``, t counted from the lever's application.
    """
    t = np.asarray(time_s, float)
    return (np.asarray(initial_temp_C, float) - ambient_temp_C) * np.exp(-t / time_constant_s) + ambient_temp_C


def temperature_change_K(drum_temp_C: ArrayLike, initial_temp_C: ArrayLike) -> np.ndarray:
    """ΔT = T(t) − T_0, eq. (1)/(9) [K]; negative while the drum cools."""
    return np.asarray(drum_temp_C, float) - initial_temp_C
