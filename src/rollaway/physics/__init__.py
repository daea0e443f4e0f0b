"""The paper's physics as small, pure, vectorised numpy functions.

One module per physical part; every function names its source equation
(Ishak et al. 2018, Ingeniería Investigación y Tecnología 19(1),
doi:10.22201/fi.25940732e.2018.19n1.004) or textbook, and carries units in
its argument names.  Orchestration lives in :mod:`rollaway.model.brake` and
:mod:`rollaway.hold`.
"""
from rollaway.physics.cooling import cooling_time_constant_s, drum_temperature_C, temperature_change_K
from rollaway.physics.drum import (
    brake_torque_Nm,
    lining_displacement_m,
    normal_force_N,
    normal_force_unenergised_N,
    self_energising_factor,
    direction_sign,
)
from rollaway.physics.vehicle import (
    grade_angle_rad,
    required_torque_Nm,
    rear_axle_load_N,
    slope_force_N,
    vehicle_mass_kg,
    centre_of_gravity_m,
)

__all__ = [
    "cooling_time_constant_s", "drum_temperature_C", "temperature_change_K",
    "brake_torque_Nm", "lining_displacement_m", "normal_force_N", "normal_force_unenergised_N",
    "self_energising_factor", "direction_sign",
    "grade_angle_rad", "required_torque_Nm", "rear_axle_load_N", "slope_force_N",
    "vehicle_mass_kg", "centre_of_gravity_m",
]
