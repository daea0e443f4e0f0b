"""How diagnose's wall time grows with tests and rows (whole catalogue), plus the CLI at 10 000 rows.

    PYTHONPATH=src python benchmarks/bench_diagnose.py

Prints seconds per run and the ratio to the reference (8 tests × 13 samples = 104 rows) measured in
the same run; targets: ≤ 1 s in-process at 104 rows, ≤ 5 s through the CLI at 10 000 rows / 164 tests.
"""
from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from rollaway.identify.diagnose import diagnose
from rollaway.identify.synth import synth


def data(n_forces: int, dt_s: float, effect=("lining_creep",), seed=1):
    return synth(list(effect), seed=seed, dt_s=dt_s, hand_forces_N=tuple(np.linspace(150.0, 400.0, n_forces)))


def timed(d, repeat=2) -> float:
    best = np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        diagnose(d)
        best = min(best, time.perf_counter() - t)
    return best


def main():
    ref = timed(data(4, 300.0))
    print(f"{'tests':>6}{'rows':>8}{'seconds':>10}{'× ref':>8}   (whole catalogue, hidden lining_creep)")
    for n_forces, dt in ((4, 300.0), (4, 60.0), (20, 300.0), (20, 60.0), (82, 300.0), (82, 60.0)):
        d = data(n_forces, dt)
        s = timed(d, 2 if len(d) < 3000 else 1)
        print(f"{d.n_tests:>6}{len(d):>8}{s:>10.2f}{s / ref:>8.1f}")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "big.csv"
        data(82, 60.0).to_csv(path)
        for effect in (("lining_creep",), ()):
            if not effect:
                data(82, 60.0, effect=()).to_csv(path)
            t = time.perf_counter()
            subprocess.run([sys.executable, "-m", "rollaway", "diagnose", str(path), "--json", str(Path(tmp) / "d.json")],
                           check=True, capture_output=True)
            s = time.perf_counter() - t
            print(f"CLI diagnose, 164 tests, 10 004 rows, hidden {effect[0] if effect else 'nothing'}: {s:.2f} s "
                  f"({s / ref:.1f}× the 104-row in-process reference {ref:.2f} s)")


if __name__ == "__main__":
    main()
