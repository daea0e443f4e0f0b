"""The drum model: parameter sets, the parameters a calibration may free, the chain from lever to
wheel, :class:`DrumModel` and its files.

Modules, read in this order:

* :mod:`rollaway.model.parameters`: parameter sets (the paper's Table 1 and assumed values), validated;
* :mod:`rollaway.model.drum_parameters`: the brake parameters a calibration may free, with bounds and spreads;
* :mod:`rollaway.model.chain`: hand force → cable → shoe → clamp force → self-energising → torque, step by
  step, each with its equation and effect hook;
* :mod:`rollaway.model.drum_model`: :class:`DrumModel`, a parameter set + effects + values (+ covariance and
  predictive record); :func:`load_model`;
* :mod:`rollaway.model.covariance`, :mod:`rollaway.model.predictive_record`: what a calibration knows of its values;
* :mod:`rollaway.model.model_file`: model files (TOML) written and read;
* :mod:`rollaway.model.brake`: the paper's chain as plain functions (``rollaway brake``).

``from rollaway.model import DrumModel, load_model`` works (names are imported on first use).
"""
from rollaway._moved import lazy_getattr

_NAMES = {name: "rollaway.model.drum_model" for name in (
    "DrumModel", "load_model", "as_model", "BrakeSeries", "Covariance", "direction_to_sign",
    "BASELINE_BOUNDS", "BASELINE_FREE", "BASELINE_UNITS")}
__all__ = sorted(_NAMES)
__getattr__ = lazy_getattr(__name__, _NAMES)
