"""Sweeps: map where a design holds and where it rolls away.

``load_sweep(path)`` reads a SWEEP.toml; ``run_sweep(spec, out_dir, ...)`` runs the analytic
pass over every point, simulates the boundary band in MuJoCo (local processes or a Dask
cluster), journals each finished point, and writes ``results.parquet``/``results.csv`` and plots.
The CI gate (:mod:`rollaway.sweep.compliance`, ``rollaway check``) runs the regulation cases the same
way.  The package is also callable: ``rollaway.sweep(spec, out)`` is :func:`rollaway.api.sweep`.
"""
from rollaway.callable_module import make_callable
from rollaway.sweep.runner import SweepResult, run_sweep
from rollaway.sweep.spec import AXES, SweepSpec, grid_spec, load_sweep

__all__ = ["AXES", "SweepResult", "SweepSpec", "grid_spec", "load_sweep", "run_sweep"]

make_callable(__name__, "rollaway.api:sweep")
