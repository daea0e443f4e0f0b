"""The FMU file: `rollaway export-fmu`, FMPy's validation, a run where rollaway cannot be imported,
calibrated models from `diagnose --save-model` against `rollaway brake`, errors the FMU reports."""
import io
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

from rollaway.model.drum_model import DrumModel
from tests.export.fmu_runs import TIMES_S, assert_same, simulate   # skips the module without FMPy or gcc

validate_fmu = pytest.importorskip("fmpy.validation").validate_fmu

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples" / "identify"


@pytest.fixture(scope="module")
def calibrated(tmp_path_factory):
    """Models calibrated by diagnose on the bundled bench data (a hidden effect; a downhill-only own drum)."""
    import rollaway
    out = tmp_path_factory.mktemp("calibrated")
    return {name: rollaway.diagnose(EXAMPLES / f"{name}.csv").save_model(out / f"{name}.toml")
            for name in ("bench-hidden-effect", "bench-own-drum-downhill")}


def brake_cli(run_cli, params, force, direction, t0=None):
    """`rollaway brake --format csv` as columns."""
    args = ["brake", "--hand-force-N", force, "--direction", direction, "--dt-s", 60, "--format", "csv",
            "--params", params] + (["--t0-C", t0] if t0 is not None else [])
    code, out, err = run_cli(*args)
    assert code == 0, err
    return np.genfromtxt(io.StringIO(out), delimiter=",", names=True)


def test_cli_writes_a_valid_fmu(run_cli, tmp_path):
    out = tmp_path / "sub" / "paper.fmu"
    code, text, err = run_cli("export-fmu", out)
    assert code == 0, err
    assert "wrote" in text
    assert validate_fmu(str(out)) == []
    names = zipfile.ZipFile(out).namelist()
    assert {"modelDescription.xml", "binaries/linux64/rollaway_drum.so", "sources/rollaway_drum.c",
            "sources/rollaway_drum.h", "sources/fmi2_cosim.c", "sources/cosim_core.c", "sources/cosim_core.h",
            "sources/fmi2Functions.h"} <= set(names)


@pytest.mark.parametrize("name", ["bench-hidden-effect", "bench-own-drum-downhill"])
def test_calibrated_models_reproduce_rollaway_brake(run_cli, tmp_path, calibrated, name):
    model_file = calibrated[name]
    fmu = tmp_path / "cal.fmu"
    code, _, err = run_cli("export-fmu", "--params", model_file, fmu)
    assert code == 0, err
    assert validate_fmu(str(fmu)) == []
    for direction in ("downhill", "uphill"):
        for force, t0 in ((180.0, 150.0), (400.0, 250.0)):
            ref = brake_cli(run_cli, model_file, force, direction, t0)
            r = simulate(fmu, hand_force_N=force, uphill=direction == "uphill", initial_drum_temp_C=t0)
            np.testing.assert_array_equal(r["time"], ref["time_s"])
            for ours, theirs in (("torque_Nm", "torque_Nm"), ("drum_temp_C", "drum_temp_C"),
                                 ("clamp_force_N", "normal_force_N")):
                np.testing.assert_allclose(r[ours], ref[theirs], rtol=1e-6, err_msg=f"{name} {direction} {ours}")


def test_a_calibrated_model_keeps_its_values_and_provenance(tmp_path, calibrated):
    from fmpy import read_model_description
    import rollaway
    model = DrumModel(calibrated["bench-hidden-effect"])
    fmu = rollaway.export_fmu(model, tmp_path / "cal.fmu")
    md = read_model_description(str(fmu))
    var = {v.name: v for v in md.modelVariables}
    assert float(var["mu_drum"].start) == model.params.mu_drum                    # the exact double
    assert "calibration: fitted" in var["mu_drum"].description
    for key, value in model.values.items():
        assert float(var[key].start) == value and var[key].variability == "constant"
    assert var["hand_force_N"].causality == "parameter" and var["facing_uphill"].type == "Boolean"
    assert var["torque_Nm"].causality == "output" and var["torque_Nm"].unit == "N.m"
    assert var["initial_drum_temp_C"].unit == "degC" and float(var["initial_drum_temp_C"].start) == 200.0
    xml = zipfile.ZipFile(fmu).read("modelDescription.xml").decode()
    assert 'data_file="bench-hidden-effect.csv"' in xml and f'rollaway_version="{rollaway.__version__}"' in xml
    assert 'verdict="lining_creep"' in xml and "bench-hidden-effect.csv" in md.description
    assert_same(simulate(fmu), model.evaluate(TIMES_S, 400.0, "downhill"))


