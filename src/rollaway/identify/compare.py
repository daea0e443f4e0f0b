"""The model against bench data on both channels: errors per test and overall, and where it fails."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from rollaway.identify.calibrate import FitResult, calibrate, evaluate
from rollaway.bench.measurements import Measurements
from rollaway.bench.rawnoise import window_noise
from rollaway.identify.residuals import Noise, association, excursions, noise_estimate, trend_words

NOISE_BAND = 2.5   # a residual leaves the noise band when |r| > 2.5 σ
WITHIN_NOISE = 1.3  # RMSE below 1.3 σ counts as "within the noise" [assumed]
GLOBAL_OFF = 3.0    # RMSE above 3 σ without calibration: the whole channel is off [assumed]


def _errors(r: np.ndarray, t: np.ndarray) -> dict:
    if r.size == 0:
        return {"rmse": math.nan, "bias": math.nan, "worst": math.nan, "worst_at_s": math.nan, "n": 0}
    k = int(np.argmax(np.abs(r)))
    return {"rmse": float(np.sqrt(np.mean(r ** 2))), "bias": float(r.mean()), "worst": float(r[k]),
            "worst_at_s": float(t[k]), "n": int(r.size)}


@dataclass
class Comparison:
    """Errors (measured − model) of one model on one data set, with the failure regions in words."""

    fit: FitResult
    noise: dict[str, Noise]
    per_test: list[dict]
    overall: dict[str, dict]
    excursions: dict[str, list[dict]]
    words: list[str] = field(default_factory=list)

    @property
    def data(self) -> Measurements:
        return self.fit.data

    @property
    def model_name(self) -> str:
        return "paper model" + "".join(" + " + e for e in self.fit.effects)

    def ratios(self) -> dict[str, float]:
        """RMSE / noise level per channel."""
        return {ch: (self.overall[ch]["rmse"] / n.sigma if n.sigma > 0 else math.inf) for ch, n in self.noise.items()}

    def verdict(self) -> tuple[str, bool]:
        """(one sentence, True when the model matches within the noise on both channels)."""
        r = self.ratios()
        calibrated = self.fit.k > 0
        name = f"{'calibrated ' if calibrated else ''}{self.model_name}"
        parts = [f"{ch} RMSE {self.overall[ch]['rmse']:.3g} {u} = {r[ch]:.1f}× the noise"
                 for ch, u in (("torque", "N·m"), ("temperature", "°C"))]
        if all(v < WITHIN_NOISE for v in r.values()):
            return f"The {name} matches these data within the measurement noise ({'; '.join(parts)}).", True
        hint = ("calibrate it (--calibrate) to see whether μ_d and h alone close the gap, or run 'rollaway diagnose'"
                if not calibrated else "run 'rollaway diagnose' to find which physical effect is missing")
        return f"The {name} does not match these data ({'; '.join(parts)}): {hint}.", False

    def findings(self, limit: int = 8) -> list[str]:
        """The findings in words; without calibration a channel far off the noise gets one line, not every test."""
        r = self.ratios()
        out = []
        for ch in self.noise:
            lines = [w for w in self.words if w.startswith(ch + ":")]
            spots = [w for w in lines if "band" in w and "no sample" not in w]
            if self.fit.k == 0 and r[ch] > GLOBAL_OFF:
                n_out = sum(e["samples"] for e in self.excursions[ch])
                out += [w for w in lines if w not in spots]
                out.append(f"{ch}: {n_out} samples in {len(spots)} runs lie outside the noise band; with the "
                           f"parameter set's values the whole channel is off, so where it fails says little — "
                           f"compare with --calibrate to see the shape errors")
            else:
                out += [w for w in lines if w not in spots] + spots[:limit]
                if len(spots) > limit:
                    out.append(f"{ch}: … and {len(spots) - limit} more excursions outside the band.")
        return out

    def as_dict(self) -> dict:
        verdict, ok = self.verdict()
        return {"verdict": verdict, "within_noise": ok, "ratio_to_noise": self.ratios(),
                "model": {"name": self.model_name, "calibrated": self.fit.k > 0, "effects": self.fit.effects,
                          "values": self.fit.values},
                "noise": {k: v.sigma for k, v in self.noise.items()}, "overall": self.overall,
                "tests": self.per_test, "excursions": self.excursions, "findings": self.words,
                "data": {"source": self.fit.data.source, "tests": self.fit.data.n_tests, **self.fit.data.rows_info()}}

    def table(self) -> str:
        head = (f"{'test':<10}{'dir':<9}{'F_hb N':>7}{'T0 °C':>7} | {'torque RMSE':>11}{'bias':>8}{'worst':>8}"
                f"{'at s':>6} | {'temp RMSE':>9}{'bias':>7}{'worst':>7}{'at s':>6}")
        lines = [head, "-" * len(head)]
        rows = self.per_test + [{"test_id": "overall", "direction": "", "hand_force_N": math.nan,
                                 "initial_temp_C": math.nan, **{f"{c}": self.overall[c] for c in self.overall}}]
        for t in rows:
            q, h = t["torque"], t["temperature"]
            f = "" if math.isnan(t["hand_force_N"]) else f"{t['hand_force_N']:.0f}"
            t0 = "" if math.isnan(t["initial_temp_C"]) else f"{t['initial_temp_C']:.0f}"
            lines.append(f"{t['test_id']:<10}{t['direction']:<9}{f:>7}{t0:>7} | {q['rmse']:>11.3g}{q['bias']:>8.3g}"
                         f"{q['worst']:>8.3g}{q['worst_at_s']:>6.0f} | {h['rmse']:>9.3g}{h['bias']:>7.3g}"
                         f"{h['worst']:>7.3g}{h['worst_at_s']:>6.0f}")
        return "\n".join(lines)

    def summary(self) -> str:
        return (self.verdict()[0] + "\n\n" + self.table() + "\n\n"
                + "\n".join(f"- {w}" for w in self.findings()))

    def _repr_html_(self) -> str:  # notebooks
        from rollaway.identify.report import esc
        v, ok = self.verdict()
        return f"<p><b>{esc(v)}</b></p><pre>{esc(self.table())}</pre>"

    def __repr__(self):
        return self.summary()

    def report(self, path) -> None:
        from rollaway.identify.report import comparison_report
        comparison_report(self, path)


def residual_channels(fit: FitResult) -> dict[str, tuple[np.ndarray, np.ndarray, str]]:
    """channel → (residual, mask of samples that are predictions, unit)."""
    rt, rq = fit.residuals()
    every = np.ones(len(rq), bool)      # T_0 is fitted: the t = 0 readings are data like the others
    if fit.data.count is not None:      # a reduced log: its partial windows (t = 0, a test's end) are far noisier
        every = fit.data.count >= 0.5 * np.median(fit.data.count)
    return {"torque": (rq, every, "N·m"), "temperature": (rt, every, "°C")}


def compare_fit(fit: FitResult) -> Comparison:
    data = fit.data
    tau = fit.model.state(data, fit.values).cooling_time_constant_s
    chans = residual_channels(fit)
    noise = {}
    for ch, (r, m, _) in chans.items():
        values = data.torque_Nm if ch == "torque" else data.drum_temp_C
        noise[ch] = noise_estimate(data, values, tau, relative=ch == "torque") or Noise(
            float(np.sqrt(np.mean(r[m] ** 2))) or 1e-9, 1, reliable=False, note="no test has 3 samples: the "
            "model's RMSE stands in for the noise")
        if data.count is not None:       # window means: compare with the noise of a window mean, σ/√n
            noise[ch] = window_noise(noise[ch], data, values, m)
    per_test = []
    for info in data.test_info():
        rows = data.test_index == data.tests.index(info["test_id"])
        entry = dict(info)
        for ch, (r, m, _) in chans.items():
            entry[ch] = _errors(r[rows & m], data.time_s[rows & m])
        per_test.append(entry)
    overall = {ch: _errors(r[m], data.time_s[m]) for ch, (r, m, _) in chans.items()}
    exc = {ch: excursions(data, r, noise[ch].sigma, NOISE_BAND, m) for ch, (r, m, _) in chans.items()}
    words = []
    info = {t["test_id"]: t for t in data.test_info()}
    for ch, (r, m, unit) in chans.items():
        sig = noise[ch].sigma
        o = overall[ch]
        ratio = o["rmse"] / sig if sig > 0 else math.inf
        verdict = "within the noise" if ratio < WITHIN_NOISE else "above the noise"
        words.append(f"{ch}: RMSE {o['rmse']:.3g} {unit} against a noise level of {sig:.3g} {unit} ({ratio:.1f}×, "
                     f"{verdict}); bias {o['bias']:+.3g} {unit}; worst {o['worst']:+.3g} {unit}.")
        # (the ±band excursion lines below contain the word "band"; findings() relies on it)
        if ratio >= WITHIN_NOISE:
            name, share = association(data, r, fit.prediction.drum_temp_C, m)[0]
            words.append(f"{ch}: the residual follows {name} ({share:.0%} of its variance explained by {name}; "
                         f"it {trend_words(data, r, fit.prediction.drum_temp_C, name, m)}).")
        runs = sorted(exc[ch], key=lambda e: -abs(e["worst"]))
        for e in runs[:8]:
            t = info[e["test_id"]]
            span = (f"at {e['from_s']:.0f} s" if e["from_s"] == e["to_s"]
                    else f"from {e['from_s']:.0f} s to {e['to_s']:.0f} s")
            words.append(f"{ch}: test {e['test_id']} ({t['direction']}, {t['hand_force_N']:.0f} N) is {e['sign']} the "
                         f"±{NOISE_BAND:g}σ band (±{NOISE_BAND * sig:.3g} {unit}) {span} ({e['samples']} sample"
                         f"{'s' if e['samples'] > 1 else ''}, worst {e['worst']:+.3g} {unit} at {e['worst_at_s']:.0f} s).")
        if len(runs) > 8:
            words.append(f"{ch}: … and {len(runs) - 8} more excursions outside the band.")
        if not runs:
            words.append(f"{ch}: no sample leaves the ±{NOISE_BAND:g}σ noise band.")
    return Comparison(fit, noise, per_test, overall, exc, words)


def compare(data: Measurements, params=None, effects=None, *, calibrated: bool = False) -> Comparison:
    """Compare the model with *data*.

    *effects*: names (at their typical values) or ``{name: {param: value}}``.  With
    ``calibrated=True`` μ_d, h and the effects' parameters are fitted first; otherwise the
    model runs at the set's values (``paper`` by default).
    """
    from rollaway.identify.synth import _effect_values
    chosen = _effect_values(effects or ())
    values = {f"{n}.{k}": v for n, vals in chosen.items() for k, v in vals.items()}
    if calibrated:
        fit = calibrate(data, list(chosen), params, start=values)
    else:
        fit = evaluate(data, list(chosen), params, values)
    return compare_fit(fit)
