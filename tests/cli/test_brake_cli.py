"""`rollaway brake` output form and bad-input handling (one line, exit 2, no traceback)."""
import csv
import io
import json
import subprocess
import sys

import numpy as np
import pytest

from rollaway import drum_brake, paper


def test_brake_csv_form(run_cli):
    code, out, err = run_cli("brake", "--hand-force-N", 250, "--direction", "uphill", "--t-end-s", 3600,
                             "--dt-s", 600, "--format", "csv")
    assert code == 0, err
    lines = out.strip().splitlines()
    assert lines[0] == "time_s,drum_temp_C,normal_force_N,torque_Nm"
    rows = list(csv.DictReader(io.StringIO(out)))
    assert [float(r["time_s"]) for r in rows] == [0, 600, 1200, 1800, 2400, 3000, 3600]
    ref = drum_brake(paper(), time_s=np.arange(7) * 600.0, hand_force_N=250, direction="uphill")
    np.testing.assert_allclose([float(r["torque_Nm"]) for r in rows], ref.torque_Nm, rtol=1e-10)
    assert float(rows[-1]["torque_Nm"]) == pytest.approx(397.758, abs=1e-3)


def test_brake_options_change_result(run_cli):
    base = run_cli("brake", "--hand-force-N", 300, "--format", "json")[1]
    for extra in (["--mu", "0.3"], ["--gap-mm", "1"], ["--t0-C", "150"]):
        code, out, _ = run_cli("brake", "--hand-force-N", 300, "--format", "json", *extra)
        assert code == 0 and json.loads(out) != json.loads(base)


def test_brake_params_file(run_cli, tmp_path):
    f = tmp_path / "p.toml"
    f.write_text('extends = "paper"\ndrum_radius_m = 0.18\n')
    a = json.loads(run_cli("brake", "--hand-force-N", 300, "--format", "json")[1])
    b = json.loads(run_cli("brake", "--hand-force-N", 300, "--format", "json", "--params", f)[1])
    assert b[0]["torque_Nm"] == pytest.approx(2 * a[0]["torque_Nm"])


@pytest.mark.parametrize("args, needle", [
    (["--hand-force-N", "-5"], "hand force -5 N is negative"),
    (["--hand-force-N", "abc"], "--hand-force-N"),
    (["--hand-force-N", "300", "--direction", "sideways"], "unknown direction 'sideways'"),
    (["--hand-force-N", "300", "--format", "xml"], "unknown format 'xml'"),
    (["--hand-force-N", "300", "--dt-s", "0"], "--dt-s 0 must be > 0"),
    (["--hand-force-N", "300", "--mu", "1.2"], "self-locks"),
    (["--hand-force-N", "300", "--params", "nope.toml"], "'nope.toml' does not exist"),
    (["--hand-force-N", "300", "--gap-mm", "-1"], "gap_m"),
    ([], "Missing option '--hand-force-N'"),
])
def test_brake_bad_input(run_cli, args, needle):
    code, out, err = run_cli("brake", *args)
    assert code == 2
    assert needle in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_console_script_bad_input_has_no_traceback():
    r = subprocess.run([sys.executable, "-m", "rollaway", "brake", "--hand-force-N", "-1"],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "Traceback" not in r.stderr and "negative" in r.stderr


@pytest.mark.parametrize("force, direction, gap_mm, mu", [(150, "downhill", 0, 0.3), (250, "uphill", 1, 0.6),
                                                          (400, "uphill", 0, 0.4), (340, "downhill", 1, 0.4)])
def test_brake_csv_matches_independent_reference(run_cli, force, direction, gap_mm, mu):
    from tests.conftest import DATA
    with open(DATA / "reference-values.csv") as fh:
        ref = [r for r in csv.DictReader(fh) if float(r["hand_force_N"]) == force and r["direction"] == direction
               and float(r["gap_m"]) == gap_mm / 1000 and float(r["mu_drum"]) == mu]
    assert len(ref) == 7
    code, out, err = run_cli("brake", "--hand-force-N", force, "--direction", direction, "--gap-mm", gap_mm,
                             "--mu", mu, "--t-end-s", 3600, "--dt-s", 600, "--format", "csv")
    assert code == 0, err
    got = list(csv.DictReader(io.StringIO(out)))
    for g, r in zip(got, ref, strict=True):
        for col in ("time_s", "drum_temp_C", "normal_force_N", "torque_Nm"):
            assert float(g[col]) == pytest.approx(float(r[col]), rel=1e-6, abs=1e-9), col


def test_the_series_ends_at_t_end_where_the_steps_do_not_land_on_it():
    from rollaway.cli.brake import time_grid_s
    assert list(time_grid_s(1.0, 600.0)) == [0.0, 1.0]
    assert list(time_grid_s(1000.0, 600.0)) == [0.0, 600.0, 1000.0]
    assert list(time_grid_s(3600.0, 600.0)) == [0.0, 600.0, 1200.0, 1800.0, 2400.0, 3000.0, 3600.0]
    assert list(time_grid_s(0.0, 600.0)) == [0.0]
