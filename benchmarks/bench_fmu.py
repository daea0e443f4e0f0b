"""Benchmark: exporting a drum model as an FMU, and running it in FMPy.

    python benchmarks/bench_fmu.py

Prints, for the paper model and a model with every catalogue effect: the export (C generation +
gcc + zip), one FMPy co-simulation of an hour at 1 s communication steps (3601 output rows; FMPy's
own overhead included) and DrumModel.evaluate of the same 3601 times — each as wall time and as a
ratio to the reference unit (:mod:`benchmarks.reference`) measured in the same run.
"""
from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_analytic import best_of  # noqa: E402
from reference import reference_unit_s  # noqa: E402


def main() -> None:
    import fmpy

    from rollaway.effects import CATALOGUE
    from rollaway.export import export_fmu
    from rollaway.model.drum_model import DrumModel

    ref = reference_unit_s()
    values = {f"{n}.{k}": v for n, c in CATALOGUE.items() for k, v in c.typical_values().items()}
    models = {"paper": DrumModel("paper"), "all effects": DrumModel("paper", effects=list(CATALOGUE), values=values)}
    t = np.arange(0, 3601, 1.0)
    print(f"reference unit (300 000 mj_step): {ref:.3f} s")
    with tempfile.TemporaryDirectory() as tmp:
        for name, model in models.items():
            path = Path(tmp) / "m.fmu"
            exp = best_of(lambda: export_fmu(model, path))
            run = best_of(lambda: fmpy.simulate_fmu(str(path), stop_time=3600, output_interval=1.0,
                                                    start_values={"hand_force_N": 300.0}))
            py = best_of(lambda: model.evaluate(t, 300.0, "downhill"))
            print(f"{name:12s} export {exp:.3f} s ({exp / ref:.3g} ref) | FMPy hour at 1 s steps {run:.3f} s "
                  f"({run / ref:.3g} ref) | DrumModel.evaluate of the same times {py * 1000:.2f} ms "
                  f"({py / ref:.3g} ref)")


if __name__ == "__main__":
    main()
