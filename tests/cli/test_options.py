"""An option a mode does not use is an error naming the mode that uses it, never silently ignored."""
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCEN = ROOT / "scenarios" / "fmvss135-uphill.toml"
BENCH = ROOT / "tests" / "corpus" / "bench" / "ok-valid.csv"


@pytest.mark.parametrize("args, words", [
    (["check", "fmvss135", "--uncertainty", "50"], "--uncertainty is used only with --analytic"),
    (["check", SCEN, "--params", "paper"], "--params sets the drum model of the regulation presets"),
    (["hold", "--grade-pct", "20", "--hand-force-N", "300", "--seed", "3"], "--seed is used only with --uncertainty"),
    (["simulate", SCEN, "--percentile", "50"], "--percentile is used only with --uncertainty"),
    (["simulate", SCEN, "--fps", "10", "--after-s", "3"], "--fps, --after-s are used only with --render"),
    (["simulate", SCEN, "--multisample", "4"], "--multisample is used only with --render"),
    (["compare", BENCH, "--effect-file", "x.py"], "--effect-file is used only with --effect"),
    (["synth", "--effect-file", "x.py"], "--effect-file is used only with --effect"),
    (["sweep", "x.toml", "--simulate", "none", "--workers", "2"], "--workers is used only with --simulate band or all"),
    (["chart", "--uncertainty", "20"], "--uncertainty 20 shades the band of calibrated models"),
    (["diagnose", BENCH, "--noise-torque-Nm", "0"], "--noise-torque-Nm 0: the instrument's noise σ must be > 0"),
])
def test_an_option_without_its_mode_is_an_error(run_cli, args, words):
    code, out, err = run_cli(*args)
    assert code == 2 and "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    assert words in err


def test_the_options_with_their_mode_still_work(run_cli, tmp_path):
    code, out, err = run_cli("hold", "--grade-pct", "20", "--hand-force-N", "300", "--seed", "3", "--params",
                             ROOT / "tests" / "corpus" / "params" / "ok-covariance-zero-rows.toml",
                             "--uncertainty", "20")
    assert code in (0, 1), err
    code, out, err = run_cli("check", "fmvss135", "--params", "paper", "--analytic")
    assert code in (0, 1), err
