"""Reading lab logs: CSV, Parquet, a folder with one file per test (+ manifest), renamed columns in °F, ms, lbf·ft
give the canonical data and the same verdict; every bad input is one line naming the file, the column and the fix."""
import json

import numpy as np
import pandas as pd
import pytest

from rollaway.errors import UserError
from rollaway.bench.columns import column_map
from rollaway.bench.sources import read_log
from rollaway.identify.synth import synth
from tests.identify.lab_export import COLUMNS_TOML, export_file, export_folder


@pytest.fixture(scope="module")
def dense():
    """10 Hz, 4 tests × 6 min, hidden lining creep (14 404 rows)."""
    return synth(["lining_creep"], seed=3, dt_s=0.1, duration_s=360.0, hand_forces_N=(210.0, 330.0))


def _same(a, b, rtol=1e-9):
    assert list(a.tests) == list(b.tests)
    for name in ("hand_force_N", "time_s", "drum_temp_C", "torque_Nm"):
        assert np.allclose(getattr(a, name), getattr(b, name), rtol=rtol, atol=1e-9), name
    assert np.array_equal(a.direction, b.direction)


@pytest.mark.parametrize("layout", ["folder_csv", "folder_parquet", "file_parquet", "file_csv", "folder_no_manifest"])
def test_lab_exports_read_as_the_canonical_data(tmp_path, dense, layout):
    if layout.startswith("folder"):
        path = export_folder(dense, tmp_path / "bench", "parquet" if layout == "folder_parquet" else "csv",
                             manifest=layout != "folder_no_manifest")
        cols = path / "columns.toml"
    else:
        path = export_file(dense, tmp_path / ("all.parquet" if layout == "file_parquet" else "all.csv"))
        cols = tmp_path / "columns.toml"
    raw = read_log(path, column_map([cols]), window_s=0)
    _same(raw, dense)
    assert raw.rows_info()["rows_read"] == len(dense) and raw.reduction.files == (4 if "folder" in layout else 1)
    red = read_log(path, column_map([cols]))
    assert red.reduction.reduced and red.rows_info()["rows"] == len(red) < len(dense) / 10


def test_canonical_csv_through_the_streaming_reader_matches_the_strict_loader(tmp_path, dense):
    from rollaway.bench.measurements import load_measurements
    f = tmp_path / "bench.csv"
    dense.to_csv(f)
    _same(read_log(f, window_s=0), load_measurements(f))


def test_european_csv_semicolons_and_decimal_commas(tmp_path, dense):
    f = tmp_path / "all.csv"
    dense.to_frame().to_csv(f, sep=";", decimal=",", index=False)
    assert "," in f.read_text().splitlines()[2]
    _same(read_log(f, window_s=0), dense)


def test_single_file_without_test_id_is_one_test_named_after_the_file(tmp_path):
    f = tmp_path / "D250.csv"
    pd.DataFrame({"time_s": [0.0, 1.0, 2.0], "drum_temp_C": [200.0, 199.0, 198.0], "torque_Nm": [800.0, 801.0, 799.0],
                  "direction": "downhill", "hand_force_N": 250.0}).to_csv(f, index=False)
    d = read_log(f)
    assert d.tests == ["D250"] and len(d) == 3 and not d.reduction.reduced


def test_lab_exports_give_the_canonical_verdict_through_the_cli(run_cli, tmp_path, dense):
    canonical = tmp_path / "bench.csv"
    dense.to_csv(canonical)
    folder = export_folder(dense, tmp_path / "lab", "parquet")
    verdicts = []
    model = tmp_path / "m.toml"
    for args in ([canonical, "--window-s", "6"], [folder, "--save-model", model]):   # columns.toml found by itself
        code, out, err = run_cli("diagnose", *args, "--format", "json")
        assert code == 0, err
        d = json.JSONDecoder().raw_decode(out)[0]          # (--save-model adds a line after the JSON)
        assert d["data"]["rows_read"] == len(dense) and d["data"]["window_s"] == 6.0
        assert "read 14,404 rows" in err and "reduced to" in err
        verdicts.append((d["verdict"], d["refined"]["parameters"]["mu_drum"]["value"]))
    assert verdicts[0][0] == verdicts[1][0] == "lining_creep"
    assert 'data_file = "lab/"' in model.read_text() and f"rows = {len(dense)}" in model.read_text()
    # the same data through two readers: equal within the fit's stopping tolerance (its standard error is ~1e-3)
    assert verdicts[0][1] == pytest.approx(verdicts[1][1], rel=1e-6)


