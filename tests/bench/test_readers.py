"""The strict (small-file) and the streaming (large-file) readers give the same rows or the same error on any log.

The CLI reads a small canonical CSV with Python's csv module (bench.measurements) and anything larger with
pyarrow's streaming reader (bench.readers, bench.sources); both hand their rows to the same reducer.  The
property test generates logs with the defects labs make (bad cells, ragged rows, rows before the lever,
swapped rows, two forces in one test, unknown directions) and forces each path in turn through
``load_data``'s size threshold.
"""
import re
import tempfile
from pathlib import Path
from unittest import mock

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rollaway.bench.readers import parse_number
from rollaway.cli import identify_common
from rollaway.errors import UserError

HEADER = ["test_id", "direction", "hand_force_N", "time_s", "drum_temp_C", "torque_Nm"]
CELLS = ["", "nan", "NA", "x", "1_0", "inf", "-5", "1e9", "sideways", "uphill", " 7 ", "3.0e3", "-60", "0", "T1",
         '"7"', '"a,b"', "a\x0cb", "1,5", " ", "+0.5", ".5", "0x10"]
LOCATION = re.compile(r"^(.*?, (?:line|row) \d+(?:, column '[^']*')?)")


@st.composite
def logs(draw):
    rows = []
    for k in range(draw(st.integers(1, 3))):
        direction = draw(st.sampled_from(["downhill", "uphill"]))
        force = draw(st.sampled_from(["200", "250.5"]))
        pre = draw(st.integers(0, 2))           # rows logged before the lever (negative time)
        times = [-(pre - i) * 1.5 for i in range(pre)] + [i * 60.0 for i in range(draw(st.integers(3, 6)))]
        rows += [[f"T{k}", direction, force, f"{t:g}", f"{200 - t / 10:.2f}", f"{900 + t / 100:.2f}"]
                 for t in times]
    for row, col, cell in draw(st.lists(st.tuples(st.integers(0, len(rows) - 1), st.integers(0, 6),
                                                  st.sampled_from(CELLS)), max_size=2)):
        if col == 6:
            rows[row] = rows[row] + [cell]      # a ragged row
        elif col < len(rows[row]):
            rows[row][col] = cell
    if draw(st.booleans()) and len(rows) > 1:   # two rows swapped
        i = draw(st.integers(0, len(rows) - 2))
        rows[i], rows[i + 1] = rows[i + 1], rows[i]
    header = list(HEADER)
    if draw(st.booleans()):                      # a logged ambient, and a column the format does not use
        header += ["ambient_C", "operator"]
        rows = [r + [draw(st.sampled_from(["21.5", "22", "", "95"])), "bob"] for r in rows]
    return "\n".join(",".join(r) for r in [header] + rows) + "\n"


def _outcome(path: Path, small_bytes: int):
    with mock.patch.object(identify_common, "SMALL_CSV_BYTES", small_bytes), mock.patch("typer.echo"):
        try:
            d = identify_common.load_data(path, window_s=0)
        except UserError as exc:
            first = str(exc).splitlines()[0]
            m = LOCATION.match(first)
            return "error", m.group(1) if m else first
    return "ok", (list(d.test_id), list(d.direction), d.hand_force_N, d.time_s, d.drum_temp_C, d.torque_Nm,
                  d.notes)


@settings(max_examples=200, deadline=None)
@given(logs())
def test_strict_and_streaming_readers_give_the_same_rows_or_the_same_error(text):
    with tempfile.TemporaryDirectory() as tmp:
        f = Path(tmp) / "log.csv"
        f.write_text(text, encoding="utf-8")
        strict, streaming = _outcome(f, 1 << 30), _outcome(f, 0)
    assert strict[0] == streaming[0], (strict, streaming)
    if strict[0] == "error":
        assert strict[1] == streaming[1]
        return
    for a, b in zip(strict[1], streaming[1]):
        if isinstance(a, np.ndarray):
            assert np.array_equal(a, b)
        else:
            assert a == b


def test_rows_before_the_lever_are_not_used_by_either_reader_and_it_is_said(tmp_path):
    text = "\n".join([",".join(HEADER), "A,downhill,250,-2,201,5", "A,downhill,250,0,200,900",
                      "A,downhill,250,60,190,890", "A,downhill,250,120,180,880"]) + "\n"
    f = tmp_path / "pre.csv"
    f.write_text(text)
    for small in (1 << 30, 0):
        kind, rows = _outcome(f, small)
        assert kind == "ok" and list(rows[3]) == [0.0, 60.0, 120.0]
        assert any("1 rows logged before time 0" in n for n in rows[6])


@pytest.mark.parametrize("cell, value", [("", None), ("NA", None), ("1_000", "bad"), ("0x10", "bad"), (" 7 ", 7.0),
                                         ("1e3", 1000.0), ("-inf", -np.inf), ("2,5", "bad"), (" ", "bad"),
                                         (" NA", "bad"), (" nan", None)])
