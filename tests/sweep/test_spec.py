"""SWEEP.toml loading: grids, ranges, list mode, and every bad form as a one-line error (exit 2)."""
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from rollaway.errors import UserError
from rollaway.sweep.spec import AXES, load_sweep

ROOT = Path(__file__).resolve().parents[2]


def write(tmp_path, text, name="s.toml"):
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


def test_grid_product_ranges_and_preset_directions(tmp_path):
    spec = load_sweep(write(tmp_path, 'base_preset = "fmvss135"\n[grid]\n'
                                      'grade_pct = {start = 0, stop = 40, num = 5}\n'
                                      'occupants = [1, 5]\nhand_force_N = {start = 100, stop = 400, step = 100}\n'))
    df = spec.points
    assert len(df) == 5 * 2 * 4 * 2          # preset gives both directions
    assert sorted(df["grade_pct"].unique()) == [0, 10, 20, 30, 40]
    assert sorted(df["hand_force_N"].unique()) == [100, 200, 300, 400]
    assert set(df["direction"]) == {"uphill", "downhill"}
    assert (df["duration_s"] == 300).all() and (df["mu_drum"] == 0.4).all()   # from the base
    assert df["point_id"].is_unique and list(df["point_index"]) == list(range(len(df)))
    assert list(df.columns[2:]) == list(AXES)


def test_point_ids_are_stable_and_depend_on_inputs_and_base(tmp_path):
    a = load_sweep(write(tmp_path, 'base_preset = "fmvss135"\n[grid]\ngrade_pct = [10, 20]\n'))
    b = load_sweep(write(tmp_path, 'base_preset = "fmvss135"\n[grid]\ngrade_pct = [20, 10, 20]\n', "b.toml"))
    assert set(a.points["point_id"]) == set(b.points["point_id"])      # same inputs, same ids; dupes dropped
    assert len(b.points) == 4
    c = load_sweep(write(tmp_path, 'base_preset = "paper30"\n[grid]\ngrade_pct = [10, 20]\n', "c.toml"))
    assert not set(a.points["point_id"]) & set(c.points["point_id"])


def test_base_file_relative_and_list_mode(tmp_path):
    (tmp_path / "scen").mkdir()
    write(tmp_path / "scen", 'name = "x"\ngrade_pct = 12\ndirection = "uphill"\noccupants = 2\n'
                             'hand_force_N = 300\nduration_s = 60\nmu_drum = 0.35\n', "base.toml")
    (tmp_path / "sw").mkdir()
    spec = load_sweep(write(tmp_path / "sw", 'base = "../scen/base.toml"\nsimulate = "all"\n'
                                             '[[points]]\ngrade_pct = 30\n[[points]]\noccupants = 5\n'
                                             'direction = "downhill"\n'))
    df = spec.points
    assert len(df) == 2 and spec.simulate == "all"
    assert df.loc[0, "grade_pct"] == 30 and df.loc[0, "occupants"] == 2 and df.loc[0, "mu_drum"] == 0.35
    assert df.loc[1, "direction"] == "downhill" and df.loc[1, "grade_pct"] == 12


def test_example_sweeps_load():
    for p in sorted((ROOT / "scenarios" / "sweeps").glob("*.toml")):
        assert len(load_sweep(p).points) > 0, p


