"""The Python API: what ``import rollaway`` offers, one function per job.

Every command of the ``rollaway`` CLI is a thin call of one of these functions, so what a
command does, the function does (same validation, same errors: :class:`rollaway.errors.UserError`
with a one-line message).  Units are in the names: ``_pct`` percent, ``_N`` newtons, ``_s``
seconds, ``_C`` degrees Celsius, ``_Nm`` newton-metres.

=================================  ============================================================
:class:`rollaway.DrumModel`        the drum brake: parameter set + effects (+ fitted values)
:func:`hold`                       analytic hold check of one parked case → :class:`HoldVerdict`
:func:`simulate`                   MuJoCo roll-away simulation of one scenario → ``SimResult``
:func:`sweep`                      a grid of cases: maps and design chart → ``SweepResult``
:func:`check`                      regulation presets (CI gate) → ``CheckResult``
:func:`load_measurements`          bench data (CSV) → ``Measurements``
:func:`diagnose`                   which effect is the model missing? → ``Diagnosis``
:func:`fit`                        refit with chosen effects (the error ladder) → ``Ladder``
:func:`risk`                       roll-away rate of a production population → ``RiskResult``
=================================  ============================================================

This module is imported on first use of one of these names (``rollaway.__getattr__``), so
``import rollaway`` and ``rollaway --help`` stay fast.
"""
from __future__ import annotations

import inspect
from pathlib import Path

from rollaway.errors import UserError, read_toml
from rollaway.hold import HoldVerdict, analytic_verdict
from rollaway.model.drum_model import DrumModel, as_model

__all__ = ["DrumModel", "HoldVerdict", "check", "diagnose", "fit", "hold", "load_measurements",
           "simulate", "sweep", "risk"]


def hold(model="paper", *, grade_pct: float, hand_force_N: float, direction: str, occupants: int = 0,
         duration_s: float = 300.0, initial_drum_temp_C: float | None = 200.0, uncertainty: int | None = None,
         seed: int | None = 0) -> HoldVerdict:
    """Will the parked car hold? The analytic check of one case over [0, duration_s].

    The brake holds while its margin ``2·T_gen(t)/T_req`` ≥ 1 (paper eqs. 17b, 23; T_gen falls
    as the drum cools, eq. 10); the rear tyres hold while ``μ_r·N_r/(m g sin θ)`` ≥ 1.  Closed
    forms for the paper's chain; a model with effects is solved numerically.

    Parameters
    ----------
    model : DrumModel or str or path-like, default "paper"
        The drum model, a parameter-set name, or a parameter/model file (``.toml``).
    grade_pct : float
        Road grade [%] (rise over run; 20 is a 20 % grade).  Negative flips the facing.
    hand_force_N : float
        Force on the hand lever [N] (FMVSS 135 and UN R13-H use 400 N).
    direction : str
        Which way the car faces: ``"downhill"`` or ``"uphill"``.
    occupants : int, default 0
        Number of 70 kg occupants, 0–5.
    duration_s : float, default 300
        How long the car must stay parked [s].
    initial_drum_temp_C : float or None, default 200
        Drum temperature when the lever is applied [°C]; None: the parameter set's.
    uncertainty : int, optional
        Draw this many parameter vectors from the model's covariance (a model calibrated by
        :func:`diagnose` or :func:`fit`) and give the roll-away probability.
    seed : int, default 0
        Random seed of the draws.

    Returns
    -------
    HoldVerdict
        ``.holds``, ``.brake_margin_min``, ``.slip_time_s``, ``.tyre_margin``,
        ``.least_hand_force_N``, ``.reason``; ``.rollaway_probability`` with *uncertainty*.

    Examples
    --------
    >>> import rollaway
    >>> v = rollaway.hold("paper", grade_pct=20, hand_force_N=400, direction="downhill", occupants=5)
    >>> v.holds
    True
    """
    m = as_model(model)
    v = analytic_verdict(m, hand_force_N=hand_force_N, grade_pct=grade_pct, direction=direction,
                         occupants=occupants, duration_s=duration_s, initial_temp_C=initial_drum_temp_C)
    if uncertainty is None:
        return v
    from dataclasses import replace

    from rollaway.uncertainty.draws import rollaway_risk
    risk = rollaway_risk(m, hand_force_N=hand_force_N, grade_pct=grade_pct, direction=direction, occupants=occupants,
                         duration_s=duration_s, initial_temp_C=initial_drum_temp_C, draws=uncertainty, seed=seed)
    return replace(v, risk=risk)


