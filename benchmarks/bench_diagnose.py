"""``rollaway diagnose`` on bench logs of 0.1–100 Hz through the CLI: wall time in reference units and peak memory.

    PYTHONPATH=src python benchmarks/bench_diagnose.py --rows 288000      # one log (8 tests × 1 h: 10 Hz)
    PYTHONPATH=src python benchmarks/bench_diagnose.py                    # 0.1, 1, 10 and 100 Hz
    PYTHONPATH=src python benchmarks/bench_diagnose.py --scaling          # in-process scaling with tests and rows
    PYTHONPATH=src python benchmarks/bench_diagnose.py --held-out         # the slow kinds of set, goal ≤ 5 s
    PYTHONPATH=src python benchmarks/bench_diagnose.py --stress           # 40 stress sets, goal ≤ 5 s each
    PYTHONPATH=src python benchmarks/bench_diagnose.py --two-effect 0:216 # the two-effect held-out campaigns
    PYTHONPATH=src python benchmarks/bench_diagnose.py --short-high-rate  # 44 logs at 1–100 Hz, ≤ 10 000 rows

Each log is 8 tests of an hour (``rollaway synth``, hidden lining_creep unless ``--effect``) written as a CSV
under a temporary folder; the CLI runs in a fresh interpreter and its peak resident memory is that process's
(``wait4``).  Wall time is also given in the reference unit of :mod:`benchmarks.reference` (300 000 raw
``mj_step`` calls, measured in the same run).  Targets (issue 20): 288 000 rows ≤ 6 units and ≤ 400 MB,
2.9 M rows ≤ 40 units and ≤ 1.5 GB.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))     # tests.identify.bench_generator

TESTS, DURATION_S = 8, 3600.0
TARGETS = {288_000: (6.0, 400.0), 2_880_000: (40.0, 1536.0)}


def write_log(rows: int, path: Path, effect: str, seed: int = 1) -> dict:
    """8 tests × 1 h with about *rows* rows in all, written by ``rollaway synth`` in its own interpreter (so
    that this process stays small: a child's peak RSS counts the parent's pages it started from)."""
    from rollaway.model.parameters import paper
    dt = TESTS * DURATION_S / rows
    cmd = [sys.executable, "-m", "rollaway", "synth", "--dt-s", repr(dt), "--duration-s", repr(DURATION_S),
           "--seed", str(seed), "--out", str(path)] + (["--effect", effect] if effect else [])
    subprocess.run(cmd, check=True, capture_output=True, env=_env())
    n = sum(1 for _ in open(path, encoding="utf-8")) - 1
    return {"rows": n, "hz": 1.0 / dt, "mu_drum": paper().mu_drum}


def _env() -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(Path(__file__).resolve().parents[1] / "src") + os.pathsep + env.get("PYTHONPATH", "")
    return env


def run_cli(path: Path, json_out: Path) -> tuple[float, float, int]:
    """(wall s, peak RSS MB, exit code) of ``rollaway diagnose PATH`` in its own interpreter."""
    t = time.perf_counter()
    p = subprocess.Popen([sys.executable, "-m", "rollaway", "diagnose", str(path), "--json", str(json_out)],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=_env())
    _, status, usage = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t
    err = p.stderr.read().decode()
    p.stderr.close()
    code = os.waitstatus_to_exitcode(status)
    if code:
        print(err, file=sys.stderr)
    return wall, usage.ru_maxrss / 1024.0, code


def bench(rows_list, effect: str) -> None:
    from reference import reference_unit_s
    ref = reference_unit_s()
    print(f"reference unit (300 000 raw mj_step): {ref:.2f} s")
    print(f"{'rows':>10}{'Hz':>8}{'wall s':>9}{'units':>8}{'peak MB':>9}   verdict (μ_d 95 % interval, truth)")
    with tempfile.TemporaryDirectory() as tmp:
        for rows in rows_list:
            path = Path(tmp) / f"log-{rows}.csv"
            truth = write_log(rows, path, effect)
            wall, mb, code = run_cli(path, Path(tmp) / "d.json")
            if code:
                print(f"{truth['rows']:>10}  diagnose failed (exit {code})")
                continue
            d = json.loads((Path(tmp) / "d.json").read_text())
            lo, hi = d["refined"]["parameters"]["mu_drum"]["ci95"]
            target = next((k for k in TARGETS if 0.9 * k <= rows <= 1.1 * k), None)
            goal = ""
            if target is not None:
                units_max, mb_max = TARGETS[target]
                goal = f"   target ≤ {units_max:g} units, ≤ {mb_max:g} MB: " + \
                    ("met" if wall / ref <= units_max and mb <= mb_max else "MISSED")
            cover = "covers" if lo <= truth["mu_drum"] <= hi else "MISSES"
            print(f"{truth['rows']:>10}{truth['hz']:>8.3g}{wall:>9.2f}{wall / ref:>8.2f}{mb:>9.0f}   {d['verdict']} "
                  f"([{lo:.5f}, {hi:.5f}] {cover} {truth['mu_drum']:g}; {d['data']['rows']} rows fitted){goal}",
                  flush=True)
            path.unlink()


def scaling() -> None:
    """In-process diagnose time against tests and rows (whole catalogue, hidden lining_creep)."""
    from rollaway.identify.diagnose import diagnose
    from rollaway.identify.synth import synth

    def data(n_forces, dt_s):
        return synth(["lining_creep"], seed=1, dt_s=dt_s, hand_forces_N=tuple(np.linspace(150.0, 400.0, n_forces)))

    def timed(d, repeat=2):
        best = np.inf
        for _ in range(repeat):
            t = time.perf_counter()
            diagnose(d)
            best = min(best, time.perf_counter() - t)
        return best
    ref = timed(data(4, 300.0))
    print(f"{'tests':>6}{'rows':>8}{'seconds':>10}{'× ref':>8}   (104-row in-process reference {ref:.2f} s)")
    for n_forces, dt in ((4, 300.0), (4, 60.0), (20, 300.0), (20, 60.0), (82, 300.0), (82, 60.0)):
        d = data(n_forces, dt)
        s = timed(d, 2 if len(d) < 3000 else 1)
        print(f"{d.n_tests:>6}{len(d):>8}{s:>10.2f}{s / ref:>8.1f}")


# the slow kinds of set (issue 23: ≤ 5 s for every diagnose of ≤ 10 000 rows), from the independent generator
HELD_OUT = {
    "two effects, 5-min": dict(effects=["friction_linear", "cable_exponential"], sampling="5min", seed=33),
    "ratchet step, uphill only, 1-min": dict(effects=["ratchet_step"], sampling="1min", seed=42,
                                             directions=("uphill",)),
    "ratchet step, downhill only, 1-min": dict(effects=["ratchet_step"], sampling="1min", seed=35,
                                               directions=("downhill",)),
    "power-law creep, 1 Hz, 8 tests": dict(effects=["creep_power_law"], sampling="1Hz", seed=47,
                                           duration_s=1248.0),
    "two effects in other forms, 1-min": dict(effects=["modulus_sigmoid", "cable_log"], sampling="1min", seed=45),
}


def held_out() -> None:
    """CPU and wall seconds of ``rollaway diagnose`` on :data:`HELD_OUT` through the CLI, and in reference units."""
    from reference import reference_unit_s
    from tests.identify.bench_generator import generate
    ref = reference_unit_s()
    print(f"reference unit (300 000 raw mj_step): {ref:.2f} s; goal: ≤ 5 s per set")
    print(f"{'rows':>6}{'CPU s':>8}{'wall s':>8}{'units':>7}   set")
    with tempfile.TemporaryDirectory() as tmp:
        for name, kw in HELD_OUT.items():
            data = generate(**kw)
            path = Path(tmp) / "set.csv"
            data.to_csv(path)
            t = time.perf_counter()
            p = subprocess.Popen([sys.executable, "-m", "rollaway", "diagnose", str(path)],
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=_env())
            _, _, usage = os.wait4(p.pid, 0)
            wall = time.perf_counter() - t
            cpu = usage.ru_utime + usage.ru_stime
            print(f"{len(data):>6}{cpu:>8.2f}{wall:>8.2f}{wall / ref:>7.2f}   {name}", flush=True)


def stress_sets():
    """(name, kwargs of ``generate``) of the 40 stress sets: irregular, 1-min, 5-min and 1 Hz sampling; one or two
    hidden effects (catalogue and other forms); a logged ambient drifting 3–10 K in every fourth; one direction in
    every fifth; the paper's drum and others; random μ_d and h."""
    from tests.identify.bench_generator import EFFECTS, OTHER_DRUMS
    hidden = [k for k, v in EFFECTS.items() if v[0] in ("exact", "other") and k != "zero_offset"]
    rng = np.random.default_rng(48)
    drums = [{}] + list(OTHER_DRUMS.values())
    out = []
    for j in range(40):
        sampling = ["irregular", "1min", "5min", "1Hz", "irregular", "1min"][j % 6]
        effects = list(rng.choice(hidden, 1 + (j % 3 == 0), replace=False))
        kw = dict(effects=effects, sampling=sampling, seed=4800 + j, drum=drums[rng.integers(len(drums))],
                  mu=rng.uniform(0.3, 0.45), h=rng.uniform(25, 45))
        if j % 4 == 1:
            kw["ambient_drift_C"] = rng.uniform(3, 10)
        if j % 5 == 2:
            kw["directions"] = (("downhill",), ("uphill",))[j % 2]
        if sampling == "1Hz":
            kw["duration_s"] = 1200.0
        out.append((f"s{j:02d} {sampling} {'+'.join(effects)}{' drifting ambient' if j % 4 == 1 else ''}", kw))
    return out