@pytest.mark.parametrize("text, words", [
    ('base_preset = "fmvss135"\n[grid]\ngrade = [10]\n', ["[grid]", "unknown key 'grade'", "grade_pct"]),
    ('base_preset = "fmvss135"\n[grid]\ngrade_pct = {start = 0, stop = 10}\n', ["grade_pct", "num", "step"]),
    ('base_preset = "fmvss135"\n[grid]\ngrade_pct = {start = 0, stop = 10, num = 3, step = 1}\n', ["exactly one"]),
    ('base_preset = "fmvss135"\n[grid]\ngrade_pct = {start = 0, stop = 10, nun = 3}\n', ["'nun'", "num"]),
    ('base_preset = "fmvss135"\n[grid]\ngrade_pct = {start = 0, stop = 10, num = 0}\n', ["num", "≥ 1"]),
    ('base_preset = "fmvss135"\n[grid]\ngrade_pct = {start = 0, stop = 10, step = -1}\n', ["step", "> 0"]),
    ('base_preset = "fmvss135"\n[grid]\ngrade_pct = []\n', ["grade_pct", "empty"]),
    ('base_preset = "fmvss135"\n[grid]\ngrade_pct = ["steep"]\n', ["grade_pct", "number", "steep"]),
    ('base_preset = "fmvss135"\n[grid]\ndirection = ["uphil"]\n', ["uphil", "did you mean 'uphill'"]),
    ('base_preset = "fmvs135"\n[grid]\ngrade_pct = [1]\n', ["fmvs135", "fmvss135"]),
    ('base = "nowhere.toml"\n[grid]\ngrade_pct = [1]\n', ["nowhere.toml", "does not exist"]),
    ('[grid]\ngrade_pct = [1]\n', ["base", "base_preset"]),
    ('base_preset = "fmvss135"\n', ["nothing to sweep"]),
    ('base_preset = "fmvss135"\nsimulate = "some"\n[grid]\ngrade_pct = [1]\n', ["simulate", "band"]),
    ('base_preset = "fmvss135"\nband = [1.2, 0.9]\n[grid]\ngrade_pct = [1]\n', ["band", "low < high"]),
    ('base_preset = "fmvss135"\nsimualte = "all"\n[grid]\ngrade_pct = [1]\n', ["simualte", "simulate"]),
    ('base_preset = "fmvss135"\n[[points]]\ngrade_pct = 5\n[[points]]\noccupnts = 2\n', ["#2", "occupnts", "occupants"]),
    ('base_preset = "fmvss135"\n[grid\n', ["not valid TOML"]),
])
def test_bad_specs_are_one_line_errors_naming_file_and_key(tmp_path, run_cli, text, words):
    p = write(tmp_path, text)
    with pytest.raises(UserError):
        load_sweep(p)
    code, out, err = run_cli("sweep", p, "--out", tmp_path / "o", "--quiet")
    assert code == 2, (out, err)
    assert err.count("\n") == 1 and "Traceback" not in err
    assert str(p) in err
    for w in words:
        assert w in err, (w, err)


@pytest.mark.parametrize("args, words", [
    (["--workers", "0"], ["--workers", "≥ 1"]),
    (["--simulate", "everything"], ["everything", "band"]),
    (["--workers", "2", "--dask", "tcp://127.0.0.1:1"], ["--dask", "one or the other"]),
])
def test_bad_options(tmp_path, run_cli, args, words):
    p = write(tmp_path, 'base_preset = "fmvss135"\n[grid]\ngrade_pct = [10]\n')
    code, out, err = run_cli("sweep", p, "--out", tmp_path / "o", "--quiet", *args)
    assert code == 2 and err.count("\n") == 1
    for w in words:
        assert w in err


def test_missing_sweep_file(tmp_path, run_cli):
    code, _, err = run_cli("sweep", tmp_path / "none.toml")
    assert code == 2 and "does not exist" in err


def test_unreachable_dask_scheduler_is_a_user_error(tmp_path, run_cli, monkeypatch):
    monkeypatch.setenv("ROLLAWAY_DASK_TIMEOUT_S", "2")
    p = write(tmp_path, 'base_preset = "fmvss135"\nsimulate = "all"\n[[points]]\ngrade_pct = 10\n')
    code, _, err = run_cli("sweep", p, "--out", tmp_path / "o", "--quiet", "--no-plots",
                           "--dask", "tcp://127.0.0.1:9")
    assert code == 2 and "cannot reach the Dask scheduler" in err and err.count("\n") == 1


