"""Road-margin bands at questions inside and beyond the bench's range, on held-out campaigns from
tests/identify/bench_generator.py (other drums, hidden effects of every kind, random μ_d and h).

Each campaign tests 3–4 hand forces over 180–360 N from T_0 100–250 °C (one direction in every third);
the questions, facing uphill (or the untested direction), one occupant, an hour's hold:

* ``inside``: 270 N from 200 °C;
* ``force_low`` / ``force_high``: 135 N and 450 N (25 % of the lowest/highest tested force beyond them);
* ``hotter``: 300 N from 280 °C (30 °C above the hottest tested T_0);
* ``direction``: 270 N from 200 °C facing the direction that was not tested (one-direction campaigns).

On each question's grade the truth's least brake margin m* is near 1; the 5–95 % band of the brake margin
should hold it in ≥ 90 % of the questions.

    PYTHONPATH=src python -m tests.uncertainty.band_questions --campaigns 30
    PYTHONPATH=src python -m tests.uncertainty.band_questions --campaigns 48 --rotated   # every kind, every question
    PYTHONPATH=src python -m tests.uncertainty.band_questions --campaigns 48 --short     # tests of 12–1200 s
"""
from __future__ import annotations

import argparse

import numpy as np
from scipy.optimize import brentq

from tests.identify.bench_generator import EFFECTS, MORE_DRUMS, OTHER_DRUMS, generate, true_torque

GRID = np.linspace(0.0, 3600.0, 361)
HIDDEN = [None] + [k for k, v in EFFECTS.items() if v[0] in ("exact", "other") and k != "zero_offset"]
QUESTIONS = {"inside": (270.0, 200.0), "force_low": (135.0, 200.0), "force_high": (450.0, 200.0),
             "hotter": (300.0, 280.0), "direction": (270.0, 200.0)}


def campaign_data(i: int, sampling: str = "5min"):
    """(hidden effect or None, its generator's drum, μ_d, h, one direction?, bench data, rng) of campaign *i*."""
    rng = np.random.default_rng(7700 + i)
    hidden = HIDDEN[i % len(HIDDEN)]
    mu, h = rng.uniform(0.3, 0.45), rng.uniform(25.0, 45.0)
    drums = list(OTHER_DRUMS.values())
    drum = drums[rng.integers(len(drums))] if i % 2 else {}
    one = i % 3 == 2
    tested = ("downhill",) if one else ("downhill", "uphill")
    data = generate([hidden] if hidden else [], sampling=sampling, seed=7700 + i, mu=mu, h=h, drum=drum,
                    directions=tested, forces=np.linspace(180.0, 360.0, 3 + i % 2), t0_range=(100.0, 250.0))
    return hidden, drum, mu, h, one, data, rng


