"""Column map and units: the units labs log in, header brackets, the map's two spellings, and its mistakes."""
import pytest
from hypothesis import given, strategies as st

from rollaway.errors import UserError
from rollaway.bench.columns import ColumnMap, column_map, conversion, parse_table, split_header


@pytest.mark.parametrize("unit, quantity, x, si", [
    ("N·m", "torque_Nm", 100.0, 100.0), ("Nm", "torque_Nm", 100.0, 100.0), ("lbf·ft", "torque_Nm", 100.0, 135.58179),
    ("lbf ft", "torque_Nm", 1.0, 1.3558179), ("kN·m", "torque_Nm", 0.5, 500.0), ("kNm", "torque_Nm", 0.5, 500.0),
    ("°C", "drum_temp_C", 200.0, 200.0), ("°F", "drum_temp_C", 392.0, 200.0), ("degF", "drum_temp_C", 32.0, 0.0),
    ("K", "drum_temp_C", 473.15, 200.0), ("s", "time_s", 3.0, 3.0), ("ms", "time_s", 1500.0, 1.5),
    ("min", "time_s", 2.0, 120.0), ("N", "hand_force_N", 250.0, 250.0), ("lbf", "hand_force_N", 10.0, 44.482216),
    ("kgf", "hand_force_N", 10.0, 98.0665), ("°F", "ambient_C", 77.0, 25.0),
])
def test_lab_units_convert_to_si(unit, quantity, x, si):
    a, b = conversion(unit, quantity)
    assert a * x + b == pytest.approx(si, rel=1e-6, abs=1e-9)


@pytest.mark.parametrize("unit, quantity, words", [
    ("furlong-ish", "torque_Nm", "unknown unit"), ("degF", "torque_Nm", "not a unit of torque"),
    ("N·m", "time_s", "not a unit of time"), ("ms", "drum_temp_C", "not a unit of temperature"),
])
def test_bad_units_say_why(unit, quantity, words):
    with pytest.raises(ValueError, match=words):
        conversion(unit, quantity)


@given(st.text(alphabet=st.characters(whitelist_categories=("L", "N"), whitelist_characters="_ -"), min_size=1,
               max_size=12).map(str.strip).filter(bool),
       st.sampled_from(["Nm", "°F", "ms", "lbf·ft", "kN·m", "K"]))
def test_split_header_reads_the_bracketed_unit(name, unit):
    assert split_header(f"{name} [{unit}]") == (name, unit)
    assert split_header(name) == (name, None)


def test_map_resolves_names_and_units_from_header_and_map():
    m = column_map(["drum_temp_C=T_drum[degF]", "time_s=Time", "torque_Nm=Torque [Nm]"])
    header = ["Time [ms]", "Torque [Nm]", "T_drum", "Comment"]
    t = m.resolve(header, "time_s", "f.csv")
    assert (t.header, t.scale) == ("Time [ms]", pytest.approx(1e-3))
    assert m.resolve(header, "torque_Nm", "f.csv").scale == 1.0
    temp = m.resolve(header, "drum_temp_C", "f.csv")
    assert temp.header == "T_drum" and temp.scale * 212 + temp.offset == pytest.approx(100.0)
    assert m.resolve(header, "hand_force_N", "f.csv") is None          # not mapped, not there


def test_toml_table_spellings(tmp_path):
    f = tmp_path / "lab.toml"
    f.write_text('[columns]\ntorque_Nm = "Torque [Nm]"\ndrum_temp_C = { column = "T_drum", unit = "degF" }\n',
                 encoding="utf-8")
    m = column_map([f])
    assert m.specs["torque_Nm"].column == "Torque [Nm]" and m.specs["drum_temp_C"].unit == "degF"


@pytest.mark.parametrize("table, words", [
    ({"torque": "Torque"}, ["unknown quantity 'torque'", "torque_Nm"]),
    ({"torque_Nm": {"column": "Torque", "unit": "parsec"}}, ["torque_Nm", "parsec", "N·m, lbf·ft"]),
    ({"torque_Nm": {"col": "Torque"}}, ["torque_Nm", "column"]),
    ({"torque_Nm": 3}, ["torque_Nm", "column name"]),
])
def test_bad_map_entries_name_the_key_and_the_fix(table, words):
    with pytest.raises(UserError) as e:
        parse_table(table, "lab.toml")
    for w in words:
        assert w in str(e.value), (w, str(e.value))


