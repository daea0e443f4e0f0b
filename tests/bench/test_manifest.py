"""Manifests: nothing dropped, overridden or reused without a word.  A test listed twice, a row without its test,
a test without its row, a test file with no rows, a log and its manifest disagreeing: each is one line naming
both places; a single log with test ids takes its directions and forces from ``--manifest``."""
import numpy as np
import pytest

from rollaway.bench.sources import read_log
from rollaway.errors import UserError
from rollaway.identify.synth import synth


@pytest.fixture(scope="module")
def data():
    return synth([], seed=1, dt_s=600.0, duration_s=3600.0, hand_forces_N=(250.0, 340.0))


def _manifest(data, extra: str = "", drop: str | None = None) -> str:
    rows = [f"{t['test_id']},{t['direction']},{t['hand_force_N']:g}" for t in data.test_info() if t["test_id"] != drop]
    return "test_id,direction,hand_force_N\n" + "\n".join(rows) + "\n" + extra


def _folder(tmp_path, data, manifest: str, skip=(), with_direction=None):
    folder = tmp_path / "bench"
    folder.mkdir(parents=True)
    (folder / "manifest.csv").write_text(manifest)
    frame = data.to_frame()
    for t, rows in frame.groupby("test_id", sort=False):
        if t in skip:
            continue
        cols = ["time_s", "drum_temp_C", "torque_Nm"]
        out = rows[cols].copy()
        if with_direction and t in with_direction:
            out.insert(0, "direction", with_direction[t])
        out.to_csv(folder / f"{t}.csv", index=False)
    return folder


def _error(fn, *args, **kw) -> str:
    with pytest.raises(UserError) as exc:
        fn(*args, **kw)
    msg = str(exc.value)
    assert "\n" not in msg.split(" (and ")[0]
    return msg


def test_a_folder_with_its_manifest_reads_as_the_canonical_data(tmp_path, data):
    d = read_log(_folder(tmp_path, data, _manifest(data)), window_s=0)
    assert d.tests == data.tests and np.array_equal(d.hand_force_N, data.hand_force_N)
    assert np.array_equal(d.direction, data.direction)


def test_a_test_listed_twice_names_both_lines(tmp_path, data):
    first = data.tests[0]
    msg = _error(read_log, _folder(tmp_path, data, _manifest(data, f"{first},downhill,300\n")))
    assert f"manifest.csv, line {len(data.tests) + 2}" in msg and f"'{first}' is listed twice (also on line 2)" in msg


def test_a_manifest_row_without_its_file_and_a_file_without_its_row(tmp_path, data):
    first, last = data.tests[0], data.tests[-1]
    msg = _error(read_log, _folder(tmp_path / "a", data, _manifest(data), skip=[first]))
    assert "manifest.csv, line 2" in msg and f"'{first}' has no data" in msg
    msg = _error(read_log, _folder(tmp_path / "b", data, _manifest(data, drop=last)))
    assert f"{last}.csv" in msg and "no manifest entry" in msg and "add a row" in msg


def test_a_test_file_with_a_header_and_no_rows_is_an_error(tmp_path, data):
    folder = _folder(tmp_path, data, _manifest(data))
    (folder / f"{data.tests[1]}.csv").write_text("time_s,drum_temp_C,torque_Nm\n")
    msg = _error(read_log, folder)
    assert f"{data.tests[1]}.csv, line 2: no data rows" in msg and "manifest row" in msg


def test_a_log_and_its_manifest_disagreeing_on_the_direction(tmp_path, data):
    first = data.tests[0]
    wrong = "uphill" if data.direction[0] == "downhill" else "downhill"
    msg = _error(read_log, _folder(tmp_path, data, _manifest(data), with_direction={first: wrong}))
    assert f"{first}.csv, line 2, column 'direction'" in msg and f"is {wrong} here" in msg
    assert "manifest.csv, line 2" in msg


def test_a_single_log_with_test_ids_takes_the_manifest_and_must_agree_with_it(tmp_path, data):
    frame = data.to_frame()
    man = tmp_path / "tests.csv"
    man.write_text(_manifest(data))
    log = tmp_path / "log.csv"
    frame.drop(columns=["direction", "hand_force_N"]).to_csv(log, index=False)
    d = read_log(log, manifest=str(man), window_s=0)
    assert np.array_equal(d.hand_force_N, data.hand_force_N) and np.array_equal(d.direction, data.direction)
    man.write_text(_manifest(data, "X9,uphill,200\n"))
    msg = _error(read_log, log, manifest=str(man))
    assert f"tests.csv, line {len(data.tests) + 2}" in msg and "'X9' has no data" in msg
    man.write_text(_manifest(data, drop=data.tests[-1]))
    msg = _error(read_log, log, manifest=str(man))
    assert f"'{data.tests[-1]}' has no row in the manifest" in msg
    frame.loc[0, "hand_force_N"] = frame.loc[0, "hand_force_N"] + 10
    frame.to_csv(log, index=False)
    man.write_text(_manifest(data))
    msg = _error(read_log, log, manifest=str(man))
    assert "log.csv, line 2, column 'hand_force_N'" in msg and "tests.csv, line 2" in msg


def test_the_cli_takes_manifest_for_a_single_file(tmp_path, data, run_cli):
    log = tmp_path / "log.csv"
    data.to_frame().drop(columns=["direction", "hand_force_N"]).to_csv(log, index=False)
    man = tmp_path / "m.csv"
    man.write_text(_manifest(data))
    code, out, err = run_cli("compare", log, "--manifest", man, "--format", "json")
    assert code == 0, err


def test_a_european_manifest_with_semicolons_and_decimal_commas(tmp_path, data):
    man = _manifest(data).replace(",", ";").replace("250.5", "250,5")
    d = read_log(_folder(tmp_path, data, man), window_s=0)
    assert np.array_equal(d.hand_force_N, data.hand_force_N)


def test_two_manifests_two_files_for_one_test_and_which_manifest_is_used(tmp_path, data):
    folder = _folder(tmp_path, data, _manifest(data))
    (folder / "tests.csv").write_text(_manifest(data))
    assert "the folder has two manifests (manifest.csv, tests.csv)" in _error(read_log, folder)
    (folder / "tests.csv").unlink()
    first = data.tests[0]
    (folder / f"{first}.parquet").write_bytes(b"")
    assert f"a second file for test '{first}' (also {first}.csv)" in _error(read_log, folder)
    (folder / f"{first}.parquet").unlink()
    (folder / "old").mkdir()
    other = tmp_path / "elsewhere.csv"
    other.write_text(_manifest(data))
    notes = read_log(folder, manifest=str(other), window_s=0).notes
    assert any("not read" in n and "old/" in n for n in notes)
    assert any(f"--manifest {other} is used, not the folder's manifest.csv" in n for n in notes)
