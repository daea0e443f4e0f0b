"""Time axes in another unit than seconds from the lever: refused with the unit they look like and how to say it."""
import pytest

from rollaway.bench.sources import read_log
from rollaway.bench.columns import column_map
from rollaway.bench.time_axis import epoch_hint, long_test_message
from rollaway.errors import UserError
from rollaway.identify.synth import synth


@pytest.fixture(scope="module")
def frame():
    return synth([], seed=4, dt_s=60.0, duration_s=3600.0, hand_forces_N=(250.0,)).to_frame()


@pytest.mark.parametrize("scale, unit", [(1e3, "ms"), (1e6, "us")])
def test_a_time_in_ms_or_us_without_a_unit_says_which_it_looks_like(tmp_path, frame, run_cli, scale, unit):
    f = tmp_path / "log.csv"
    frame.assign(time_s=frame.time_s * scale).to_csv(f, index=False)
    for small in (True, False):          # the strict and the streaming reader say the same
        code, out, err = run_cli("compare", f, *([] if small else ["--columns", "time_s=time_s"]))
        assert code == 2 and "Traceback" not in err and len(err.strip().splitlines()) == 1, err
        assert f"looks like {unit}" in err and f"--columns 'time_s=time_s[{unit}]'" in err and "log.csv, line" in err
    code, _, err = run_cli("compare", f, "--columns", f"time_s=time_s[{unit}]")
    assert code == 0, err


def test_a_unit_stated_as_seconds_is_taken_as_stated(tmp_path, frame, run_cli):
    f = tmp_path / "log.csv"
    frame.assign(time_s=frame.time_s * 100).to_csv(f, index=False)       # 100 h: longer than any bench test
    with pytest.raises(UserError, match="looks like ms"):
        read_log(f, window_s=0)
    d = read_log(f, column_map(["time_s=time_s[s]"]), window_s=0)
    assert d.time_s.max() == pytest.approx(360000.0)
    code, _, err = run_cli("compare", f, "--columns", "time_s=time_s[s]")
    assert code == 0 and "Traceback" not in err, err


@pytest.mark.parametrize("offset, words", [(1.7e9, "Unix time stamp in s (2023-"), (1.7e12, "Unix time stamp in ms")])
def test_an_epoch_time_axis_is_named(tmp_path, frame, run_cli, offset, words):
    f = tmp_path / "log.csv"
    frame.assign(time_s=frame.time_s * (1e3 if offset > 1e10 else 1) + offset).to_csv(f, index=False)
    code, _, err = run_cli("compare", f)
    assert code == 2 and words in err and "log.csv, line 2, column 'time_s'" in err and "starts at 0" in err


def test_the_hints_leave_plausible_times_alone():
    assert epoch_hint(3600.0) is None and epoch_hint(-30.0) is None
    assert long_test_message("f", "'time_s'", "time_s", "A", 8 * 3600.0) is None
    assert "looks like ns" in long_test_message("f", "'time_s'", "time_s", "A", 3.6e12)
