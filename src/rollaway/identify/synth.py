"""Bench-like synthetic data from the baseline plus chosen effects (deterministic with a seed).

Default campaign: hand forces 200, 245, 290, 340 N × both directions (8 tests), a sample
every 300 s for an hour (13 samples, 104 rows), T_0 = 200 ± 15 °C (uniform), Gaussian noise
σ = 8 N·m on torque and 1.5 °C on drum temperature (every sample, the t = 0 one included,
so T_0 itself is measured with noise, as on the bench).
"""
from __future__ import annotations

import numpy as np

from rollaway.effects import get_effect
from rollaway.bench.measurements import Measurements
from rollaway.identify.model import BenchModel
from rollaway.errors import UserError

DEFAULT_HAND_FORCES_N = (200.0, 245.0, 290.0, 340.0)


def parse_effect_spec(text: str) -> tuple[str, dict[str, float]]:
    """``"name"``, ``"name=param=value,param=value"`` or ``"name:param=value"`` → (name, values)."""
    text = text.strip()
    for sep in (":", "="):
        if sep in text:
            name, rest = text.split(sep, 1)
            break
    else:
        name, rest = text, ""
    eff = get_effect(name.strip())
    values = {}
    for item in filter(None, (s.strip() for s in rest.split(","))):
        if "=" not in item:
            raise UserError(f"--effect {text!r}: '{item}' is not 'param=value'; e.g. "
                            f"{eff.name}={eff.parameters[0].name}={eff.parameters[0].typical or eff.parameters[0].initial:g}")
        key, val = (s.strip() for s in item.split("=", 1))
        spec = eff.parameter(key)
        try:
            x = float(val)
        except ValueError:
            raise UserError(f"--effect {text!r}: {key} = {val!r} is not a number in {spec.unit}") from None
        if not (spec.lower <= x <= spec.upper):
            raise UserError(f"--effect {text!r}: {key} = {x:g} is outside [{spec.lower:g}, {spec.upper:g}] {spec.unit}")
        values[key] = x
    return eff.name, values


def _effect_values(effects) -> dict[str, dict[str, float]]:
    if isinstance(effects, dict):
        items = effects.items()
    else:
        items = [parse_effect_spec(e) if isinstance(e, str) else (e, {}) for e in effects]
    out = {}
    for name, vals in items:
        eff = get_effect(name)
        out[eff.name] = {**eff.typical_values(), **(vals or {})}
    return out


def synth(effects=(), *, params=None, seed: int = 0, hand_forces_N=DEFAULT_HAND_FORCES_N,
          directions=("downhill", "uphill"), dt_s: float = 300.0, duration_s: float = 3600.0,
          initial_temp_C: float = 200.0, initial_temp_spread_C: float = 15.0, noise_torque_Nm: float = 8.0,
          noise_temp_C: float = 1.5, noise_torque_rel: float = 0.0, mu_drum: float | None = None,
          heat_transfer_W_m2K: float | None = None) -> Measurements:
    """Synthetic measurements; *effects* is a list of names/specs or ``{name: {param: value}}``
    (missing parameters take the effect's typical value)."""
    if dt_s <= 0 or duration_s < 2 * dt_s:
        raise UserError(f"dt {dt_s:g} s and duration {duration_s:g} s give fewer than 3 samples per test")
    for what, v in (("--noise-torque-Nm", noise_torque_Nm), ("--noise-temp-C", noise_temp_C),
                    ("noise_torque_rel", noise_torque_rel)):
        if not np.isfinite(v) or v < 0:
            raise UserError(f"{what} = {v:g} must be ≥ 0")
    chosen = _effect_values(effects)
    model = BenchModel(params, list(chosen))
    values = model.neutral_values()
    if mu_drum is not None:
        values["mu_drum"] = float(mu_drum)
    if heat_transfer_W_m2K is not None:
        values["heat_transfer_W_m2K"] = float(heat_transfer_W_m2K)
    for name, vals in chosen.items():
        values.update({f"{name}.{k}": v for k, v in vals.items()})
    rng = np.random.default_rng(seed)
    times = np.arange(0.0, duration_s + 1e-9, dt_s)
    tests = [(f, d) for d in directions for f in hand_forces_N]
    t0 = initial_temp_C + rng.uniform(-initial_temp_spread_C, initial_temp_spread_C, len(tests))
    n = len(times)
    ids = np.repeat([f"{'D' if d == 'downhill' else 'U'}{int(round(f))}" for f, d in tests], n)
    truth = Measurements(ids, np.repeat([d for _, d in tests], n), np.repeat([float(f) for f, _ in tests], n),
                         np.tile(times, len(tests)), np.repeat(t0, n), np.zeros(n * len(tests)),
                         np.full(n * len(tests), model.params.ambient_temp_C), source="synth")
    pred = model.predict(truth, values)
    if not np.all(np.isfinite(pred.torque_Nm)):
        raise UserError("the chosen parameters make a shoe self-lock (infinite torque); lower the friction")
    torque = pred.torque_Nm + rng.normal(0, 1, len(truth)) * np.hypot(noise_torque_Nm, noise_torque_rel * pred.torque_Nm)
    temp = pred.drum_temp_C + rng.normal(0, noise_temp_C, len(truth))
    out = Measurements(truth.test_id, truth.direction, truth.hand_force_N, truth.time_s, np.round(temp, 3),
                       np.round(torque, 3), truth.ambient_C, source=f"synth(seed={seed})")
    out.truth = {"values": values, "effects": chosen, "noise_torque_Nm": noise_torque_Nm,
                 "noise_temp_C": noise_temp_C}
    return out