def build_scenario(scenario=None, *, model=None, **scenario_keys):
    """A :class:`rollaway.hold.scenario.Scenario` from a file, keys, or both (keys override the file's);
    the arguments are those of :func:`simulate`."""
    import dataclasses

    from rollaway.hold.scenario import Scenario, scenario_from_mapping
    if isinstance(scenario, Scenario):
        if scenario_keys:
            raise UserError("give a scenario file and keys to change, or a Scenario object alone; use "
                            "dataclasses.replace(scenario, ...) to change a Scenario")
        s = scenario
    else:
        data, where, base_dir = {}, "simulate()", None
        if scenario is not None:
            path = Path(scenario)
            data = read_toml(path, "scenario file", "see scenarios/*.toml for examples")
            where, base_dir = str(path), path.parent
        data = {**({"name": "python"} if scenario is None else {}), **data, **scenario_keys}
        s = scenario_from_mapping(data, where=where, base_dir=base_dir,
                                  params=None if model is None or isinstance(model, DrumModel) else str(model))
    if isinstance(model, DrumModel):
        s = dataclasses.replace(s, params=model.params, model=model)
    return s


def simulate(scenario=None, *, model=None, render=None, mode: str = "fast", render_options: dict | None = None,
             **scenario_keys):
    """Simulate a parked car held by the drum brake in MuJoCo: held, brake_slip or tyre_skid.

    Parameters
    ----------
    scenario : str or path-like or Scenario, optional
        A scenario file (``scenarios/*.toml``).  Without one, give the scenario's keys.
    model : DrumModel or str or path-like, optional
        The drum model (replaces the scenario's ``params``); default: the scenario's, else the paper set.
    render : str or path-like, optional
        Also write a video or picture of the run: ``FILE.mp4``, ``FILE.gif`` or ``FILE.png``.
    mode : str, default "fast"
        ``fast`` skips ahead while the car is provably at rest; ``fixed`` steps at 1 ms throughout.
    render_options : dict, optional
        ``size`` (width, height) [px], ``fps``, ``after_s`` [s], ``multisample``.
    **scenario_keys
        Keys of a scenario file, overriding the file's: ``grade_pct`` [%], ``direction``
        (``"downhill"``/``"uphill"``), ``occupants``, ``hand_force_N`` [N], ``duration_s`` [s],
        ``initial_drum_temp_C`` [°C], ``mu_drum`` [–], ``tyre_road_mu`` [–], ``name``, ...

    Returns
    -------
    rollaway.sim.SimResult
        ``.outcome`` (``held``, ``brake_slip``, ``tyre_skid`` or ``diverged``), ``.rollaway_time_s``
        (None if held), ``.min_margin``, ``.max_displacement_m``, ``.drum_temp_C_end``, ...

    Examples
    --------
    >>> r = rollaway.simulate(grade_pct=20, direction="downhill", occupants=5, hand_force_N=400,
    ...                       duration_s=60)                                       # doctest: +SKIP
    >>> r.outcome                                                                  # doctest: +SKIP
    'held'
    """
    from rollaway.sim import simulate as run
    return run(build_scenario(scenario, model=model, **scenario_keys), render=render, mode=mode,
               render_options=render_options)


def sweep(spec, out, *, model=None, **options):
    """Map where a design holds and where it rolls away: the analytic margin of every point, MuJoCo
    near the hold/roll boundary; a table (``results.parquet``/``.csv``) and plots in *out*.

    Parameters
    ----------
    spec : str or path-like or SweepSpec
        A sweep file (``scenarios/sweeps/*.toml``) or a spec built with :func:`rollaway.sweep.grid_spec`.
    out : str or path-like
        Output folder; running again into the same folder resumes an interrupted sweep.
    model : DrumModel or str or path-like, optional
        Drum model of every point (replaces the base scenario's; keeps its initial drum temperature).
    **options
        Of :func:`rollaway.sweep.run_sweep`: ``workers`` (local processes), ``dask_address``
        (a dask.distributed scheduler, e.g. ``"tcp://10.0.0.5:8786"``), ``simulate``
        (``"band"``, ``"all"``, ``"none"``), ``plots``, ``progress`` (default False here),
        ``retry_failed``, ``fresh``, ``uncertainty`` (N draws: each point's roll-away probability).

    Returns
    -------
    rollaway.sweep.SweepResult
        ``.table`` (a pandas DataFrame, one row per point, ``verdict`` ``hold``/``roll``), ``.files``.
    """
    from rollaway.sweep import load_sweep, run_sweep
    from rollaway.sweep.spec import SweepSpec
    s = spec if isinstance(spec, SweepSpec) else load_sweep(spec)
    if model is not None:
        s = s.with_model(as_model(model))
    if options.get("uncertainty") is not None and s.base.model.covariance is None:
        raise UserError("--uncertainty needs a model file with a [covariance] table; give --params FILE.toml "
                        "saved by 'rollaway fit --save-model' (in Python: model=, a model saved by .save_model())")
    out_dir = Path(out)
    if out_dir.exists() and not out_dir.is_dir():
        raise UserError(f"--out '{out_dir}' is a file; give a folder")
    return run_sweep(s, out_dir, **{"progress": False, **options})


