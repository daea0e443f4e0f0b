"""The result of :func:`rollaway.identify.diagnose.diagnose`: the verdict, its alternatives and evidence, the fits,
and their views — a dict / JSON, the text summary, the HTML report, the calibrated model (lmfit's split of a model
and its result: the procedure is :mod:`rollaway.identify.diagnose`)."""
from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass, field

from rollaway.bench.measurements import Measurements
from rollaway.bench.noise import Noise
from rollaway.identify.ambiguity import verdict_line
from rollaway.identify.calibrate import FitResult
from rollaway.identify.diagnose_words import score_text
from rollaway.identify.drum import DrumCalibration
from rollaway.identify.export import CalibratedModelMixin
from rollaway.identify.selection import Candidate, nested_shortfall
from rollaway.jsonsafe import to_jsonable


@dataclass
class Diagnosis(CalibratedModelMixin):
    """What :func:`diagnose` found: ``verdict`` (the missing effect, or ``"none"``), the evidence, the fits.

    ``model`` / ``save_model(path)``: the calibrated drum model of the verdict; ``report(path)``: an HTML page.
    """

    _command = "diagnose"
    data: Measurements
    paper: FitResult
    baseline: FitResult
    noise_torque: Noise
    noise_temp: Noise
    candidates: list[Candidate]          # first selection step (against the baseline), best first
    verdict: str
    indistinguishable_from: list[str]
    refined: FitResult
    remaining_structure: bool
    structure: dict
    baseline_cv: float | None
    evidence: list[str] = field(default_factory=list)
    effects: list[dict] = field(default_factory=list)     # selected, in order: {"effect", "form", ...}
    steps: list[dict] = field(default_factory=list)       # forward-selection log
    shape: dict | None = None                              # flexible form of a "partial" effect
    drum: DrumCalibration | None = None                    # which brake parameters the data identify
    alternatives: list[dict] = field(default_factory=list)  # effect sets the data cannot rule out (ambiguity.py)
    procedure: Callable | None = field(default=None, repr=False, compare=False)   # what made it (for again)
    detection: list[dict] = field(default_factory=list)    # with "none": the least size of each effect found (detection.py)
    hidden: list[dict] = field(default_factory=list)       # effects the data could miss, and the values with them

    @property
    def named(self) -> list[str]:
        """Every effect named, in order (``verdict`` is the first)."""
        return [e["effect"] for e in self.effects]

    def as_dict(self) -> dict:
        def rm(f):
            return {"rmse_torque_Nm": f.rmse_torque_Nm, "rmse_temp_C": f.rmse_temp_C, "bic": f.bic, "aic": f.aic,
                    "parameters": {k: e.as_dict() for k, e in f.estimates.items()}, **f.statistics()}
        return {"data": {"source": self.data.source, "samples": len(self.data), "tests": self.data.n_tests,
                         **self.data.rows_info()},
                "noise": {"torque_Nm": self.noise_torque.sigma, "temp_C": self.noise_temp.sigma,
                          "torque": self.noise_torque.as_dict(), "temperature": self.noise_temp.as_dict()},
                "paper": {"rmse_torque_Nm": self.paper.rmse_torque_Nm, "rmse_temp_C": self.paper.rmse_temp_C},
                "baseline": {**rm(self.baseline), "cv_score": self.baseline_cv},
                "candidates": [{**c.as_dict(), "nested_shortfall": nested_shortfall(c.fit, self.baseline)}
                               for c in self.candidates],
                "verdict": self.verdict, "verdict_line": verdict_line(self.verdict, self.alternatives, self.detection,
                                                                     self.remaining_structure, self.named),
                "alternatives": [{k: v for k, v in a.items() if not isinstance(v, FitResult)}   # fit, shape_fit
                                 for a in self.alternatives],
                "effects": self.effects,
                "indistinguishable_from": self.indistinguishable_from,
                "refined": {"effects": self.refined.effects, **rm(self.refined),
                            "held": self._held()},
                "remaining_structure": self.remaining_structure, "structure": self.structure,
                "steps": [{k: v for k, v in st.items() if not isinstance(v, FitResult)} for st in self.steps],
                "shape": self.shape, "evidence": self.evidence,
                "detection_limits": self.detection, "hidden_effects": self.hidden,
                "drum": None if self.drum is None else self.drum.as_dict(),
                "predictive": {**(self.refined.fit_info.get("predictive") or {}),
                               "alternatives": [{"effects": f.effects, "weight": w}
                                                for w, f in self.refined.fit_info.get("alternatives") or []]}}

    def _held(self) -> dict:
        """The brake parameters the refined fit holds at their assumed values, each with the 95 % interval of its
        assumed spread (:meth:`rollaway.identify.drum_status.ParameterStatus.interval`): these data do not narrow it."""
        if self.drum is None:
            return {}
        out = {}
        for n, e in self.drum.entries.items():
            ci, source = e.interval()
            if n not in self.refined.estimates and ci is not None:
                out[n] = {"value": e.value, "unit": e.unit, "status": e.status, "prior_sd": e.prior_sd,
                          "ci95": list(ci), "ci95_from": source}
        return out

    def to_json(self, path=None) -> str:
        text = json.dumps(to_jsonable(self.as_dict()), indent=2)
        if path is not None:
            with open(path, "w", encoding="utf-8") as fh:
                fh.write(text + "\n")
        return text

    def summary(self) -> str:
        forms = ", ".join(f"{e['effect']} ({e['form']})" for e in self.effects)
        head = verdict_line(self.verdict, self.alternatives, self.detection, self.remaining_structure, self.named)
        lines = [f"verdict: {head}" + (f"   effects: {forms}" if len(self.effects) > 1 or
                                                any(e["form"] != "exact" for e in self.effects) else "")]
        lines += [f"  {w}" for w in self.evidence]
        lines.append("")
        lines.append(f"{'candidate (step 1)':<28}{'ΔBIC':>9}{'torque RMSE':>13}{'temp RMSE':>11}{'CV score':>12}")
        lines.append(f"{'(baseline)':<28}{0.0:>9.1f}{self.baseline.rmse_torque_Nm:>13.3g}"
                     f"{self.baseline.rmse_temp_C:>11.3g}{score_text(self.baseline_cv):>12}")
        mark = {"traded": " *", "short": " †"}
        marks = [mark.get(nested_shortfall(c.fit, self.baseline), "") for c in self.candidates]
        for c, m in zip(self.candidates, marks):
            lines.append(f"{c.effect + m:<28}{c.delta_bic:>9.1f}{c.fit.rmse_torque_Nm:>13.3g}"
                         f"{c.fit.rmse_temp_C:>11.3g}{score_text(c.cv_score):>12}")
        for m, words in ((" *", "its fit (the noise-weighted sum of squares) gave up temperature fit for torque fit, "
                                "and BIC, which weighs each channel by its own scale, charges that"),
                         (" †", "its fit stopped before it came back to the drum alone")):
            if m in marks:
                lines.append(f"{m.strip()} above the drum alone, which it contains: {words}; no evidence against the "
                             f"effect (docs/limits.md)")
        if self.drum is not None:
            lines += ["", self.drum.report()]
        lines.append("")
        lines.append(self.refined.report())
        return "\n".join(lines)

    def __repr__(self):
        return self.summary()

    def _repr_html_(self) -> str:  # notebooks
        from rollaway.display import diagnosis_html
        return diagnosis_html(self)

    def report(self, path) -> None:
        """Write a self-contained HTML report (verdict, evidence, figures) to *path*."""
        from rollaway.identify.report import diagnosis_report
        diagnosis_report(self, path)

    def _calibrated_fit(self):
        return self.refined

    def again(self, data: Measurements) -> "Diagnosis":
        """Diagnose other measurements (a synthetic campaign of the same design) with the default options."""
        return self.procedure(data)


__all__ = ["Diagnosis"]
