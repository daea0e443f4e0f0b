"""Add effects and watch the error fall: the error ladder of ``rollaway fit``."""
from __future__ import annotations

from dataclasses import dataclass

from rollaway.identify.calibrate import FitResult, calibrate, evaluate
from rollaway.identify.enough import require
from rollaway.identify.export import CalibratedModelMixin
from rollaway.effects import get_effect
from rollaway.bench.measurements import Measurements


@dataclass
class Ladder(CalibratedModelMixin):
    """Rungs: paper defaults → calibrated baseline → + each effect in turn (each rung calibrated)."""

    data: Measurements
    rungs: list[tuple[str, FitResult]]

    @property
    def final(self) -> FitResult:
        return self.rungs[-1][1]

    @property
    def baseline(self) -> FitResult:
        return self.rungs[1][1]

    def verdict(self) -> tuple[str, bool]:
        """(one sentence on whether the last effect earned its place, True when it did by BIC)."""
        if len(self.rungs) < 3:
            return "Only the paper model was fitted; add effects with --effect.", True
        ref, last = self.rungs[1][1], self.final
        d = last.bic - ref.bic
        names = " + ".join(last.effects)
        ok = d < -10.0
        return (f"Adding {names} changes BIC by {d:+.1f} against the calibrated paper model "
                f"({'very strong evidence for it' if ok else 'not enough evidence (needs below −10)'}); torque RMSE "
                f"{ref.rmse_torque_Nm:.3g} → {last.rmse_torque_Nm:.3g} N·m, temperature RMSE {ref.rmse_temp_C:.3g} → "
                f"{last.rmse_temp_C:.3g} °C.", ok)

    def as_dict(self) -> dict:
        verdict, ok = self.verdict()
        return {"verdict": verdict, "effects_supported": ok, "ladder": [{"model": name, "rmse_torque_Nm": f.rmse_torque_Nm, "rmse_temp_C": f.rmse_temp_C,
                            "bic": f.bic if f.k else None, "k": f.k} for name, f in self.rungs],
                "parameters": {k: e.as_dict() for k, e in self.final.estimates.items()},
                "warnings": self.final.warnings,
                "data": {"source": self.data.source, "tests": self.data.n_tests, **self.data.rows_info()}}

    def table(self, width: int = 30) -> str:
        top = max(f.rmse_torque_Nm for _, f in self.rungs) or 1.0
        lines = [f"{'model':<42}{'torque RMSE':>12}{'temp RMSE':>11}{'ΔBIC':>8}  torque error"]
        ref = self.rungs[1][1].bic
        for name, f in self.rungs:
            bar = "█" * max(1, round(width * f.rmse_torque_Nm / top))
            dbic = f"{f.bic - ref:+.1f}" if f.k else ""
            lines.append(f"{name:<42}{f.rmse_torque_Nm:>10.3g}  {f.rmse_temp_C:>9.3g}  {dbic:>7}  {bar}")
        return "\n".join(lines)

    def summary(self) -> str:
        return self.verdict()[0] + "\n\n" + self.table() + "\n\n" + self.final.report()

    def _repr_html_(self) -> str:  # notebooks
        from rollaway.identify.report import esc
        return f"<p><b>{esc(self.verdict()[0])}</b></p><pre>{esc(self.table())}</pre>"

    def __repr__(self):
        return self.summary()

    def report(self, path) -> None:
        """Write a self-contained HTML report of the ladder to *path*."""
        from rollaway.identify.report import ladder_report
        ladder_report(self, path)

    def _calibrated_fit(self):
        return self.final

    def plot(self, path=None):
        from rollaway.identify.ladder_plot import ladder_figure
        fig = ladder_figure(self)
        if path is not None:
            fig.savefig(path, dpi=110, bbox_inches="tight")
        return fig


def fit(data: Measurements, effects, params=None, start: dict | None = None) -> Ladder:
    """Refit with *effects* added one after another; every rung is calibrated from the previous one."""
    chosen = [get_effect(e) for e in effects]
    rungs = [("paper defaults", evaluate(data, (), params))]
    prev = calibrate(data, (), params)
    require(data, prev.k + data.n_tests, "calibrate the paper model")
    rungs.append(("calibrated paper model (μ_d, h)", prev))
    for i, eff in enumerate(chosen):
        prev = calibrate(data, chosen[:i + 1], params, start={**prev.values, **(start or {})})
        require(data, prev.k + data.n_tests, "judge " + " + ".join(e.name for e in chosen[:i + 1]))
        rungs.append((("calibrated + " if i == 0 else "  + ") + eff.name, prev))
    return Ladder(data, rungs)