def test_cells_are_numbers_as_pyarrow_reads_them(cell, value):
    got = parse_number(cell)
    if value is None:
        assert np.isnan(got)
    elif value == "bad":
        assert got is None
    else:
        assert got == value
    assert parse_number("2,5", ",") == 2.5


def test_a_ragged_row_of_a_large_file_is_named_by_its_line(tmp_path, run_cli):
    rows = [",".join(HEADER)] + [f"A,downhill,250,{t},{200 - t / 1000:.3f},{900 + t / 1000:.3f}" for t in range(40000)]
    rows[30000] += ",1"
    f = tmp_path / "big.csv"
    f.write_text("\n".join(rows) + "\n")
    assert f.stat().st_size > identify_common.SMALL_CSV_BYTES
    code, out, err = run_cli("compare", f)
    assert code == 2 and "Traceback" not in err
    assert "big.csv, line 30001: 7 fields but the header has 6" in err.splitlines()[0]


VALID = "\n".join([",".join(HEADER)] + [f"{tid},{d},{f},{t},{200 - t / 20:.2f},{900 + t / 50:.2f}"
                                        for tid, d, f in (("A", "downhill", 250), ("B", "uphill", 340))
                                        for t in (0, 300, 600, 900)]) + "\n"
LINES = VALID.splitlines()
ODD = {   # name: (file text, "ok" or words of the error's first line)
    "bom": ("\ufeff" + VALID, "ok"),
    "bom and semicolons": ("\ufeff" + VALID.replace(",", ";"), "ok"),
    "crlf": (VALID.replace("\n", "\r\n"), "ok"),
    "spaces in the header": (VALID.replace(",", ", ", 5), "ok"),
    "blank line": ("\n".join(LINES[:3] + [""] + LINES[3:]) + "\n", "ok"),
    "multi-line quoted cell": ("\n".join([LINES[0] + ",note", LINES[1] + ',"a\nb"'] + [x + ",x" for x in LINES[2:]])
                               + "\n", "ok"),
    "trailing separators": ("\n".join(x + "," for x in LINES) + "\n", "ok"),
    "quoted numbers": ("\n".join([LINES[0]] + [",".join(f'"{c}"' for c in x.split(",")) for x in LINES[1:]]) + "\n",
                       "ok"),
    "duplicate header": ("\n".join([LINES[0] + ",torque_Nm"] + [x + ",1" for x in LINES[1:]]) + "\n",
                         "line 1, column 'torque_Nm': duplicate column"),
    "a whitespace-only line": (VALID + "   \n", "line 10: 1 fields but the header has 6"),
    "all-empty torque": ("\n".join([LINES[0]] + [x.rsplit(",", 1)[0] + "," for x in LINES[1:]]) + "\n",
                         "line 2, column 'torque_Nm': empty cell"),
    "excel sep line": ("sep=,\n" + VALID, "line 1: 'sep=' is a spreadsheet's separator hint"),
    "unit-only header": ("[-],[-],[N],[s],[degC],[Nm]\n" + "\n".join(LINES[1:]) + "\n", "units but no column names"),
    "capitalised direction": (VALID.replace("downhill", "Downhill"), "line 2, column 'direction': unknown direction"),
    "a huge number": (VALID.replace("900.00", "1e400", 1), "line 2, column 'torque_Nm': empty cell or not a finite"),
}


@pytest.mark.parametrize("name", list(ODD))
def test_odd_csvs_are_read_alike_by_both_readers(tmp_path, name):
    text, want = ODD[name]
    f = tmp_path / "odd.csv"
    f.write_bytes(text.encode("utf-8"))
    strict, streaming = _outcome(f, 1 << 30), _outcome(f, 0)
    assert strict[0] == streaming[0]
    if want == "ok":
        assert strict[0] == "ok", strict
        assert list(strict[1][3]) == list(streaming[1][3]) == [0.0, 300.0, 600.0, 900.0] * 2
    else:
        with mock.patch.object(identify_common, "SMALL_CSV_BYTES", 0), pytest.raises(UserError) as exc:
            identify_common.load_data(f, window_s=0)
        assert strict == streaming or strict[1].split(":")[0] == streaming[1].split(":")[0]
        assert want in str(exc.value).splitlines()[0], str(exc.value)


def test_a_test_logged_only_before_the_lever_says_so(tmp_path):
    f = tmp_path / "pre.csv"
    f.write_text(",".join(HEADER) + "\n" + "".join(f"A,downhill,250,{t},200,900\n" for t in (-3, -2, -1)))
    for small in (1 << 30, 0):
        kind, where = _outcome(f, small)
        assert kind == "error" and where.endswith("pre.csv, line 2, column 'test_id'")
    with pytest.raises(UserError, match=r"has 0 sample\(s\) from time 0 on \(3 before it, not used\)"):
        identify_common.load_data(f)