def check(targets=(), *, model=None, analytic: bool = False, uncertainty: int | None = None):
    """Regulation hold checks: the CI gate (simulated in MuJoCo) or the paper's analytic check.

    Parameters
    ----------
    targets : sequence of str, default ("fmvss135", "unr13h")
        Regulation presets (``fmvss135``: FMVSS 135 S7.12; ``unr13h``: UN R13-H; ``paper30``:
        the paper's 30 % case; ``"all"``) and, simulated, scenario files (each names its own model).
    model : DrumModel or str or path-like, optional
        Drum model of the presets (default: the paper set).
    analytic : bool, default False
        Use the paper's analytic check instead of the simulation (presets only; seconds, not minutes).
    uncertainty : int, optional
        With *analytic*: N draws from the model's covariance; adds each case's roll-away probability.

    Returns
    -------
    rollaway.sweep.compliance.CheckResult
        ``.passed`` (every case holds), ``.failed`` (row numbers), ``.table()`` (pandas), ``.columns``.
    """
    from rollaway.sweep.compliance import run_check
    return run_check(targets, model, analytic=analytic, uncertainty=uncertainty)


def load_measurements(path, window_s: float | None = None, **mapping):
    """Read and validate bench measurements (CSV) for :func:`diagnose` and :func:`fit`.

    Parameters
    ----------
    path : str or path-like
        CSV file with columns ``test_id``, ``direction``, ``hand_force_N`` [N], ``time_s`` [s],
        ``drum_temp_C`` [°C], ``torque_Nm`` [N·m] (per drum), optionally ``ambient_C`` [°C].
    window_s : float or None
        None (default): a dense log is reduced to window means as the command line does (the automatic window,
        :mod:`rollaway.bench.reduction`), so the same file gives the same answer either way; 0: every sample a
        row; a whole number of seconds: that window.
    **mapping
        Passed to the loader (e.g. column names of your file) when this version's loader
        accepts them; otherwise an error says so.

    Returns
    -------
    rollaway.identify.Measurements
        Validated samples, flattened over tests; ``.tests``, ``.n_tests``, ``.to_frame()``.

    Raises
    ------
    rollaway.errors.UserError
        Listing every problem of the file (line and column) at once.
    """
    from rollaway.bench.measurements import load_measurements as load
    if mapping:
        accepted = inspect.signature(load).parameters
        unknown = [k for k in mapping if k not in accepted]
        if unknown and not any(p.kind is inspect.Parameter.VAR_KEYWORD for p in accepted.values()):
            raise UserError(f"load_measurements: this loader takes no {', '.join(unknown)}; it reads the columns "
                            f"test_id, direction, hand_force_N, time_s, drum_temp_C, torque_Nm (and ambient_C)")
    return load(path, window_s=window_s, **mapping)


def _data(data):
    """Measurements from a path or as given."""
    return load_measurements(data) if isinstance(data, (str, Path)) else data


def diagnose(data, **options):
    """Which physical effect is the paper's model missing in these bench data?

    Calibrates μ_d, h and each test's initial temperature, then selects catalogue effects forward
    (BIC, then K-fold cross-validation by test) until the residual is down to the noise.

    Parameters
    ----------
    data : str or path-like or Measurements
        A measurement CSV (see :func:`load_measurements`) or loaded measurements.
    **options
        Of :func:`rollaway.identify.diagnose.diagnose`: ``params`` (starting parameter set),
        ``effects`` (candidate effects, default: the catalogue and registered plugins),
        ``noise_torque_Nm`` [N·m], ``noise_temp_C`` [°C] (the instrument's σ), ``max_effects``.

    Returns
    -------
    rollaway.identify.diagnosis.Diagnosis
        ``.verdict`` (effect name or ``"none"``), ``.evidence``, ``.model`` (the calibrated
        :class:`DrumModel`, with covariance), ``.save_model(path)``, ``.report(path)`` (HTML).
    """
    from rollaway.identify.diagnose import diagnose as run
    return run(_data(data), **options)


