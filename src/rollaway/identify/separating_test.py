"""The test that would separate two fitted models: :func:`tell_apart`.

Both calibrated drum models
predict the torque over a grid of road/bench conditions — both directions, hand forces 25 % beyond
the tested range, start temperatures 50 °C beyond it, holds twice the tested length — and the
condition where their predictions differ most, in units of the torque noise, is the test to run.
Within the tested conditions the two agree (both were fitted there); the largest difference each
factor alone reaches outside them is reported too, so the words can name the factor that matters.
:mod:`rollaway.identify.ambiguity` proposes it for effect sets the bench data cannot tell apart.
"""
from __future__ import annotations

import numpy as np

FORCE_REACH = 0.25            # hand forces this far beyond the tested range (relative) [assumed]
TEMP_REACH_C = 50.0           # start temperatures this far beyond the tested range [assumed]
DURATION_REACH = 2.0          # holds this many times the tested length [assumed]
FACTORS = {"direction": "the other direction", "hand_force_N": "other hand forces",
           "initial_temp_C": "other start temperatures", "duration_s": "a longer hold"}


def _grid(validity: dict):
    """(hand forces, start temperatures, times, tested hold) of the conditions compared: the tested ranges of
    *validity* and the reach beyond them."""
    f_lo, f_hi = validity["hand_force_N"]
    span = max(f_hi - f_lo, 0.1 * f_hi)
    forces = np.unique(np.concatenate([np.linspace(f_lo, f_hi, 5),
                                       np.linspace(max(f_lo - FORCE_REACH * span, 0.25 * f_lo), f_lo, 3),
                                       np.linspace(f_hi, f_hi + FORCE_REACH * span, 3)]))
    t_lo, t_hi = validity["initial_temp_C"]
    temps = np.unique(np.concatenate([np.linspace(t_lo, t_hi, 5), [max(t_lo - TEMP_REACH_C, 40.0), t_hi + TEMP_REACH_C,
                                                                   t_hi + 0.5 * TEMP_REACH_C]]))
    duration = validity["duration_s"]
    times = np.linspace(0.0, DURATION_REACH * duration, 41)
    return forces, temps, times, duration


def _torques(model, forces, temps, times, direction) -> np.ndarray:
    """(force, T_0, time) torque of a drum model facing *direction*."""
    s = model.evaluate(times[None, None, :], forces[:, None, None], direction,
                       initial_temp_C=temps[None, :, None])
    return np.broadcast_to(np.asarray(s.torque_Nm, float), (forces.size, temps.size, times.size))


def tell_apart(a, b, validity: dict, noise_torque_Nm: float) -> dict:
    """Where the torque predictions of fits *a* and *b* differ most (module docstring)."""
    ma, mb = a.model.drum_model(a.values), b.model.drum_model(b.values)
    forces, temps, times, duration = _grid(validity)
    f_lo, f_hi = validity["hand_force_N"]
    t_lo, t_hi = validity["initial_temp_C"]
    f_in = (forces >= f_lo - 1e-9) & (forces <= f_hi + 1e-9)
    t_in = (temps >= t_lo - 1e-9) & (temps <= t_hi + 1e-9)
    d_in = times <= duration * (1 + 1e-9)
    best, tested, by = None, 0.0, dict.fromkeys(FACTORS, 0.0)
    for direction in ("downhill", "uphill"):
        diff = np.abs(_torques(ma, forces, temps, times, direction) - _torques(mb, forces, temps, times, direction))
        diff = np.where(np.isfinite(diff), diff, 0.0)
        tested_dir = direction in validity["directions"]
        inside = f_in[:, None, None] & t_in[None, :, None] & d_in[None, None, :]
        if tested_dir:
            tested = max(tested, float(np.max(diff[inside], initial=0.0)))
            for key, mask in (("hand_force_N", ~f_in[:, None, None] & t_in[None, :, None] & d_in[None, None, :]),
                              ("initial_temp_C", f_in[:, None, None] & ~t_in[None, :, None] & d_in[None, None, :]),
                              ("duration_s", f_in[:, None, None] & t_in[None, :, None] & ~d_in[None, None, :])):
                by[key] = max(by[key], float(np.max(diff[mask], initial=0.0)))
        else:
            by["direction"] = max(by["direction"], float(np.max(diff[inside], initial=0.0)))
        i, j, k = np.unravel_index(int(np.argmax(diff)), diff.shape)
        if best is None or diff[i, j, k] > best[0]:
            best = (float(diff[i, j, k]), direction, float(forces[i]), float(temps[j]),
                    float(max(times[k], duration)))
    sigma = max(float(noise_torque_Nm), 1e-9)
    gap, direction, force, temp, hold = best
    factor = max(by, key=by.get)
    test = {"direction": direction, "hand_force_N": round(force, 1), "initial_temp_C": round(temp, 1),
            "duration_s": round(hold, 0)}
    words = (f"a test facing {direction} at {force:.0f} N from T_0 {temp:.0f} °C held {hold:.0f} s would: "
             f"the two predict torques {gap:.3g} N·m apart there ({gap / sigma:.1f}× the torque noise), against "
             f"{tested:.3g} N·m at most over the tested conditions; {FACTORS[factor]} matter"
             f"{'s' if factor != 'initial_temp_C' and factor != 'hand_force_N' else ''} most "
             f"({by[factor]:.3g} N·m apart with only that changed)")
    return {"test": test, "difference_Nm": gap, "noise_sigmas": gap / sigma, "tested_difference_Nm": tested,
            "by_factor_Nm": by, "factor": factor, "words": words}


__all__ = ["DURATION_REACH", "FACTORS", "FORCE_REACH", "TEMP_REACH_C", "tell_apart"]
