"""A reliability study of a population: the rate, what drives it, the design that meets a target.

As in OpenTURNS, a study is three objects — the model (:mod:`rollaway.risk.limit_state`), the input
distribution (:class:`~rollaway.risk.population.Population`) and an algorithm
(:mod:`rollaway.risk.estimators`, :mod:`rollaway.risk.sensitivity`, :mod:`rollaway.risk.design`) —
put together by :func:`run_study`; :class:`RiskResult` is its answer as data (``as_dict``, JSON keys
``probability``, ``ci95``, ``ppm``, ``method``, ``samples``, ``brake``, ``tyres``, ``sensitivity``,
``design``, ``simulation``) and as text (``summary``).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from rollaway.errors import UserError, ensure_parent_dir
from rollaway.risk.estimators import Estimate, estimate
from rollaway.risk.population import Population, load_population

SIM_THRESHOLD = 0.005      # the simulator's measured hold/slip and tyre thresholds: within 0.5 % (docs/simulator.md)
SIM_POOL = 100_000         # cars sampled to choose the ones nearest the boundary for --simulate


@dataclass
class RiskResult:
    """The answer of a study: rate with interval and method, modes, and the optional parts."""

    population: Population
    estimate: Estimate
    sensitivity: object | None = None          # rollaway.risk.sensitivity.Sensitivity
    design: object | None = None               # rollaway.risk.design.Design
    simulation: dict | None = None
    charts: list[str] = field(default_factory=list)
    wall_time_s: float = 0.0

    @property
    def probability(self) -> float:
        return self.estimate.total.probability

    @property
    def ci95(self) -> tuple[float, float]:
        return self.estimate.total.ci95

    @property
    def ppm(self) -> float:
        return self.probability * 1e6

    def as_dict(self) -> dict:
        e = self.estimate
        out = {"population": self.population.as_dict(), **e.total.as_dict(), "method": e.method,
               "samples": e.samples, "brake": e.brake.as_dict(), "tyres": e.tyres.as_dict(),
               "estimator": dict(e.detail)}
        if self.sensitivity is not None:
            out["sensitivity"] = self.sensitivity.as_dict()
        if self.design is not None:
            out["design"] = self.design.as_dict()
        if self.simulation is not None:
            out["simulation"] = self.simulation
        out["charts"] = list(self.charts)
        out["wall_time_s"] = self.wall_time_s
        return out

    def summary(self) -> str:
        e, lo_hi = self.estimate, self.ci95
        pop = self.population
        lines = [f"population {pop.name}: {', '.join(pop.names) or 'nothing'} varied, facing "
                 f"{' and '.join(pop.directions)}, model {pop.model.name}",
                 f"roll-away rate {_ppm(self.probability)} (95 % interval {_ppm(lo_hi[0])} – {_ppm(lo_hi[1])}), "
                 f"method {e.method}, {e.samples} cars evaluated"]
        if np.isfinite(e.brake.probability):
            lines.append(f"  brake slips {_ppm(e.brake.probability)}, rear tyres skid {_ppm(e.tyres.probability)}")
        if self.sensitivity is not None:
            s = self.sensitivity
            lines.append("what drives the least brake margin (Sobol total / first-order index):")
            for n in s.ranked():
                i = s.names.index(n)
                lines.append(f"  {n:28s} {s.total[i]:6.3f} ± {s.total_ci[i]:.3f}   {s.first[i]:6.3f} ± {s.first_ci[i]:.3f}")
        if self.design is not None:
            d = self.design
            lines.append(f"design: {d.side} {d.name} = {d.value:.6g} keeps the rate ≤ {_ppm(d.target)} "
                         f"(rate there {_ppm(d.probability)}, {d.method})")
        if self.simulation is not None:
            s = self.simulation
            lines.append(f"MuJoCo: {s['confirmed']} of {s['simulated']} analytic verdicts near the boundary "
                         f"confirmed; {s['flipped_outside_threshold']} flipped outside the simulator's "
                         f"±{SIM_THRESHOLD:.1%} threshold")
        lines += [f"wrote {c}" for c in self.charts]
        return "\n".join(lines)

    def _repr_html_(self) -> str:  # notebooks
        from rollaway.display import result_html
        rows = {"probability": self.probability, "ci95": f"{self.ci95[0]:.3g} – {self.ci95[1]:.3g}",
                "ppm": self.ppm, "method": self.estimate.method, "samples": self.estimate.samples}
        return result_html(f"fleet roll-away rate of {self.population.name}", rows, self.probability == 0)


def _ppm(p: float) -> str:
    if not np.isfinite(p):
        return "n/a"
    return f"{p * 1e6:.3g} ppm" if p < 1e-3 else f"{p:.3%}"


def simulate_boundary(population: Population, n: int, seed: int | None = 0, simulate_fn=None) -> dict:
    """Run the *n* sampled cars nearest the boundary in MuJoCo; count the analytic verdicts it confirms.

    The cars are the n of :data:`SIM_POOL` sampled ones whose least margin (brake or tyres, the
    model without its own scatter) is nearest 1; each is simulated facing the direction of its least
    margin.  A flip (simulator and analytic check disagree) counts against the check only where the
    margin is further than :data:`SIM_THRESHOLD` from 1.
    """
    from rollaway.risk.limit_state import margins

    if n < 1:
        raise UserError(f"--simulate {n} must be ≥ 1 cars")
    if simulate_fn is None:
        from rollaway.sim import simulate as simulate_fn
    rng = np.random.default_rng(seed)
    u = rng.standard_normal((SIM_POOL, population.dim))
    vals = population.values_from_normal(u)
    per_dir = {d: margins(_facing(population, d), vals, SIM_POOL) for d in population.directions}
    least = np.min([m.least for m in per_dir.values()], axis=0)
    pick = np.argsort(np.abs(least - 1.0))[:n]
    cars = []
    for i in pick:
        d = min(per_dir, key=lambda k: per_dir[k].least[i])
        m = per_dir[d]
        changes = {k: (int(round(v[i])) if k == "occupants" else float(v[i])) for k, v in vals.items()}
        scen = population.base.replace(direction=d, **changes)
        res = simulate_fn(scen)
        analytic_rolls = bool(m.least[i] < 1.0)
        sim_rolls = res.outcome != "held"
        cars.append({"values": changes, "direction": d, "brake_margin": float(m.brake[i]),
                     "tyre_margin": float(m.tyre[i]), "analytic": "rolls" if analytic_rolls else "holds",
                     "simulated": res.outcome, "agree": analytic_rolls == sim_rolls,
                     "inside_threshold": bool(abs(m.least[i] - 1.0) <= SIM_THRESHOLD)})
    confirmed = sum(c["agree"] for c in cars)
    flips = sum((not c["agree"]) and not c["inside_threshold"] for c in cars)
    return {"simulated": len(cars), "confirmed": confirmed, "flipped_outside_threshold": flips,
            "threshold": SIM_THRESHOLD, "cars": cars}


def _facing(population: Population, direction: str) -> Population:
    import dataclasses
    return dataclasses.replace(population, directions=(direction,))


def run_study(population, *, samples: int = 1_000_000, method: str = "auto", seed: int | None = 0,
              sensitivity: bool = False, sensitivity_samples: int | None = None, design: str | None = None,
              target: float | None = None, chart: str | Path | None = None, simulate: int = 0,
              executor: str = "local", dask_address: str | None = None, progress: bool = False,
              params: str | None = None) -> RiskResult:
    """The study of *population* (a Population or a population file); see :func:`rollaway.api.risk`."""
    t0 = time.perf_counter()
    pop = population if isinstance(population, Population) else load_population(population, params=params)
    if (design is None) != (target is None):
        raise UserError("--design NAME and --target P go together: give both (e.g. --design hand_force_N "
                        "--target 1e-5) or neither")
    if chart is not None:
        chart = ensure_parent_dir(chart, "--chart")
        if not sensitivity and design is None:
            raise UserError("--chart draws the sensitivity or design chart; add --sensitivity or --design")
    from rollaway.risk.executors import executor_for
    runner = executor_for(executor, dask_address)
    try:
        with _bar(progress, samples) as advance:
            est = estimate(pop, method, samples, seed, progress=advance, executor=runner)
    finally:
        if runner is not None:
            runner.close()
    result = RiskResult(pop, est)
    if sensitivity:
        from rollaway.risk.sensitivity import BASE_SAMPLES, sensitivity_chart, sobol_indices
        result.sensitivity = sobol_indices(pop, sensitivity_samples or BASE_SAMPLES, seed)
        if chart is not None:
            result.charts.append(sensitivity_chart(result.sensitivity, chart, f"What drives {pop.name}"))
    if design is not None:
        from rollaway.risk.design import design as solve, design_chart
        result.design = solve(pop, design, float(target), samples, seed)
        if chart is not None:
            path = Path(chart)
            path = path.with_name(path.stem + "-design" + path.suffix) if sensitivity else path
            result.charts.append(design_chart(result.design, path))
    if simulate:
        result.simulation = simulate_boundary(pop, int(simulate), seed)
    result.wall_time_s = time.perf_counter() - t0
    return result


class _bar:
    """A rich progress bar with ETA over the cars of the rate estimate (nothing when off)."""

    def __init__(self, on: bool, total: int):
        self.on, self.total, self.progress = on, total, None

    def __enter__(self):
        if not self.on:
            return None
        from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn
        self.progress = Progress(TextColumn("cars"), BarColumn(), TextColumn("{task.completed}/{task.total}"),
                                 TimeRemainingColumn(), transient=True)
        self.progress.start()
        task = self.progress.add_task("risk", total=self.total)
        return lambda n: self.progress.advance(task, n)

    def __exit__(self, *exc):
        if self.progress is not None:
            self.progress.stop()
        return False