def short_high_rate_sets():
    """(name, kwargs of ``generate``) of 44 logs at 1, 10 and 100 Hz of at most 10 000 rows, so of short tests
    (12–1200 s): 24 with none, a linear friction law, a power-law creep or a cable relaxation with radiation, then 20
    with one or two random hidden effects, on the paper's drum and others, random μ_d and h."""
    from tests.identify.bench_generator import EFFECTS, OTHER_DRUMS
    hidden = [k for k, v in EFFECTS.items() if v[0] in ("exact", "other") and k != "zero_offset"]
    drums = [{}] + list(OTHER_DRUMS.values())
    out = []
    for k, (sampling, duration_s, n_forces, effects) in enumerate(
            (s, d, n, e) for s, d, n in (("10Hz", 240.0, 2), ("10Hz", 120.0, 4), ("100Hz", 24.0, 2),
                                         ("100Hz", 12.0, 4), ("1Hz", 1200.0, 4), ("1Hz", 600.0, 4))
            for e in ([], ["friction_linear"], ["creep_power_law"], ["cable_exponential", "radiation"])):
        out.append((f"h{k:02d} {sampling} {'+'.join(effects) or 'none'}",
                    dict(effects=effects, sampling=sampling, seed=900 + k, duration_s=duration_s, n_forces=n_forces,
                         drum=drums[k % len(drums)], mu=0.3 + 0.01 * (k % 15), h=30.0 + k % 10)))
    rng = np.random.default_rng(55)
    for k in range(20):
        sampling, duration_s, n_forces = [("10Hz", 120.0, 4), ("100Hz", 12.0, 4), ("10Hz", 240.0, 2),
                                          ("100Hz", 24.0, 2)][k % 4]
        effects = [str(e) for e in rng.choice(hidden, 1 + (k % 3 == 0), replace=False)]
        out.append((f"g{k:02d} {sampling} {'+'.join(effects)}",
                    dict(effects=effects, sampling=sampling, seed=5500 + k, duration_s=duration_s, n_forces=n_forces,
                         drum=drums[rng.integers(len(drums))], mu=rng.uniform(0.3, 0.45), h=rng.uniform(25, 45))))
    return out