def test_absent_mapped_column_names_file_column_and_fix():
    with pytest.raises(UserError) as e:
        column_map(["torque_Nm=Torq"]).resolve(["Time", "Torque [Nm]"], "torque_Nm", "bench/D200.csv, line 1")
    msg = str(e.value)
    assert "bench/D200.csv" in msg and "'Torq'" in msg and "did you mean 'Torque'" in msg and "--columns" in msg
    assert "\n" not in msg


def test_unknown_unit_in_header_names_the_column():
    with pytest.raises(UserError) as e:
        ColumnMap().resolve(["torque_Nm [flurbs]"], "torque_Nm", "x.csv")
    assert "x.csv, column 'torque_Nm [flurbs]'" in str(e.value) and "unknown unit 'flurbs'" in str(e.value)


def test_a_map_unit_disagreeing_with_the_header_is_an_error_unless_stated():
    header = ["T_drum [degC]", "Time"]
    with pytest.raises(UserError) as exc:
        column_map(["drum_temp_C=T_drum[degF]"]).resolve(header, "drum_temp_C", "f.csv, line 1")
    msg = str(exc.value)
    assert "f.csv, line 1, column 'T_drum [degC]'" in msg and "header says °C" in msg and "says °F" in msg
    assert "drum_temp_C=T_drum[degF]!" in msg
    r = column_map(["drum_temp_C=T_drum[degF]!"]).resolve(header, "drum_temp_C", "f.csv, line 1")
    assert r.scale * 212 + r.offset == pytest.approx(100.0) and "override" in r.note and "°F" in r.note
    same = column_map(["drum_temp_C=T_drum[°C]"]).resolve(header, "drum_temp_C", "f.csv")   # one unit, two spellings
    assert (same.scale, same.offset, same.note) == (1.0, 0.0, "")


def test_toml_override_units_and_its_mistakes(tmp_path):
    f = tmp_path / "lab.toml"
    f.write_text('[columns]\ndrum_temp_C = { column = "T_drum", unit = "degF", override_units = true }\n'
                 'torque_Nm = "Torque [lbf*ft]!"\n', encoding="utf-8")
    m = column_map([f])
    assert m.specs["drum_temp_C"].override and m.specs["torque_Nm"].override
    assert m.resolve(["Torque [Nm]"], "torque_Nm", "x").note
    with pytest.raises(UserError, match="override_units must be true or false"):
        parse_table({"drum_temp_C": {"column": "T", "override_units": "yes"}}, "lab.toml")
    with pytest.raises(UserError, match="no unit is given"):
        column_map(["drum_temp_C=T_drum!"])


def test_a_stated_override_is_noted_on_stderr_and_in_the_json(tmp_path, run_cli):
    import json
    from rollaway.identify.synth import synth
    f = tmp_path / "log.csv"
    frame = synth([], seed=2).to_frame().rename(columns={"drum_temp_C": "T_drum [degC]"})
    frame.to_csv(f, index=False)
    code, out, err = run_cli("compare", f, "--columns", "drum_temp_C=T_drum[degC]", "--format", "json")
    assert code == 0 and "override" not in err
    frame["T_drum [degC]"] = frame["T_drum [degC]"] * 1.8 + 32       # the values are °F, the header is wrong
    frame.to_csv(f, index=False)
    code, out, err = run_cli("compare", f, "--columns", "drum_temp_C=T_drum[degF]!", "--format", "json")
    assert code == 0, err
    note = "drum_temp_C: column 'T_drum [degC]' read in °F"
    assert f"note: {note}" in err and any(note in n for n in json.loads(out)["data"]["notes"])


def test_one_column_mapped_to_two_quantities_is_an_error(tmp_path, run_cli):
    from rollaway.identify.synth import synth
    f = tmp_path / "log.csv"
    synth([], seed=2).to_csv(f)
    code, _, err = run_cli("compare", f, "--columns", "torque_Nm=drum_temp_C")
    assert code == 2 and "column 'drum_temp_C': read as both drum_temp_C and torque_Nm" in err
    assert "torque_Nm mapped to it by --columns" in err and len(err.strip().splitlines()) == 1
