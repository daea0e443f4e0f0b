"""How sure are we: what the doubt of a calibrated model does to the answer.

Modules:

* :mod:`rollaway.uncertainty.heldout`: every test predicted by the model calibrated on the others
  (leave-one-test-out, linearised);
* :mod:`rollaway.uncertainty.bands`: model error, competing effect sets and the tested range, measured on
  the bench data (the model file's ``[predictive]`` record, :mod:`rollaway.model.predictive_record`);
* :mod:`rollaway.uncertainty.predictive`: that record in use: model-error draws, widened beyond the tested range;
* :mod:`rollaway.uncertainty.draws`: draws of the fitted values (covariance) with the model error →
  roll-away probability and margin bands, least-force bands;
* :mod:`rollaway.uncertainty.direction`: what those bands do facing a direction the bench did not test (the effect
  sets' weights, the gap drawn, the torque carried over with a friction coefficient drawn apart from μ_d);
* :mod:`rollaway.uncertainty.calibration_check`: do the bands hold the truth at their nominal rate on
  the user's own test design?

The names of the previous release's ``rollaway.uncertainty`` module (``rollaway_risk``, ``draw_values``,
``least_force_band``, ``Risk``) still work from here for one release, with a DeprecationWarning
naming :mod:`rollaway.uncertainty.draws`.
"""
from rollaway._moved import lazy_getattr

__all__: list[str] = []
__getattr__ = lazy_getattr(__name__, {}, {name: "rollaway.uncertainty.draws" for name in (
    "rollaway_risk", "draw_values", "least_force_band", "Risk", "MAX_REJECTION_ROUNDS", "PERCENTILES")})
