"""The figure of docs/how-to/fmu-export.md: the exported FMU (run by FMPy) against rollaway's own chain.

Calibrates the drum on the bundled bench data (diagnose, as quickstart.sh step 6), exports the model as
an FMU, runs it in FMPy for both directions and two hand forces and draws its torque over rollaway's
(DrumModel.evaluate, what `rollaway brake` prints), with the bench measurements behind them.

    python scripts/fmu-figure.py       # writes renders/fmu-vs-rollaway.png (build-docs.sh copies it to docs/assets/)
"""
import sys
import tempfile
from pathlib import Path

import fmpy
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import rollaway  # noqa: E402
from rollaway.bench.measurements import load_measurements  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "examples" / "identify" / "bench-hidden-effect.csv"


def main(out: Path) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        model_file = rollaway.diagnose(DATA).save_model(Path(tmp) / "calibrated.toml")
        model = rollaway.DrumModel(model_file)
        fmu = rollaway.export_fmu(model, Path(tmp) / "calibrated.fmu")
        bench = load_measurements(DATA)
        fig, (ax, ax_err) = plt.subplots(2, 1, figsize=(7.5, 6.2), sharex=True, height_ratios=(3, 1))
        worst = 0.0
        for (direction, force), colour in zip([("downhill", 350.0), ("uphill", 350.0), ("downhill", 200.0),
                                               ("uphill", 200.0)], ("C0", "C1", "C2", "C3")):
            sel = (bench.hand_force_N == force) & ((bench.sign > 0) == (direction == "downhill"))
            t0 = float(bench.drum_temp_C[sel][np.argmin(bench.time_s[sel])])
            res = fmpy.simulate_fmu(str(fmu), stop_time=3600, output_interval=30, start_values={
                "hand_force_N": force, "facing_uphill": direction == "uphill", "initial_drum_temp_C": t0})
            ref = model.evaluate(res["time"], force, direction, initial_temp_C=t0).torque_Nm
            rel = np.abs(res["torque_Nm"] - ref) / np.abs(ref)
            worst = max(worst, float(rel.max()))
            ax.plot(bench.time_s[sel] / 60, bench.torque_Nm[sel], ".", color="0.6", ms=4)
            ax.plot(res["time"] / 60, ref, "-", color=colour, lw=2.5, alpha=0.45,
                    label=f"rollaway, {force:g} N {direction}")
            ax.plot(res["time"][::6] / 60, res["torque_Nm"][::6], "o", color=colour, mfc="none", ms=5,
                    label=f"FMU (FMPy), {force:g} N {direction}")
            ax_err.plot(res["time"] / 60, rel, "-", color=colour)
        ax.plot([], [], ".", color="0.6", label="bench measurements")
        ax.set_ylabel("torque of one drum [N·m]")
        ax.set_title(f"calibrated drum ({', '.join(e.name for e in model.effects) or 'no effect'}): "
                     f"exported FMU vs rollaway", fontsize=10)
        ax.legend(fontsize=7, ncol=2)
        ax_err.set_ylabel("|FMU − rollaway|\n/ rollaway")
        ax_err.set_xlabel("time since the lever was applied [min]")
        ax_err.set_ylim(-1e-7, 1.2e-6)
        ax_err.axhline(1e-6, color="k", ls=":", lw=1)
        ax_err.text(1, 1.05e-6, "tolerance 1e-6", fontsize=7, va="bottom")
        ax_err.text(30, 5e-7, f"largest relative difference: {worst:.1e}", fontsize=8, ha="center")
        fig.tight_layout()
        out.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(out, dpi=110)
        print(f"wrote {out}: largest relative torque difference FMU vs rollaway {worst:.2e}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "renders" / "fmu-vs-rollaway.png")