def test_calibrated_values_cannot_be_set(tmp_path):
    import fmpy
    from rollaway.export import export_fmu
    path = export_fmu("paper", tmp_path / "p.fmu")
    with pytest.raises(Exception, match="mu_drum"):        # FMPy refuses to set a constant
        fmpy.simulate_fmu(str(path), stop_time=60, start_values={"mu_drum": 0.5})


def test_the_fmu_refuses_a_parameter_out_of_range(tmp_path):
    import fmpy
    from rollaway.export import export_fmu
    path = export_fmu("paper", tmp_path / "p.fmu")
    logged = []
    with pytest.raises(Exception):
        fmpy.simulate_fmu(str(path), stop_time=60, start_values={"hand_force_N": -5.0},
                          logger=lambda *a: logged.append(a))
    assert any(b"hand_force_N = -5" in (m if isinstance(m, bytes) else str(m).encode()) for a in logged for m in a)


CHILD = """
import sys
sys.modules['rollaway'] = None              # any 'import rollaway' now fails
import fmpy, numpy
r = fmpy.simulate_fmu(sys.argv[1], stop_time=3600, output_interval=600,
                      start_values={'hand_force_N': 300.0, 'facing_uphill': True})
try:
    import rollaway
    print('rollaway importable')
except ImportError:
    print(' '.join(repr(float(x)) for x in r['torque_Nm']))
"""


def test_the_fmu_runs_where_rollaway_cannot_be_imported(tmp_path):
    from rollaway.export import export_fmu
    model = DrumModel("paper", effects=["radiation_cooling", "lining_creep"],
                      values={"radiation_cooling.emissivity": 0.7, "lining_creep.relaxed_fraction": 0.1})
    fmu = export_fmu(model, tmp_path / "alone.fmu")
    proc = subprocess.run([sys.executable, "-I", "-c", CHILD, str(fmu)], capture_output=True, text=True,
                          cwd=tmp_path, timeout=120)
    assert proc.returncode == 0, proc.stderr
    got = np.array([float(x) for x in proc.stdout.split()])
    ref = model.evaluate(np.arange(0, 3601, 600.0), 300.0, "uphill").torque_Nm
    np.testing.assert_allclose(got, ref, rtol=1e-6)


def test_the_binary_needs_only_the_c_library(tmp_path):
    from rollaway.export import export_fmu
    fmu = export_fmu("paper", tmp_path / "p.fmu")
    so = tmp_path / "rollaway_drum.so"
    so.write_bytes(zipfile.ZipFile(fmu).read("binaries/linux64/rollaway_drum.so"))
    needed = subprocess.run(["objdump", "-p", str(so)], capture_output=True, text=True).stdout
    libs = {ln.split()[-1] for ln in needed.splitlines() if "NEEDED" in ln}
    assert libs <= {"libm.so.6", "libc.so.6"}, libs


@pytest.mark.parametrize("initial_drum_temp_C", [-20.0, 10.0, 27.0])
def test_radiation_from_below_or_at_the_ambient_agrees(tmp_path, initial_drum_temp_C):
    """A drum parked colder than the air warms towards it by the same law in both implementations;
    one at the ambient stays there."""
    from rollaway.export import export_fmu
    model = DrumModel("paper", effects=["radiation_cooling"], values={"radiation_cooling.emissivity": 0.8})
    path = export_fmu(model, tmp_path / "r.fmu")
    result = simulate(path, initial_drum_temp_C=initial_drum_temp_C)
    series = model.evaluate(TIMES_S, 400.0, "downhill", initial_temp_C=initial_drum_temp_C)
    assert_same(result, series)
    if initial_drum_temp_C < 27.0:
        assert initial_drum_temp_C < result["drum_temp_C"][-1] < 27.0
    else:
        assert np.all(result["drum_temp_C"] == 27.0)


