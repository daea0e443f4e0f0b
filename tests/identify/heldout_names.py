"""Held-out campaigns for the names ``diagnose`` gives: one hidden effect of every kind (the catalogue's
form, other forms, none), other drums, random μ_d, h and tested hand forces, 1- or 5-min sampling,
one direction in every third campaign.  Counts whether the truth is the verdict or one of its flagged
alternatives, partner effects (a second effect named where one is hidden), structure and time.  Each log is read as
the command line reads its file: a dense one reduced to window means (:mod:`rollaway.bench.reduction`; the short
logs), a sparse one as it is.

    PYTHONPATH=src python -m tests.identify.heldout_names --sets 60
    PYTHONPATH=src python -m tests.identify.heldout_names --sets 72 --rotated    # every kind in every setting
    PYTHONPATH=src python -m tests.identify.heldout_names --sets 72 --two        # two hidden effects a campaign
    PYTHONPATH=src python -m tests.identify.heldout_names --sets 96 --short      # short high-rate logs

With ``--two`` the campaigns are :func:`tests.uncertainty.band_questions.two_effect_data`'s: right is the verdict's
set of effects equal to the hidden pair's; a false name is an effect named that is not hidden, with no flagged
alternative made of hidden effects only.
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from tests.identify.bench_generator import EFFECTS, MORE_DRUMS, OTHER_DRUMS, generate

HIDDEN = [None] + [n for n, (k, _) in EFFECTS.items() if k in ("exact", "other") and n != "zero_offset"]
EQUIVALENT = {"gap": {"none", "drum_radial_contraction"}}     # a gap is a thicker lining (eq. 16b)


def campaign(i: int):
    """(hidden effect or None, data) of held-out campaign *i*."""
    rng = np.random.default_rng(9100 + i)
    hidden = HIDDEN[i % len(HIDDEN)]
    drums = [{}] + list(OTHER_DRUMS.values())
    drum = drums[rng.integers(len(drums))]
    lo = rng.uniform(150.0, 220.0)
    forces = np.linspace(lo, lo + rng.uniform(120.0, 200.0), int(rng.integers(2, 5)))
    kw = {"directions": (("downhill",), ("uphill",))[i % 2]} if i % 3 == 2 else {}
    data = generate([hidden] if hidden else [], sampling=("1min", "5min")[i % 2], seed=9100 + i, drum=drum,
                    mu=rng.uniform(0.3, 0.45), h=rng.uniform(25.0, 45.0), forces=forces, **kw)
    return hidden, data


def rotated_campaign(i: int):
    """(hidden effect or None, data) of :func:`campaign` where every hidden kind meets every setting: there the kinds
    repeat every 12 while the sampling turns every 2 and one direction falls on every third campaign, so a kind is
    only ever sampled one way (the logarithmic cable creep always every 5 minutes, one direction).  Here the
    setting turns once per round of kinds (1- and 5-min alternating, one direction in every third round), and the
    drums come from ``OTHER_DRUMS`` and ``MORE_DRUMS`` too (seeds 8100 + i)."""
    rng = np.random.default_rng(8100 + i)
    hidden, rnd = HIDDEN[i % len(HIDDEN)], i // len(HIDDEN)
    drums = [{}] + list(OTHER_DRUMS.values()) + list(MORE_DRUMS.values())
    drum = drums[rng.integers(len(drums))]
    lo = rng.uniform(150.0, 220.0)
    forces = np.linspace(lo, lo + rng.uniform(120.0, 200.0), int(rng.integers(2, 5)))
    kw = {"directions": (("downhill",), ("uphill",))[(rnd // 3) % 2]} if rnd % 3 == 2 else {}
    data = generate([hidden] if hidden else [], sampling=("1min", "5min")[rnd % 2], seed=8100 + i, drum=drum,
                    mu=rng.uniform(0.3, 0.45), h=rng.uniform(25.0, 45.0), forces=forces, **kw)
    return hidden, data


SHORT = [("10Hz", 120.0, 4), ("100Hz", 12.0, 4), ("1Hz", 1200.0, 3), ("10Hz", 240.0, 2)]   # sampling, s, forces


def short_campaign(i: int):
    """(hidden effect or None, data) of a short high-rate log (≤ 10 000 rows: tests of 12–1200 s at 1–100 Hz, as
    :data:`SHORT` turns once per round of kinds), one direction in every fifth, drums from ``OTHER_DRUMS`` and
    ``MORE_DRUMS`` too (seeds 3300 + i).  Each short test sits at its own temperature: a temperature law's form
    mismatch is a level error test by test there."""
    rng = np.random.default_rng(3300 + i)
    hidden = HIDDEN[i % len(HIDDEN)]
    sampling, duration_s, n_forces = SHORT[(i // len(HIDDEN)) % len(SHORT)]
    drums = [{}] + list(OTHER_DRUMS.values()) + list(MORE_DRUMS.values())
    kw = {"directions": (("downhill",), ("uphill",))[i % 2]} if i % 5 == 4 else {}
    data = generate([hidden] if hidden else [], sampling=sampling, seed=3300 + i, duration_s=duration_s,
                    n_forces=n_forces, drum=drums[rng.integers(len(drums))], mu=rng.uniform(0.3, 0.45),
                    h=rng.uniform(25.0, 45.0), **kw)
    return hidden, data


def judge(hidden, d) -> dict:
    """Right (verdict or a flagged alternative), partner named, structure, of one diagnosis."""
    expect = {"none"} if hidden is None else ({EFFECTS[hidden][1]} | EQUIVALENT.get(hidden, set()))
    alts = {e for a in getattr(d, "alternatives", []) for e in a["effects"]}
    named = [e["effect"] for e in d.effects]
    return {"right": d.verdict in expect, "right_or_alternative": d.verdict in expect or bool(alts & expect),
            "partner": len(named) > 1, "ambiguous": bool(alts), "structure": bool(d.remaining_structure),
            "verdict": d.verdict, "effects": named, "alternatives": sorted(alts)}


def judge_two(hidden: list, d) -> dict:
    """Of one diagnosis of two hidden effects: right (the verdict's set is the pair's, or a flagged alternative's
    is; an effect the free drum writes as well — a gap is a thicker lining, :data:`EQUIVALENT` — may be left out or
    named by its equivalent, as :func:`judge` lets it be for one), a false name (an effect named that is not hidden)
    and whether an alternative of hidden effects only flags it."""
    true = set().union(*({EFFECTS[h][1]} | EQUIVALENT.get(h, set()) for h in hidden)) - {None}
    need = {EFFECTS[h][1] for h in hidden if "none" not in EQUIVALENT.get(h, ())} - {None}
    named = {e["effect"] for e in d.effects}
    alts = [set(a["effects"]) for a in getattr(d, "alternatives", [])]
    false = sorted(named - true)

    def holds(effects: set) -> bool:
        return need <= effects <= true and len(effects) <= len(hidden)
    return {"right": holds(named), "right_or_alternative": holds(named) or any(holds(a) for a in alts),
            "false": false, "false_unflagged": bool(false) and not any(a and a <= true for a in alts),
            "ambiguous": bool(alts), "structure": bool(d.remaining_structure), "verdict": d.verdict,
            "effects": sorted(named), "alternatives": [sorted(a) for a in alts]}


def run(sets: int, start: int = 0, rotated: bool = False, two: bool = False, short: bool = False) -> list[dict]:
    from rollaway.bench.reduction import reduce_measurements
    from rollaway.identify.diagnose import diagnose
    from tests.uncertainty.band_questions import two_effect_data
    rows = []
    for i in range(start, start + sets):
        if two:
            got = two_effect_data(i)
            hidden, data = [str(e) for e in got[0]], got[5]
        else:
            hidden, data = (short_campaign if short else rotated_campaign if rotated else campaign)(i)
        data = reduce_measurements(data)        # as `rollaway diagnose FILE` and load_measurements read it
        t = time.perf_counter()
        d = diagnose(data)
        rows.append({"i": i, "hidden": hidden, "rows": len(data), "seconds": time.perf_counter() - t,
                     **(judge_two if two else judge)(hidden, d)})
    return rows


def summary(rows: list[dict]) -> dict:
    n = len(rows)
    sec = np.array([r["seconds"] for r in rows])
    return {"sets": n, "right": sum(r["right"] for r in rows), "right_or_alternative":
            sum(r["right_or_alternative"] for r in rows), "partner": sum(r.get("partner", 0) for r in rows),
            "false_unflagged": sum(r.get("false_unflagged", 0) for r in rows),
            "ambiguous": sum(r["ambiguous"] for r in rows), "structure": sum(r["structure"] for r in rows),
            "seconds_median": float(np.median(sec)), "seconds_max": float(sec.max())}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sets", type=int, default=60)
    ap.add_argument("--start", type=int, default=0)
    ap.add_argument("--rotated", action="store_true", help="every hidden kind in every setting (rotated_campaign)")
    ap.add_argument("--two", action="store_true", help="two hidden effects a campaign (band_questions.two_effect_data)")
    ap.add_argument("--short", action="store_true", help="short high-rate logs (short_campaign)")
    ap.add_argument("--json", help="write every campaign's row to this file")
    a = ap.parse_args(argv)
    rows = run(a.sets, a.start, a.rotated, a.two, a.short)
    if a.json:
        import json
        Path(a.json).write_text(json.dumps(rows))
    for r in rows:
        if not r["right_or_alternative"] or r.get("partner") or r.get("false_unflagged"):
            print(f"  {r['i']}: {r['hidden']} → {r['verdict']} {r['effects']} alt {r['alternatives']} "
                  f"structure={r['structure']}")
    print(summary(rows))


if __name__ == "__main__":
    main()