def _folder(tmp_path, files: dict, manifest: str | None = None):
    folder = tmp_path / "lab"
    folder.mkdir()
    (folder / "columns.toml").write_text('[columns]\ntime_s = "Time"\ntorque_Nm = "Torque"\ndrum_temp_C = "T_drum"\n',
                                         encoding="utf-8")
    for name, text in files.items():
        (folder / name).write_text(text, encoding="utf-8")
    if manifest is not None:
        (folder / "manifest.csv").write_text(manifest, encoding="utf-8")
    return folder


LOG = "Time [ms],Torque [Nm],T_drum [°F]\n0,800,392\n1000,801,390\n2000,799,388\n"
MANIFEST = "test_id,direction,hand_force_N\nD250,downhill,250\nU250,uphill,250\n"


@pytest.mark.parametrize("case, words", [
    ("unknown unit", ["D250.csv", "'Torque [Nmm]'", "unknown unit 'Nmm'", "N·m, lbf·ft, kN·m"]),
    ("absent column", ["D250.csv", "'Drum temperature'", "no such column", "--columns"]),
    ("mixed units", ["U250.csv", "'Torque [lbf·ft]'", "N·m in D250.csv", "mixed units", "one unit"]),
    ("no hand force", ["D250.csv", "'hand_force_N'", "no hand force", "manifest.csv"]),
    ("not in manifest", ["U250.csv", "'hand_force_N'", "add a row for test 'U250'"]),
    ("not a number", ["D250.csv, line 3, column 'Torque [Nm]'", "'n/a?'", "not a number"]),
    ("late start", ["D250.csv", "line 2", "'Time [ms]'", "starts at 5 s", "time 0"]),
    ("time decreases", ["D250.csv", "line 4", "'Time [ms]'", "time decreases", "sort the rows"]),
    ("bad direction", ["manifest", "direction", "'downhil'", "did you mean 'downhill'"]),
])
def test_bad_lab_input_is_one_line_with_file_column_and_fix(run_cli, tmp_path, case, words):
    files, manifest, extra = {"D250.csv": LOG, "U250.csv": LOG}, MANIFEST, []
    if case == "unknown unit":
        files["D250.csv"] = LOG.replace("[Nm]", "[Nmm]")
    elif case == "absent column":
        extra = ["--columns", "drum_temp_C=Drum temperature[degF]", "--columns", "time_s=Time",
                 "--columns", "torque_Nm=Torque"]
    elif case == "mixed units":
        files["U250.csv"] = LOG.replace("[Nm]", "[lbf·ft]")
    elif case == "no hand force":
        manifest = None
    elif case == "not in manifest":
        manifest = "test_id,direction,hand_force_N\nD250,downhill,250\n"
    elif case == "not a number":
        files["D250.csv"] = LOG.replace("801", "n/a?")
    elif case == "late start":
        files["D250.csv"] = LOG.replace("\n0,", "\n5000,").replace("1000,", "6000,").replace("2000,", "7000,")
    elif case == "time decreases":
        files["D250.csv"] = LOG.replace("2000,", "500,")
    elif case == "bad direction":
        manifest = MANIFEST.replace("D250,downhill", "D250,downhil")
    folder = _folder(tmp_path, files, manifest)
    code, out, err = run_cli("compare", folder, *extra)
    assert code == 2 and "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    for w in words:
        assert w in err, (w, err)


