"""How far the fits of a diagnosis end from their optimum: every least-squares fit ``diagnose`` makes on a log, refitted
from the same start with a larger budget.

    PYTHONPATH=src python benchmarks/check_fit_convergence.py                  # 4 of the short high-rate logs
    PYTHONPATH=src python benchmarks/check_fit_convergence.py --logs h14,g13 --factor 4

The logs are those of ``benchmarks/bench_diagnose.py --short-high-rate`` (by their tags: h00–h23, g00–g19), written
to CSV and read as the CLI reads them (reduced to window means).  Each fit's problem (:class:`rollaway.identify.fitting.
Problem`: the model, the data, its free parameters, the start and the options) is captured as ``diagnose`` poses it,
then solved twice more in this process: with its own budget (the reference: the same numbers) and with *factor* times
the iterations per pass.  Printed, for the fits with the full budget and for those with short budgets of their own
(screens, re-formed fits: short on purpose): how many end more than 1, 10 and 50 in χ² (the sum of squared
standardised residuals, the unit of the BIC differences the selection decides on) above the larger budget's end,
and the evaluations each took.  A measure for a change of the minimiser (``rollaway.identify.solver``); not a test.
"""
from __future__ import annotations

import argparse
import copy
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))     # tests.identify.bench_generator


def captured_problems(paths: list[Path]) -> list[tuple]:
    """(problem, start, args, kwargs) of every :meth:`Problem.solve` call of ``diagnose`` on each log of *paths*,
    fitted one after another (``ROLLAWAY_WORKERS=1`` semantics: the calls of this process only)."""
    import rollaway.identify.fitting as fitting
    import rollaway.identify.workers as workers
    from rollaway.api import diagnose
    from rollaway.cli.identify_common import load_data
    caught = []
    solve = fitting.Problem.solve

    def capture(self, start, *args, **kwargs):
        caught.append((copy.copy(self), dict(start), args, dict(kwargs)))
        return solve(self, start, *args, **kwargs)

    cores = workers.cores
    fitting.Problem.solve, workers.cores = capture, (lambda: 1)
    try:
        for path in paths:
            diagnose(load_data(path))
    finally:
        fitting.Problem.solve, workers.cores = solve, cores
    return caught


def refit(problem, start, args, kwargs, factor: float):
    """The captured fit solved again with *factor* times its iterations per pass: (χ², evaluations)."""
    from rollaway.identify.fitting import MAX_ITERATIONS
    p = copy.copy(problem)
    p.nfev, p._profiled = 0, None
    kw = dict(kwargs)
    kw["max_iterations"] = int(round(factor * kw.get("max_iterations", MAX_ITERATIONS)))
    s = p.solve(start, *args, **kw)
    return float(s.residual @ s.residual), s.nfev, s.gave_up


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--logs", default="h14,g13,g07,g00", help="tags of bench_diagnose's short high-rate logs")
    ap.add_argument("--factor", type=float, default=4.0, help="the larger budget, in times the fit's own")
    a = ap.parse_args(argv)
    from bench_diagnose import short_high_rate_sets
    from tests.identify.bench_generator import generate
    sets = dict((name.split()[0], kw) for name, kw in short_high_rate_sets())
    tags = [t.strip() for t in a.logs.split(",") if t.strip()]
    unknown = [t for t in tags if t not in sets]
    if unknown:
        sys.exit(f"--logs {unknown[0]}: not a log of bench_diagnose --short-high-rate (h00–h23, g00–g19)")
    with tempfile.TemporaryDirectory() as tmp:
        paths = []
        for t in tags:
            paths.append(Path(tmp) / f"{t}.csv")
            generate(**sets[t]).to_csv(paths[-1])
        caught = captured_problems(paths)
    own = [refit(*c, 1.0) for c in caught]
    more = [refit(*c, a.factor) for c in caught]
    from rollaway.identify.fitting import MAX_ITERATIONS
    print(f"logs {', '.join(tags)}: {len(caught)} fits (screens given up against a bar left out)")
    full = [c[3].get("max_iterations", MAX_ITERATIONS) >= MAX_ITERATIONS for c in caught]
    for label, want in ((f"full budget ({MAX_ITERATIONS} iterations per parameter and pass)", True),
                        ("short budgets (screens, re-formed fits)", False)):
        kept = [i for i, (o, m) in enumerate(zip(own, more)) if not o[2] and not m[2] and full[i] == want]
        if not kept:
            continue
        excess = np.array([own[i][0] - more[i][0] for i in kept])
        e_own, e_more = sum(own[i][1] for i in kept), sum(more[i][1] for i in kept)
        print(f"{label}, {len(kept)} fits: χ² above the end with {a.factor:g}× the budget more than 1 in "
              f"{int((excess > 1).sum())}, more than 10 in {int((excess > 10).sum())}, more than 50 in "
              f"{int((excess > 50).sum())}; largest {excess.max():.1f}; below it in {int((excess < -1).sum())}; "
              f"evaluations {e_own} → {e_more} (ratio {e_more / max(e_own, 1):.2f})")


if __name__ == "__main__":
    main()
