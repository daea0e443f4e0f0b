import textwrap

import pytest

from rollaway.bench import load_measurements
from rollaway.errors import UserError

GOOD = """\
test_id,direction,hand_force_N,time_s,drum_temp_C,torque_Nm
A,downhill,250,0,200,1126
A,downhill,250,300,180,1100
A,downhill,250,600,160,1080
B,uphill,300,0,195,600
B,uphill,300,300,175,590
B,uphill,300,600,158,580
"""


def _write(tmp_path, text, name="m.csv"):
    p = tmp_path / name
    p.write_text(textwrap.dedent(text))
    return p


def test_good_file_loads(tmp_path):
    d = load_measurements(_write(tmp_path, GOOD))
    assert len(d) == 6 and d.tests == ["A", "B"]
    assert list(d.test_initial_temp_C) == [200.0, 195.0]
    assert d.ambient_C is None


def _bad(text, line, col):
    return text, line, col


CASES = {
    "missing column": (GOOD.replace(",torque_Nm", "").replace(",1126", "").replace(",1100", "")
                       .replace(",1080", "").replace(",600\n", "\n").replace(",590", "").replace(",580", ""),
                       1, "torque_Nm", "missing column"),
    "non-numeric": (GOOD.replace("A,downhill,250,300,180", "A,downhill,250,300,hot"), 3, "drum_temp_C",
                    "not a number"),
    "nan": (GOOD.replace("1080", "nan"), 4, "torque_Nm", "not a finite number"),
    "duplicate time": (GOOD.replace("B,uphill,300,300,175", "B,uphill,300,0,175"), 6, "time_s", "duplicate time"),
    "decreasing time": (GOOD.replace("A,downhill,250,600,160", "A,downhill,250,200,160"), 4, "time_s",
                        "time decreases"),
    "unknown direction": (GOOD.replace("B,uphill,300,300", "B,upnill,300,300"), 6, "direction",
                          "unknown direction"),
    "two hand forces": (GOOD.replace("B,uphill,300,600", "B,uphill,320,600"), 7, "hand_force_N",
                        "two hand forces"),
    "empty cell": (GOOD.replace("A,downhill,250,300,180,1100", "A,downhill,,300,180,1100"), 3, "hand_force_N",
                   "empty cell"),
    "not starting at zero": (GOOD.replace("A,downhill,250,0,200", "A,downhill,250,60,200")
                             .replace("A,downhill,250,300", "A,downhill,250,310"), 2, "time_s", "must start"),
}


@pytest.mark.parametrize("cell", [" 1126 ", "1.126e3", "NA", "", "nan", "+inf", "11x6"])
def test_columns_read_at_once_give_what_the_cells_one_by_one_give(tmp_path, monkeypatch, cell):
    """Clean numeric columns are converted in one call; anything else falls back to the cells one by one.  Both
    read every file the same: the same rows and values, or the same error (a missing or infinite cell, a typo)."""
    import numpy as np

    from rollaway.bench import measurements
    path = _write(tmp_path, GOOD.replace("A,downhill,250,0,200,1126", f"A,downhill,250,0,200,{cell}", 1))

    def read():
        try:
            return load_measurements(path)
        except UserError as exc:
            return str(exc)
    fast = read()
    monkeypatch.setattr(measurements, "_columns_at_once", lambda *a, **k: None)
    slow = read()
    if isinstance(slow, str):
        assert fast == slow and "line 2, column 'torque_Nm'" in slow
        return
    assert float(slow.torque_Nm[0]) == 1126.0
    for name in ("test_id", "direction", "hand_force_N", "time_s", "drum_temp_C", "torque_Nm"):
        assert np.array_equal(getattr(fast, name), getattr(slow, name)), name


def test_an_underscore_in_a_number_is_not_read_as_one(tmp_path):
    """``float`` reads '1_126' as 1126; the bench readers (as pyarrow) do not: the cell is listed as not a number."""
    with pytest.raises(UserError, match=r"line 2, column 'torque_Nm': '1_126' is not a number"):
        load_measurements(_write(tmp_path, GOOD.replace(",1126", ",1_126", 1)))


@pytest.mark.parametrize("case", list(CASES))
def test_malformed_files_name_file_line_and_column(tmp_path, case, run_cli):
    text, line, col, what = CASES[case]
    path = _write(tmp_path, text)
    with pytest.raises(UserError) as exc:
        load_measurements(path)
    first = str(exc.value).splitlines()[0]
    assert f"{path}, line {line}, column '{col}'" in first and what in first
    for cmd in ("compare", "diagnose"):
        code, out, err = run_cli(cmd, path)
        assert code == 2, (cmd, out, err)
        assert f"line {line}, column '{col}'" in err.splitlines()[0]
        assert "Traceback" not in err


def test_every_problem_is_listed(tmp_path):
    text = GOOD.replace("1080", "nan").replace("B,uphill,300,300", "B,sideways,300,300")
    with pytest.raises(UserError) as exc:
        load_measurements(_write(tmp_path, text))
    msg = str(exc.value)
    assert "(and 1 more problem)" in msg and "line 4" in msg and "line 6" in msg


def test_missing_file_and_typo_header(tmp_path):
    with pytest.raises(UserError, match="does not exist"):
        load_measurements(tmp_path / "nope.csv")
    with pytest.raises(UserError, match="rename it 'torque_Nm'"):
        load_measurements(_write(tmp_path, GOOD.replace("torque_Nm", "torque_nm")))