def test_a_parquet_column_of_text_is_refused_by_name(tmp_path):
    f = tmp_path / "D250.parquet"
    pd.DataFrame({"time_s": ["0", "1", "x"], "drum_temp_C": [1.0, 2.0, 3.0], "torque_Nm": [1.0, 2.0, 3.0],
                  "direction": "uphill", "hand_force_N": 200.0}).to_parquet(f)
    with pytest.raises(UserError, match=r"D250.parquet, column 'time_s'.*not numbers"):
        read_log(f)


def test_columns_toml_without_table_is_refused(tmp_path):
    f = tmp_path / "c.toml"
    f.write_text(COLUMNS_TOML.replace("[columns]", "[cols]"), encoding="utf-8")
    with pytest.raises(UserError, match="no \\[columns\\] table"):
        column_map([f])


def test_mdf4_files_with_channel_units_read_as_the_canonical_data(tmp_path, dense):
    asammdf = pytest.importorskip("asammdf")
    folder = tmp_path / "mdf"
    folder.mkdir()
    frame = dense.to_frame()
    for tid, part in frame.groupby("test_id", sort=False):
        t = part["time_s"].to_numpy()
        m = asammdf.MDF(version="4.10")
        m.append([asammdf.Signal(part["torque_Nm"].to_numpy() / 1000.0, t, name="Torque", unit="kNm"),
                  asammdf.Signal(part["drum_temp_C"].to_numpy() + 273.15, t, name="T_drum", unit="K")])
        m.save(folder / f"{tid}.mf4", overwrite=True)
        m.close()
    frame.groupby("test_id", sort=False)[["direction", "hand_force_N"]].first().to_csv(folder / "manifest.csv")
    d = read_log(folder, column_map(["torque_Nm=Torque", "drum_temp_C=T_drum"]), window_s=0)
    _same(d, dense)


def test_rows_before_the_lever_is_applied_are_read_but_not_kept(tmp_path, dense):
    frame = dense.to_frame()
    pre = frame.groupby("test_id", sort=False).head(50).copy()
    pre["time_s"] = pre["time_s"] - 5.0                         # 5 s of pre-trigger log per test
    both = pd.concat([pre, frame]).sort_values(["test_id", "time_s"], kind="stable")
    both = both.set_index("test_id").loc[list(dense.tests)].reset_index()
    f = tmp_path / "pretrigger.csv"
    both.to_csv(f, index=False)
    d = read_log(f, window_s=0)
    _same(d, dense)
    info = d.rows_info()
    assert info["rows_read"] == len(dense) + 200 and info["rows_kept"] == len(dense)
    assert any("200 rows logged before time 0" in n for n in d.notes)
    assert "kept 14,404" in d.reduction.summary() and "read 14,604" in d.reduction.summary()


def test_a_folder_says_what_it_does_not_read_and_checks_a_test_id_column(tmp_path, run_cli):
    d = synth([], seed=6, dt_s=600.0, duration_s=3600.0, hand_forces_N=(250.0,))
    folder = tmp_path / "bench"
    folder.mkdir()
    frame = d.to_frame()
    for t, rows in frame.groupby("test_id", sort=False):
        rows.assign(operator="bob").to_csv(folder / f"{t}.csv", index=False)
    (folder / "photo.jpg").write_bytes(b"\xff\xd8")
    code, out, err = run_cli("compare", folder, "--format", "json")
    assert code == 0, err
    notes = json.loads(out)["data"]["notes"]
    assert any("ignoring column(s) 'operator'" in n for n in notes) and any("photo.jpg" in n for n in notes)
    first = d.tests[0]
    frame[frame.test_id == first].assign(test_id="other").to_csv(folder / f"{first}.csv", index=False)
    with pytest.raises(UserError, match=rf"{first}.csv, line 2, column 'test_id': test 'other', but a folder's file"):
        read_log(folder)
