"""Property tests of the loaders and CLI values: any input is accepted or a UserError (exit 2),
never a traceback, never NaN printed."""
import math
import re

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rollaway.errors import UserError, read_toml
from rollaway.bench.measurements import load_measurements
from rollaway.model.parameters import SPEC_BY_NAME, SPECS, parameters_from_mapping
from rollaway.hold.scenario import scenario_from_mapping
from rollaway.sweep.spec import MAX_POINTS, spec_from_mapping
from rollaway.sweep.store import JOURNAL, Journal

SETTINGS = settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
NAN = re.compile(r"\b-?nan\b", re.IGNORECASE)

numbers = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-10**30, 10**30),
                    st.sampled_from([0, -0.0, 5e-324, 1e308, -1e308, 400, 20, 0.4]))
values = st.one_of(numbers, st.booleans(), st.text(max_size=12), st.lists(numbers, max_size=3),
                   st.dictionaries(st.text(max_size=5), numbers, max_size=2))
SCENARIO_KEYS = ["name", "description", "grade_pct", "direction", "occupants", "hand_force_N", "duration_s",
                 "initial_drum_temp_C", "mu_drum", "tyre_road_mu", "params", "regulation", "parameters", "bogus"]
GOOD = {"name": "x", "grade_pct": 20, "direction": "uphill", "occupants": 1, "hand_force_N": 400, "duration_s": 300}


def _user_error_or(fn, *args, **kw):
    try:
        return fn(*args, **kw)
    except UserError as exc:
        msg = str(exc)
        assert msg and "Traceback" not in msg
        return None


@SETTINGS
@given(st.dictionaries(st.sampled_from(SCENARIO_KEYS), values, max_size=6))
def test_scenario_mapping_is_valid_or_a_user_error(changes):
    s = _user_error_or(scenario_from_mapping, {**GOOD, **changes}, where="f.toml")
    if s is not None:
        for v in (s.grade_pct, s.hand_force_N, s.duration_s, *s.params.as_dict().values()):
            assert math.isfinite(v)


@SETTINGS
@given(st.dictionaries(st.sampled_from([s.name for s in SPECS] + ["extends", "nope"]), values, max_size=5))
def test_parameter_mapping_is_in_range_or_a_user_error(data):
    p = _user_error_or(parameters_from_mapping, {"extends": "paper", **data}, where="p.toml")
    if p is not None:
        for k, v in p.as_dict().items():
            assert SPEC_BY_NAME[k].lower <= v <= SPEC_BY_NAME[k].upper
        assert 0 < p.cooling_time_constant_s < math.inf


ranges = st.fixed_dictionaries({"start": numbers, "stop": numbers},
                                optional={"num": st.one_of(st.integers(-3, 60), numbers), "step": numbers,
                                          "junk": numbers})


@SETTINGS
@given(st.dictionaries(st.sampled_from(["grade_pct", "hand_force_N", "occupants", "mu_drum", "direction"]),
                       st.one_of(ranges, st.lists(values, max_size=3), values), max_size=3),
       st.sampled_from(["band", "all", "none", 3]))
def test_sweep_spec_is_bounded_or_a_user_error(tmp_path, grid, mode):
    spec = _user_error_or(spec_from_mapping, {"base_preset": "fmvss135", "simulate": mode, "grid": grid},
                          "s.toml", tmp_path)
    if spec is not None:
        assert 0 < len(spec.points) <= MAX_POINTS and spec.points["point_id"].is_unique


@SETTINGS
@given(st.binary(max_size=300))
def test_any_toml_bytes_parse_or_give_a_user_error(tmp_path, blob):
    f = tmp_path / "x.toml"
    f.write_bytes(blob)
    _user_error_or(read_toml, f, "scenario file", "see scenarios/")


HEADER = "test_id,direction,hand_force_N,time_s,drum_temp_C,torque_Nm\n"
cells = st.one_of(st.sampled_from(["A", "downhill", "uphill", "0", "300", "200", "nan", "inf", "", '"', "1e999"]),
                  st.text(max_size=6), numbers.map(str))


@SETTINGS
@given(st.lists(st.lists(cells, min_size=0, max_size=7), max_size=6), st.booleans(), st.binary(max_size=20))
def test_any_bench_csv_loads_or_gives_a_user_error(tmp_path, rows, header, junk):
    f = tmp_path / "d.csv"
    text = (HEADER if header else "") + "".join(",".join(r) + "\n" for r in rows)
    f.write_bytes(text.encode("utf-8") + junk)
    m = _user_error_or(load_measurements, f)
    if m is not None:
        assert all(math.isfinite(v) for v in m.torque_Nm)


@SETTINGS
@given(st.lists(st.one_of(st.binary(max_size=40),
                          st.sampled_from([b'{"point_id": "a", "error": ""}', b'{"point_id": 3}', b"null"])),
                max_size=8))
def test_any_journal_bytes_load(tmp_path, lines):
    (tmp_path / JOURNAL).write_bytes(b"\n".join(lines))
    recs = Journal(tmp_path).load()
    assert all(isinstance(k, str) and isinstance(r, dict) for k, r in recs.items())
    Journal(tmp_path).load()                 # the rewritten journal loads again


cli_numbers = st.one_of(st.floats(allow_nan=True, allow_infinity=True, width=64),
                        st.sampled_from([0.0, -5.0, 1e308, 5e-324, 3600.0, 20.0, 400.0])).map(repr)


@SETTINGS
@given(cli_numbers, cli_numbers, cli_numbers, st.integers(-3, 9), st.one_of(st.none(), cli_numbers),
       st.one_of(st.none(), cli_numbers))
def test_hold_cli_values(run_cli, grade, force, duration, occupants, mu, tyre):
    args = ["hold", "--grade-pct", grade, "--hand-force-N", force, "--duration-s", duration, "--occupants",
            occupants, "--dt-s", "3600", "--format", "csv"]
    args += ["--mu", mu] if mu else []
    args += ["--tyre-mu", tyre] if tyre else []
    code, out, err = run_cli(*args)
    assert code in (0, 1, 2), (code, err)        # 1: the car rolls away (a verdict, not an error)
    assert "Traceback" not in out + err
    assert not NAN.search(out), out
    if code == 2:
        assert err.startswith("rollaway hold: error: ") and err.count("\n") == 1, err


@SETTINGS
@given(cli_numbers, cli_numbers, st.one_of(st.none(), cli_numbers), st.one_of(st.none(), cli_numbers))
def test_brake_cli_values(run_cli, force, t_end, gap, t0):
    args = ["brake", "--hand-force-N", force, "--t-end-s", t_end, "--dt-s", "3600", "--format", "csv"]
    args += ["--gap-mm", gap] if gap else []
    args += ["--t0-C", t0] if t0 else []
    code, out, err = run_cli(*args)
    assert code in (0, 2), (code, err)
    assert "Traceback" not in out + err
    assert not NAN.search(out), out