def rotated_campaign_data(i: int, sampling: str = "5min"):
    """:func:`campaign_data` where every hidden kind meets every setting: in :func:`campaign_data` one direction falls
    on every third campaign and the kinds repeat every 12, so four kinds (those at places 2, 5, 8 and 11) are only
    ever tested one way and asked only the untested direction.  Here the setting turns once per round of kinds
    (one direction in every third round), and half the drums, at random, come from ``OTHER_DRUMS`` and ``MORE_DRUMS``
    (seeds 4400 + i)."""
    rng = np.random.default_rng(4400 + i)
    hidden = HIDDEN[i % len(HIDDEN)]
    mu, h = rng.uniform(0.3, 0.45), rng.uniform(25.0, 45.0)
    drums = list(OTHER_DRUMS.values()) + list(MORE_DRUMS.values())
    drum = drums[rng.integers(len(drums))] if rng.random() < 0.5 else {}      # not by parity: 12 kinds are even
    one = (i // len(HIDDEN)) % 3 == 2
    data = generate([hidden] if hidden else [], sampling=sampling, seed=4400 + i, mu=mu, h=h, drum=drum,
                    directions=("downhill",) if one else ("downhill", "uphill"),
                    forces=np.linspace(180.0, 360.0, 3 + (i // len(HIDDEN)) % 2), t0_range=(100.0, 250.0))
    return hidden, drum, mu, h, one, data, rng


SHORT = [("10Hz", 120.0, 4), ("10Hz", 240.0, 3), ("1Hz", 1200.0, 3), ("100Hz", 12.0, 4)]   # sampling, s, forces


def short_campaign_data(i: int):
    """:func:`rotated_campaign_data` on short tests (12–1200 s at 1–100 Hz, :data:`SHORT` turning once per round of
    kinds, one direction in every fifth; seeds 5500 + i): the questions' hour-long hold lies far beyond the bench's,
    where the drum cools on and a creep or relaxation goes on unseen."""
    rng = np.random.default_rng(5500 + i)
    hidden = HIDDEN[i % len(HIDDEN)]
    sampling, duration_s, n_forces = SHORT[(i // len(HIDDEN)) % len(SHORT)]
    mu, h = rng.uniform(0.3, 0.45), rng.uniform(25.0, 45.0)
    drums = list(OTHER_DRUMS.values()) + list(MORE_DRUMS.values())
    drum = drums[rng.integers(len(drums))] if rng.random() < 0.5 else {}
    one = i % 5 == 4
    data = generate([hidden] if hidden else [], sampling=sampling, seed=5500 + i, duration_s=duration_s, mu=mu, h=h,
                    drum=drum, directions=("downhill",) if one else ("downhill", "uphill"),
                    forces=np.linspace(180.0, 360.0, n_forces), t0_range=(100.0, 250.0))
    return hidden, drum, mu, h, one, data, rng


def two_effect_data(i: int):
    """(hidden effects, drum, μ_d, h, one direction?, bench data, rng) of two-effect campaign *i*: a random pair of
    catalogue and other forms, 5-min and 1-min sampling alternating."""
    rng = np.random.default_rng(6600 + i)
    effects = list(rng.choice(HIDDEN[1:], 2, replace=False))
    mu, h = rng.uniform(0.3, 0.45), rng.uniform(25.0, 45.0)
    drums = list(OTHER_DRUMS.values())
    drum = drums[rng.integers(len(drums))] if i % 2 else {}
    one = i % 3 == 2
    data = generate(effects, sampling=("5min", "1min")[i % 2], seed=6600 + i, mu=mu, h=h, drum=drum,
                    directions=("downhill",) if one else ("downhill", "uphill"),
                    forces=np.linspace(180.0, 360.0, 3 + i % 2), t0_range=(100.0, 250.0))
    return effects, drum, mu, h, one, data, rng


def campaign(i: int, draws: int = 300, sampling: str = "5min", two: bool = False, rotated: bool = False,
             short: bool = False) -> list[dict]:
    """The questions of held-out campaign *i* (*two*: of :func:`two_effect_data`; *rotated*: of
    :func:`rotated_campaign_data`; *short*: of :func:`short_campaign_data`), each with the truth's least margin and
    the model's band."""
    from rollaway.identify.diagnose import diagnose
    if two:
        effects, drum, mu, h, one, data, rng = two_effect_data(i)
    elif short:
        hidden, drum, mu, h, one, data, rng = short_campaign_data(i)
        effects = [hidden] if hidden else []
    else:
        hidden, drum, mu, h, one, data, rng = (rotated_campaign_data if rotated else campaign_data)(i, sampling)
        effects = [hidden] if hidden else []
    return answers(diagnose(data).model, i, effects, drum, mu, h, one, rng, draws)


def answers(model, i: int, effects: list, drum: dict, mu: float, h: float, one: bool, rng, draws: int = 300):
    """Each question's truth (its least margin m* on a grade drawn near 1) and *model*'s band."""
    from rollaway.hold import required_torque
    from rollaway.uncertainty.draws import rollaway_risk
    rows = []
    for q, (force, t0) in QUESTIONS.items():
        if (q == "direction") != one:
            continue
        direction = "uphill" if q == "direction" or not one else "downhill"

        def truth(grade):
            t_req = float(required_torque(model.params, grade, 1))
            tq = true_torque(force, GRID, direction, drum=drum, mu=mu, h=h, t0=t0, effects=effects)
            return float(np.min(2 * tq / t_req))
        target = 1.0 + rng.uniform(-0.1, 0.1)
        try:
            grade = brentq(lambda g: truth(g) - target, 0.2, 80.0)
        except ValueError:
            continue
        m_star = truth(grade)
        risk = rollaway_risk(model, hand_force_N=force, grade_pct=grade, direction=direction, occupants=1,
                             duration_s=3600.0, initial_temp_C=t0, draws=draws, seed=i)
        p = risk.brake_margin_percentiles          # the truth is the brake's (the tyre limit is not hidden)
        rows.append({"campaign": i, "hidden": "+".join(effects) or None, "question": q, "m_star": m_star,
                     "p5": p["p5"], "p95": p["p95"], "half_width": 0.5 * (p["p95"] - p["p5"]),
                     "probability": risk.rollaway_probability, "covered": p["p5"] <= m_star <= p["p95"]})
    return rows


def confident_wrong(r: dict) -> bool:
    """The whole 5–95 % brake-margin band on the wrong side of 1 (≥ 95 % sure of the wrong answer)."""
    return (r["p5"] >= 1.0 > r["m_star"]) or (r["p95"] < 1.0 <= r["m_star"])


def summary(rows: list[dict]) -> dict:
    out = {"questions": len(rows), "coverage": float(np.mean([r["covered"] for r in rows])),
           "half_width_median": float(np.median([r["half_width"] for r in rows])),
           "confident_wrong": int(sum(confident_wrong(r) for r in rows))}
    for q in QUESTIONS:
        sub = [r for r in rows if r["question"] == q]
        if sub:
            out[q] = {"n": len(sub), "coverage": float(np.mean([r["covered"] for r in sub])),
                      "half_width_median": float(np.median([r["half_width"] for r in sub]))}
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--campaigns", type=int, default=30)
    ap.add_argument("--sampling", default="5min")
    ap.add_argument("--start", type=int, default=0)
    ap.add_argument("--two", action="store_true", help="two hidden effects a campaign (5-min and 1-min alternating)")
    ap.add_argument("--rotated", action="store_true", help="every hidden kind in every setting (rotated_campaign_data)")
    ap.add_argument("--short", action="store_true", help="short tests at 1–100 Hz (short_campaign_data)")
    a = ap.parse_args(argv)
    rows = [r for i in range(a.start, a.start + a.campaigns)
            for r in campaign(i, sampling=a.sampling, two=a.two, rotated=a.rotated, short=a.short)]
    for r in rows:
        if not r["covered"]:
            print(f"  miss {r['campaign']} {r['hidden']} {r['question']}: m* {r['m_star']:.3f} band "
                  f"[{r['p5']:.3f}, {r['p95']:.3f}]")
    print(summary(rows))


if __name__ == "__main__":
    main()
