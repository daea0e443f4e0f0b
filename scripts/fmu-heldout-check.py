"""Acceptance check of the FMU export on held-out bench data, run by a Python that has only FMPy.

For each hidden effect: `rollaway synth` writes bench data with it, `rollaway diagnose --save-model`
calibrates a model on them, `rollaway export-fmu` exports that model; then an interpreter WITHOUT
rollaway (a virtualenv holding only FMPy) validates the FMU and runs it in both directions at two
hand forces and two start temperatures, and its torque, drum temperature and clamp force are compared
with `rollaway brake` (12 significant digits printed: the floor of the comparison).

    python -m venv /tmp/fmpy-only && /tmp/fmpy-only/bin/pip install fmpy
    python scripts/fmu-heldout-check.py --python /tmp/fmpy-only/bin/python [--fmi-version 3.0] [EFFECT ...]

Prints one line per hidden effect: what diagnose found, FMPy's validation problems, the largest relative
difference; exit 1 if any is above 1e-6 or any FMU does not validate.
"""
import argparse
import io
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

RUNNER = """
import json, sys, fmpy
from fmpy.validation import validate_fmu
out = {"problems": validate_fmu(sys.argv[1]), "runs": []}
for start in json.loads(sys.argv[2]):
    r = fmpy.simulate_fmu(sys.argv[1], stop_time=3600, output_interval=60, start_values=start)
    out["runs"].append({k: [float(x) for x in r[k]] for k in ("time", "torque_Nm", "drum_temp_C", "clamp_force_N")})
print(json.dumps(out))
"""
EFFECTS = ("lining_creep", "radiation_cooling", "shoe_thermal_lag", "friction_temperature", "cable_relaxation",
           "drum_radial_contraction", "modulus_temperature", "nonlinear_lining_stiffness", "installation_gap")


def rollaway(*args) -> str:
    return subprocess.run([sys.executable, "-m", "rollaway", *map(str, args)], capture_output=True, text=True,
                          check=True).stdout


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("effects", nargs="*", default=EFFECTS, help="hidden effects (default: the catalogue's)")
    ap.add_argument("--python", required=True, help="an interpreter with FMPy and without rollaway")
    ap.add_argument("--fmi-version", default="2.0")
    args = ap.parse_args()
    clean = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}   # no rollaway by a path
    no_rollaway = subprocess.run([args.python, "-c", "import rollaway"], capture_output=True, env=clean).returncode != 0
    print(f"{args.python}: rollaway importable: {not no_rollaway}")
    cases = [(f, t0, up) for f in (150.0, 400.0) for t0 in (120.0, 260.0) for up in (False, True)]
    failed = False
    with tempfile.TemporaryDirectory() as tmp:
        for k, effect in enumerate(args.effects):
            d = Path(tmp) / effect
            d.mkdir()
            rollaway("synth", "--effect", effect, "--seed", k + 11, "--out", d / "bench.csv")
            rollaway("diagnose", d / "bench.csv", "--save-model", d / "model.toml")
            found = [ln[9:-1] for ln in (d / "model.toml").read_text().splitlines() if ln.startswith("[effects.")]
            rollaway("export-fmu", "--params", d / "model.toml", "--fmi-version", args.fmi_version, d / "model.fmu")
            starts = [{"hand_force_N": f, "initial_drum_temp_C": t0, "facing_uphill": up} for f, t0, up in cases]
            res = json.loads(subprocess.run([args.python, "-c", RUNNER, str(d / "model.fmu"), json.dumps(starts)],
                                            capture_output=True, text=True, check=True, env=clean).stdout)
            worst = 0.0
            for (f, t0, up), run in zip(cases, res["runs"]):
                ref = np.genfromtxt(io.StringIO(rollaway(
                    "brake", "--params", d / "model.toml", "--hand-force-N", f, "--t0-C", t0, "--direction",
                    "uphill" if up else "downhill", "--dt-s", 60, "--format", "csv")), delimiter=",", names=True)
                assert np.array_equal(ref["time_s"], run["time"])
                for ours, theirs in (("torque_Nm", "torque_Nm"), ("drum_temp_C", "drum_temp_C"),
                                     ("clamp_force_N", "normal_force_N")):
                    worst = max(worst, float(np.max(np.abs(np.array(run[ours]) - ref[theirs]) / np.abs(ref[theirs]))))
            failed |= worst > 1e-6 or bool(res["problems"])
            print(f"hidden {effect:28s} diagnose found {found or 'no effect'}; validation problems "
                  f"{res['problems']}; largest relative difference {worst:.1e}")
    return 1 if failed or not no_rollaway else 0


if __name__ == "__main__":
    sys.exit(main())