def fit(data, effects, **options):
    """Refit with *effects* added one after another and watch the error fall (the error ladder).

    Parameters
    ----------
    data : str or path-like or Measurements
        A measurement CSV (see :func:`load_measurements`) or loaded measurements.
    effects : sequence of str
        Effect names in ladder order (``rollaway.identify.available_effects()`` lists them).
    **options
        ``params`` (starting parameter set), ``start`` (``{"effect.parameter": value}`` start values).

    Returns
    -------
    rollaway.identify.ladder.Ladder
        ``.rungs`` (name, fit), ``.final``, ``.verdict()``, ``.model``, ``.save_model(path)``,
        ``.report(path)``, ``.plot(path)``.
    """
    from rollaway.identify.ladder import fit as run
    return run(_data(data), list(effects), **options)


def export_fmu(model, path, **options):
    """Export a drum model as an FMI 2.0 co-simulation FMU that runs without rollaway (Simulink, Dymola,
    OpenModelica, FMPy, ...).

    The chain and every catalogue effect of the model are C code in the FMU, with the model's values
    baked in as read-only constants; a linux64 binary is compiled with the system ``gcc``.

    Parameters
    ----------
    model : DrumModel or str or path-like
        The drum model, a parameter-set name, or a parameter/model file (``.toml``, e.g. written by
        ``diagnose(...).save_model``).  A model with a plugin effect cannot be exported.
    path : str or path-like
        The ``.fmu`` file to write.
    **options
        ``stop_time_s``: stop time of the FMU's default experiment [s] (3600); ``fmi_version``:
        ``"2.0"`` (default, imported by every tool) or ``"3.0"``.

    Returns
    -------
    pathlib.Path
        The FMU written: parameters ``hand_force_N``, ``initial_drum_temp_C``, ``ambient_temp_C``,
        ``facing_uphill``; outputs ``torque_Nm`` (one rear drum), ``drum_temp_C``, ``clamp_force_N``,
        ``lining_temp_C``; time is the time since the lever was applied [s].
    """
    from rollaway.export import export_fmu as run
    return run(model, path, **options)


__all__ += ["export_fmu"]
def risk(population, *, samples: int = 1_000_000, method: str = "auto", seed: int | None = 0,
         sensitivity: bool = False, design: str | None = None, target: float | None = None, chart=None,
         simulate: int = 0, executor: str = "local", dask_address: str | None = None, params=None,
         progress: bool = False):
    """The roll-away rate of a production fleet, with its 95 % interval, what drives it and a design.

    Parameters
    ----------
    population : str or path-like or rollaway.risk.Population
        A population file (``scenarios/populations/*.toml``: a scenario's fixed values + ``[vary]``).
    samples : int, default 1000000
        Cars (limit-state evaluations) the estimate may use at most (Monte Carlo uses them all).
    method : str, default "auto"
        ``auto`` (a pilot Monte Carlo run decides), ``mc``, ``is`` (importance sampling around the FORM
        design points), ``form`` (Φ(−β) with an importance-sampling check) or ``subset`` (OpenTURNS).
    seed : int, optional
        Seed of every random draw (the same seed gives the same answer).
    sensitivity : bool, default False
        Also the Sobol first and total indices of the least brake margin per varied name (SALib).
    design, target : str and float, optional
        The least (or greatest, on the safe side) value of the fixed input *design* — or the spec limit
        ``NAME.lower``/``NAME.upper`` of a varied one — whose rate is ≤ *target*.
    chart : str or path-like, optional
        PNG of the sensitivity bars (and ``*-design.png`` of the design curve; the design curve alone
        without ``sensitivity``).
    simulate : int, default 0
        Run this many sampled cars nearest the boundary in MuJoCo and count the verdicts it confirms.
    executor, dask_address : str, optional
        ``local`` or ``dask`` (Monte Carlo chunks on a ``dask.distributed`` cluster: the scheduler at
        *dask_address*, or a local cluster).
    params : str, optional
        Another drum model for the population (a set name, parameter file or model file).
    progress : bool, default False
        A progress bar with ETA on the terminal.

    Returns
    -------
    rollaway.risk.RiskResult
        ``.probability``, ``.ci95``, ``.ppm``, ``.estimate`` (method, samples, per-mode rates),
        ``.sensitivity``, ``.design``, ``.simulation``; ``.as_dict()`` and ``.summary()``.

    Examples
    --------
    >>> r = rollaway.risk("scenarios/populations/fmvss135-production.toml", samples=200_000)  # doctest: +SKIP
    >>> r.ppm, r.ci95, r.estimate.method                                                      # doctest: +SKIP
    """
    from rollaway.risk.study import run_study
    return run_study(population, samples=samples, method=method, seed=seed, sensitivity=sensitivity,
                     design=design, target=target, chart=chart, simulate=simulate, executor=executor,
                     dask_address=dask_address, params=params, progress=progress)
