"""Identify the user's drum from bench data: calibrate it, select the effects the paper's model misses,
the error ladder, compare, reports.

Modules: :mod:`~rollaway.identify.model` (the drum model on measurement rows), :mod:`~rollaway.identify.fitting`
and :mod:`~rollaway.identify.calibrate` (least squares with statistics), :mod:`~rollaway.identify.drum` (which
brake parameters the data identify), :mod:`~rollaway.identify.residuals` and :mod:`~rollaway.identify.shape`
(structure left in the residuals, its flexible shape), :mod:`~rollaway.identify.selection` and
:mod:`~rollaway.identify.coarse` (effect selection, on coarser copies of dense logs),
:mod:`~rollaway.identify.diagnose`, :mod:`~rollaway.identify.compare`, :mod:`~rollaway.identify.ladder` and
:mod:`~rollaway.identify.ladder_plot`, :mod:`~rollaway.identify.report` and
:mod:`~rollaway.identify.report_figures`, :mod:`~rollaway.identify.export` (a fit as a model file),
:mod:`~rollaway.identify.synth` (synthetic bench data from a model).

Bench logs are read by :mod:`rollaway.bench`; ``rollaway.identify.load_measurements`` and
``Measurements`` (and the effect names once re-exported here) still work for one release, with a
DeprecationWarning naming the new path.
"""
from rollaway._moved import lazy_getattr

_NAMES = {"BenchModel": "rollaway.identify.model"}
_MOVED = {"Measurements": "rollaway.bench.measurements", "load_measurements": "rollaway.bench.measurements",
          **{name: "rollaway.effects" for name in ("CATALOGUE", "Effect", "EffectParameter", "available_effects",
                                                   "get_effect", "load_effect_file", "register_effect")}}
__all__ = sorted(_NAMES)
__getattr__ = lazy_getattr(__name__, _NAMES, _MOVED)