def test_range_endpoints_inclusive_step(tmp_path):
    spec = load_sweep(write(tmp_path, 'base_preset = "fmvss135"\n[grid]\n'
                                      'grade_pct = {start = 0, stop = 1, step = 0.1}\n'))
    g = np.sort(spec.points["grade_pct"].unique())
    assert len(g) == 11 and g[-1] == pytest.approx(1.0)


def test_point_ids_are_stable_vectorised_and_ignore_the_sign_of_zero():
    import subprocess
    import sys
    from rollaway.hold.scenario import preset_scenarios
    from rollaway.sweep.spec import grid_spec, point_ids
    base = preset_scenarios("fmvss135")[0]
    spec = grid_spec(base, {"grade_pct": [0.0, -0.0, 10.0, 20.0], "direction": ["uphill", "downhill"]})
    assert len(spec.points) == 2 * 3                       # -0.0 and 0.0 are one point
    ids = list(spec.points["point_id"])
    assert len(set(ids)) == len(ids) and all(len(i) == 16 and int(i, 16) >= 0 for i in ids)
    code = ("from rollaway.hold.scenario import preset_scenarios; from rollaway.sweep.spec import grid_spec;"
            "print(list(grid_spec(preset_scenarios('fmvss135')[0], {'grade_pct': [0.0, 10.0, 20.0],"
            "'direction': ['uphill', 'downhill']}).points['point_id']))")
    other = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert other.strip() == str(ids)                        # same ids in another process
    changed = base.replace(mu_drum=0.41)
    assert set(point_ids(changed, spec.points)).isdisjoint(ids)   # the base's parameters are part of the id


def test_a_sweep_on_a_model_takes_the_axes_it_does_not_set_from_the_model(tmp_path):
    """μ_d and μ_r unset by the sweep are the model's (a calibrated μ_d), not the base's paper values; an axis the
    sweep sets keeps its values."""
    import rollaway
    f = tmp_path / "s.toml"
    f.write_text('base_preset = "fmvss135"\nsimulate = "none"\n[grid]\ngrade_pct = [10, 20]\n')
    model = rollaway.DrumModel("paper").replace_params(mu_drum=0.27, tyre_road_mu=0.7)
    s = load_sweep(f).with_model(model)
    assert np.allclose(s.points["mu_drum"], 0.27) and np.allclose(s.points["tyre_road_mu"], 0.7)
    assert sorted(set(s.points["grade_pct"])) == [10.0, 20.0]
    f.write_text('base_preset = "fmvss135"\nsimulate = "none"\n[grid]\nmu_drum = [0.3, 0.4]\n')
    s = load_sweep(f).with_model(model)
    assert sorted(set(s.points["mu_drum"])) == [0.3, 0.4] and np.allclose(s.points["tyre_road_mu"], 0.7)
    res = rollaway.sweep(f, tmp_path / "out", model=model, plots=False)
    assert sorted(set(res.table["mu_drum"])) == [0.3, 0.4]


def test_a_self_locking_point_is_said_so_and_claims_no_agreement(tmp_path):
    """A point where the leading shoe self-locks (μ_d = 1.5 facing downhill, eqs. 18–21) is outside the 1D model:
    its row says why and counts neither as agreeing nor as a tyre skid."""
    import rollaway
    f = tmp_path / "s.toml"
    f.write_text('base_preset = "fmvss135"\nsimulate = "none"\n[grid]\nmu_drum = [0.4, 1.5]\n')
    t = rollaway.sweep(f, tmp_path / "out", plots=False).table
    row = t[(t["mu_drum"] == 1.5) & (t["direction"] == "downhill")].iloc[0]
    assert row["analytic_outcome"] == "self_locking" and row["verdict"] != "hold"
    assert "self-locks" in row["disagreement"] and "tyres" not in row["disagreement"]
    assert row["agree"] is pd.NA
    assert t[t["mu_drum"] == 0.4]["agree"].all()
