"""The hold check: will the parked car stay put, and for how long? (docs/model.md, the hold check)

The question, then the answer.  Modules, read in this order:

* :mod:`rollaway.hold.regulations`: the regulation presets (FMVSS 135, UN R13-H: grade, force, load);
* :mod:`rollaway.hold.scenario`: a scenario (car, grade, load, direction, temperatures), validated from TOML;
* :mod:`rollaway.hold.closed_form`: input validation, required torque, brake and tyre margins,
  slip time and least hand force of the paper's chain, solved in closed form;
* :mod:`rollaway.hold.numeric`: the same quantities for a model with effects (the torque may no
  longer be monotone in time), solved numerically and vectorised;
* :mod:`rollaway.hold.verdict`: :class:`HoldVerdict`, the answer for one case.

The MuJoCo simulator (:mod:`rollaway.sim`) answers the same question in the time domain.

The names below are re-exported so ``from rollaway.hold import required_torque`` works.  The
package is also callable: ``rollaway.hold(model, grade_pct=20, ...)`` is :func:`rollaway.api.hold`.
"""
from rollaway.callable_module import make_callable
from rollaway.hold.closed_form import (MAX_HAND_FORCE_N, MAX_OCCUPANTS, NUMERIC_HORIZON_S, Model,  # noqa: F401
                                       _effective,  # (private, used by rollaway.uncertainty.draws)
                                       effective_slope, hold_margin, invalid_grade, invalid_hand_force,
                                       invalid_occupants, min_brake_margin, minimum_hand_force_N, required_torque,
                                       self_locking, time_to_slip_s, total_mass_kg, tyre_adhesion_margin,
                                       validate_grade, validate_hand_force, validate_occupants)
from rollaway.hold.verdict import OUTCOMES, HoldVerdict, analytic_verdict

__all__ = ["HoldVerdict", "MAX_HAND_FORCE_N", "MAX_OCCUPANTS", "Model", "NUMERIC_HORIZON_S", "OUTCOMES",
           "analytic_verdict", "effective_slope", "hold_margin", "invalid_grade", "invalid_hand_force",
           "invalid_occupants", "min_brake_margin", "minimum_hand_force_N", "required_torque", "self_locking",
           "time_to_slip_s", "total_mass_kg", "tyre_adhesion_margin", "validate_grade", "validate_hand_force",
           "validate_occupants"]

make_callable(__name__, "rollaway.api:hold")