@pytest.mark.parametrize("version, folder", [("2.0", "linux64"), ("3.0", "x86_64-linux")])
def test_both_fmi_versions_validate_and_agree(run_cli, tmp_path, version, folder):
    model = DrumModel("paper", effects=["radiation_cooling", "shoe_thermal_lag", "lining_creep"],
                      values={"radiation_cooling.emissivity": 0.6, "shoe_thermal_lag.lag_time_s": 900.0,
                              "lining_creep.relaxed_fraction": 0.15})
    from rollaway.model.model_file import save_model
    params = save_model(model, tmp_path / "m.toml")
    fmu = tmp_path / f"m{version}.fmu"
    code, _, err = run_cli("export-fmu", "--params", params, "--fmi-version", version, fmu)
    assert code == 0, err
    assert validate_fmu(str(fmu)) == []
    assert f"binaries/{folder}/rollaway_drum.so" in zipfile.ZipFile(fmu).namelist()
    for uphill in (False, True):
        assert_same(simulate(fmu, hand_force_N=250.0, uphill=uphill, initial_drum_temp_C=280.0),
                    DrumModel(params).evaluate(TIMES_S, 250.0, "uphill" if uphill else "downhill", initial_temp_C=280.0))


@pytest.mark.parametrize("version", ["2.0", "3.0"])
def test_the_binary_exports_only_the_fmi_functions(tmp_path, version):
    """Internal names stay hidden, so two exported drums in one process cannot call each other's code."""
    from rollaway.export import export_fmu
    fmu = export_fmu("paper", tmp_path / "p.fmu", fmi_version=version)
    assert validate_fmu(str(fmu)) == []                     # the paper's model too (no unit 's' of its own)
    so = tmp_path / "rollaway_drum.so"
    so.write_bytes(next(zipfile.ZipFile(fmu).read(n) for n in zipfile.ZipFile(fmu).namelist() if n.endswith(".so")))
    symbols = subprocess.run(["nm", "-D", "--defined-only", str(so)], capture_output=True, text=True).stdout
    functions = [ln.split()[-1] for ln in symbols.splitlines() if " T " in ln]
    import re

    from rollaway.export.fmu import fmi_headers_dir
    header = (fmi_headers_dir() / f"fmi{version[0]}Functions.h").read_text()
    declared = set(re.findall(r"FMI[23]_Export\s+\w+TYPE\s+(fmi[23]\w+);", header))
    model_exchange = {"fmi2EnterEventMode", "fmi2NewDiscreteStates", "fmi2EnterContinuousTimeMode",
                      "fmi2CompletedIntegratorStep", "fmi2SetTime", "fmi2SetContinuousStates", "fmi2GetDerivatives",
                      "fmi2GetEventIndicators", "fmi2GetContinuousStates", "fmi2GetNominalsOfContinuousStates"}
    # FMI 2.0: the common and co-simulation functions; FMI 3.0: every function of the header
    assert set(functions) == declared - (model_exchange if version == "2.0" else set())


def test_two_drums_run_side_by_side_in_one_process(tmp_path):
    """Two FMUs of different models instantiated together and stepped in turn: each answers with its own model."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave

    from rollaway.export import export_fmu
    models = [DrumModel("paper"), DrumModel("paper", effects=["lining_creep"],
                                            values={"lining_creep.relaxed_fraction": 0.3}).replace_params(mu_drum=0.33)]
    slaves = []
    for k, model in enumerate(models):
        fmu = export_fmu(model, tmp_path / f"d{k}.fmu")
        md = read_model_description(str(fmu))
        slave = FMU2Slave(guid=md.guid, unzipDirectory=extract(str(fmu)), modelIdentifier="rollaway_drum",
                          instanceName=f"drum{k}")
        slave.instantiate()
        slave.setupExperiment(startTime=0.0)
        slave.enterInitializationMode()
        slave.exitInitializationMode()
        slaves.append(slave)
    torque = {v.name: v.valueReference for v in md.modelVariables}["torque_Nm"]
    for t in (0.0, 600.0, 1200.0):
        for slave, model in zip(slaves, models):
            slave.doStep(currentCommunicationPoint=t, communicationStepSize=600.0)
            ref = model.evaluate(t + 600.0, 400.0, "downhill").torque_Nm
            assert slave.getReal([torque])[0] == pytest.approx(float(ref), rel=1e-12)
    for slave in slaves:
        slave.terminate()
        slave.freeInstance()
