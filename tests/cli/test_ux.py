"""What a new user sees: --version, fast --help, JSON decisions, messages naming the right file kind."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCEN = ROOT / "scenarios"


def test_version(run_cli):
    from rollaway import __version__
    code, out, _ = run_cli("--version")
    assert code == 0 and out.strip() == f"rollaway {__version__}"


def test_help_imports_no_command_module():
    code = ("import sys; from rollaway.cli import main; main(['--help']); "
            "print(sorted(m for m in sys.modules if m.split('.')[0] in ('numpy', 'pandas', 'mujoco', 'matplotlib')"
            " or m.startswith('rollaway.cli.') and m not in ('rollaway.cli.app',)))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip().splitlines()[-1] == "[]"


def test_command_summaries_match_the_commands():
    from rollaway.cli.app import COMMANDS, load_command
    for name in COMMANDS:
        assert load_command(name).name == name


def test_simulate_json_has_the_decision(run_cli):
    code, out, err = run_cli("simulate", SCEN / "tyre-skid.toml", "--format", "json")
    assert code == 0, err
    d = json.loads(out)
    assert d["holds"] is False and d["outcome"] == "tyre_skid" and d["verdict"].startswith("ROLLS AWAY")


def test_simulate_text_ends_with_verdict(run_cli):
    code, out, _ = run_cli("simulate", SCEN / "fmvss135-uphill.toml")
    assert code == 0 and out.strip().splitlines()[-1] == "verdict: HOLDS"


@pytest.mark.parametrize("args, words", [
    (["simulate", SCEN / "sweeps" / "grade-load.toml"], ["sweep file", "rollaway sweep"]),
    (["sweep", SCEN / "tyre-skid.toml"], ["scenario file", "rollaway simulate"]),
    (["check", "--analytic", SCEN / "tyre-skid.toml"], ["scenario file", "no --analytic", "rollaway hold"]),
    (["check", SCEN / "sweeps" / "cases.toml"], ["sweep file", "rollaway sweep"]),
    (["compare", SCEN], ["is a folder", "CSV"]),
    (["simulate", SCEN / "tyre-skid.toml", "--size", "big"], ["--size", "640x480"]),
    (["simulate", SCEN / "tyre-skid.toml", "--fps", "0"], ["--fps"]),
    (["simulate", SCEN / "tyre-skid.toml", "--format", "xml"], ["xml"]),
    (["hold", "--grade-pct", "20", "--hand-force-N", "300", "--uncertainty", "10", "--seed", "-1"], ["--seed"]),
    (["synth", "--seed", "-5"], ["--seed"]),
    (["synth", "--t0-C", "5000"], ["--t0-C 5000", "[-60, 1000]"]),
    (["synth", "--dt-s", "1e-9"], ["--dt-s", "rows"]),
])
def test_wrong_input_names_the_kind_and_the_command(run_cli, args, words):
    code, out, err = run_cli(*args)
    assert code == 2 and "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    for w in words:
        assert w in err, (w, err)


def test_non_numeric_parameter(run_cli, tmp_path):
    f = tmp_path / "p.toml"
    f.write_text('extends = "paper"\nmu_drum = "abc"\n')
    code, _, err = run_cli("params", f)
    assert code == 2 and "mu_drum" in err and "without quotes" in err and "in –" not in err


def test_params_json_booleans(run_cli):
    rows = json.loads(run_cli("params", "--format", "json")[1])
    assert {type(r["assumed"]) for r in rows} == {bool}
    assert any(r["assumed"] for r in rows) and not all(r["assumed"] for r in rows)


def test_check_table_fits_a_terminal(run_cli):
    code, out, _ = run_cli("check", "fmvss135")
    table = [line for line in out.splitlines() if not line.startswith("  fmvss135:")]
    assert code == 0 and max(len(line) for line in table) <= 100


def test_the_console_script_ends_with_the_commands_code_its_output_whole_and_exit_handlers_run(tmp_path):
    """:func:`rollaway.cli.run` skips the interpreter's teardown: the exit code, every line written and the
    ``atexit`` handlers (pools, temporary folders) are kept."""
    marker = tmp_path / "atexit.txt"
    code = ("import atexit, sys; from pathlib import Path; "
            f"atexit.register(lambda: Path({str(marker)!r}).write_text('ran')); "
            "sys.argv = ['rollaway'] + sys.argv[1:]; from rollaway.cli import run; run()")
    ok = subprocess.run([sys.executable, "-c", code, "hold", "--grade-pct", "20", "--hand-force-N", "400"],
                        capture_output=True, text=True)
    assert ok.returncode == 0, ok.stderr
    assert ok.stdout.strip() and "verdict" in ok.stdout.lower() and marker.read_text() == "ran"
    marker.unlink()
    bad = subprocess.run([sys.executable, "-c", code, "hold", "--grade-pct", "20", "--hand-force-N", "-5"],
                         capture_output=True, text=True)
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1 and "Traceback" not in bad.stderr
    assert marker.read_text() == "ran"