def two_effect_sets(first: int, stop: int):
    """(name, data maker) of the two-effect held-out campaigns *first* … *stop* − 1 of
    ``tests/uncertainty/band_questions.py`` (a random pair of catalogue and other forms, 5- and 1-min sampling,
    other drums, one direction in every third)."""
    from tests.uncertainty.band_questions import two_effect_data
    return [(f"t{i:03d} " + "+".join(map(str, two_effect_data(i)[0])), lambda i=i: two_effect_data(i)[5])
            for i in range(first, stop)]


def stress(sets=None) -> None:
    """Wall seconds of ``rollaway diagnose`` through the CLI on each of *sets* ((name, data maker); default
    :func:`stress_sets`), their mean and the slowest, and the reference unit measured before and after."""
    from reference import reference_unit_s
    from tests.identify.bench_generator import generate
    if sets is None:
        sets = [(name, lambda kw=kw: generate(**kw)) for name, kw in stress_sets()]
    ref = reference_unit_s()
    print(f"reference unit (300 000 raw mj_step): {ref:.2f} s; goal: ≤ 5 s per set")
    walls = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, make in sets:
            data = make()
            path = Path(tmp) / "set.csv"
            data.to_csv(path)
            t = time.perf_counter()
            subprocess.run([sys.executable, "-m", "rollaway", "diagnose", str(path)], stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL, env=_env(), check=False)
            walls.append(time.perf_counter() - t)
            print(f"{len(data):>6}{walls[-1]:>8.2f} s   {name}", flush=True)
    print(f"mean {np.mean(walls):.2f} s, slowest {max(walls):.2f} s, over 5 s: {sum(w > 5 for w in walls)}; "
          f"reference unit before {ref:.2f} s, after {reference_unit_s():.2f} s")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", type=int, action="append", help="rows of the log (8 tests × 1 h; repeatable)")
    ap.add_argument("--effect", default="lining_creep", help="hidden effect ('' for none)")
    ap.add_argument("--scaling", action="store_true", help="in-process scaling with tests and rows instead")
    ap.add_argument("--held-out", action="store_true", help="the slow kinds of set from the independent generator")
    ap.add_argument("--stress", action="store_true", help="40 stress sets from the independent generator")
    ap.add_argument("--two-effect", metavar="FIRST:STOP", help="the two-effect held-out campaigns FIRST … STOP − 1")
    ap.add_argument("--short-high-rate", action="store_true", help="44 logs at 1–100 Hz of ≤ 10 000 rows")
    a = ap.parse_args(argv)
    if a.stress:
        stress()
        return
    if a.short_high_rate:
        from tests.identify.bench_generator import generate
        stress([(name, lambda kw=kw: generate(**kw)) for name, kw in short_high_rate_sets()])
        return
    if a.two_effect:
        first, _, stop = a.two_effect.partition(":")
        stress(two_effect_sets(int(first), int(stop or int(first) + 1)))
        return
    if a.held_out:
        held_out()
        return
    if a.scaling:
        scaling()
        return
    rows = a.rows or [int(TESTS * DURATION_S * hz) for hz in (0.1, 1.0, 10.0, 100.0)]
    bench(rows, a.effect)


if __name__ == "__main__":
    main()
