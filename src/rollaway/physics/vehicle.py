"""The parked vehicle on a slope: mass, demand torque (eq. 23) and axle loads.

The rear-axle load comes from a rigid-body static balance on the slope (any vehicle
dynamics text, e.g. Gillespie, *Fundamentals of Vehicle Dynamics*, 1992, §2; Limpert,
*Brake Design and Safety*, 1999, §7): the brake force acts at the rear contact
patches at ground level, so moments about the rear contact give the front load.
The vehicle geometry is not in the paper and is **assumed** (docs/model.md).
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

FRONT_ROW_SEATS = 2  # occupants 1–2 sit in the front row, the rest in the rear row [assumed]


def grade_angle_rad(grade_pct: ArrayLike) -> np.ndarray:
    """Slope angle θ = atan(grade/100) [rad]; 20 % → 11.31°, 30 % → 16.70°."""
    return np.arctan(np.asarray(grade_pct, float) / 100.0)


def vehicle_mass_kg(vehicle_mass: ArrayLike, occupants: ArrayLike, occupant_mass_kg: ArrayLike) -> np.ndarray:
    """m_tot = m + n·m_d (paper Table 1, Fig. 14) [kg]."""
    return np.asarray(vehicle_mass, float) + np.asarray(occupants, float) * occupant_mass_kg


def centre_of_gravity_m(occupants: ArrayLike, *, vehicle_mass_kg_, occupant_mass_kg, cg_behind_front_m,
                        cg_height_m, front_seat_behind_front_m, rear_seat_behind_front_m,
                        seat_height_m) -> tuple[np.ndarray, np.ndarray]:
    """Centre of gravity of car plus occupants: (distance behind the front axle, height) [m].

    Occupants 1 and 2 sit in the front row, 3 and up in the rear row [assumed].
    """
    n = np.asarray(occupants, float)
    n_front = np.minimum(n, FRONT_ROW_SEATS)
    n_rear = n - n_front
    m_car = vehicle_mass_kg_
    m_tot = m_car + n * occupant_mass_kg
    x = (m_car * cg_behind_front_m + occupant_mass_kg * (n_front * front_seat_behind_front_m
                                                          + n_rear * rear_seat_behind_front_m)) / m_tot
    z = (m_car * cg_height_m + occupant_mass_kg * n * seat_height_m) / m_tot
    return x, z


def slope_force_N(mass_kg: ArrayLike, grade_pct: ArrayLike, gravity_m_s2: float = 9.81) -> np.ndarray:
    """Weight component along the slope m·g·sin θ (eq. 22, right-hand side) [N]."""
    return np.asarray(mass_kg, float) * gravity_m_s2 * np.sin(grade_angle_rad(grade_pct))


def required_torque_Nm(mass_kg: ArrayLike, grade_pct: ArrayLike, wheel_radius_m: ArrayLike,
                       gravity_m_s2: float = 9.81) -> np.ndarray:
    """Torque needed at the rear axle to hold the vehicle, T_req = m g sin θ R_wheel, eq. (23) [N·m]."""
    return slope_force_N(mass_kg, grade_pct, gravity_m_s2) * wheel_radius_m


def rear_axle_load_N(mass_kg: ArrayLike, grade_pct: ArrayLike, sign: ArrayLike, *, wheelbase_m,
                     cg_behind_front_m: ArrayLike, cg_height_m: ArrayLike,
                     gravity_m_s2: float = 9.81) -> np.ndarray:
    """Static normal load on the rear axle of a vehicle parked on a slope [N].

    ``N_r = m g (a cos θ − s h sin θ) / L`` with a the CG distance behind the front axle,
    h its height, L the wheelbase and s = +1 facing downhill (weight moves to the
    lower, front axle), −1 facing uphill.  Clipped at 0 (the rear lifts off).
    """
    th = grade_angle_rad(grade_pct)
    w = np.asarray(mass_kg, float) * gravity_m_s2
    n_r = w * (np.asarray(cg_behind_front_m) * np.cos(th) - np.asarray(sign, float) * cg_height_m * np.sin(th)) / wheelbase_m
    return np.maximum(n_r, 0.0)
