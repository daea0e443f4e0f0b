"""A plugin that ends, crashes or hangs the interpreter at import is an error line, not the end of the tool."""
import time
from pathlib import Path

import pytest

from rollaway.effects import load_effect_file
from rollaway.effects.preflight import preflight_import
from rollaway.errors import UserError

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "identify" / "ratchet_slip_effect.py"


def plugin(tmp_path, body: str) -> Path:
    path = tmp_path / "plugin.py"
    path.write_text(body)
    return path


@pytest.mark.parametrize("body, words", [
    ("import os\nos._exit(0)\n", "exit code 0"),
    ("import os\nos._exit(5)\n", "exit code 5"),
    ("import os, signal\nos.kill(os.getpid(), signal.SIGSEGV)\n", "signal SIGSEGV"),
    ("import os, signal\nos.kill(os.getpid(), signal.SIGKILL)\n", "signal SIGKILL"),
])
def test_an_abnormal_end_at_import_is_a_user_error(tmp_path, body, words):
    path = plugin(tmp_path, body)
    with pytest.raises(UserError, match=words) as err:
        load_effect_file(path)
    assert str(path) in str(err.value) and "\n" not in str(err.value)


def test_an_endless_import_runs_out_of_time(tmp_path):
    path = plugin(tmp_path, "while True:\n    pass\n")
    t = time.perf_counter()
    with pytest.raises(UserError, match="did not finish within 2 s"):
        preflight_import(path, timeout_s=2.0)
    assert time.perf_counter() - t < 10


def test_raised_errors_are_left_to_the_real_import_which_names_the_line(tmp_path):
    path = plugin(tmp_path, "x = 1\nraise ValueError('bad constant')\n")
    preflight_import(path)                                  # ended normally: nothing to say
    with pytest.raises(UserError, match=r"line 2: importing the effect file failed: ValueError: bad constant"):
        load_effect_file(path)
    path = plugin(tmp_path, "import sys\nsys.exit(3)\n")
    with pytest.raises(UserError, match=r"called sys.exit\(3\)"):
        load_effect_file(path)


def test_a_good_plugin_passes_and_registers(monkeypatch):
    import rollaway.effects as effects
    monkeypatch.setattr(effects, "_USER", {})               # leave the registry as the other tests expect it
    assert load_effect_file(EXAMPLE) == list(effects._USER)


def test_trusting_plugins_skips_the_child(tmp_path, monkeypatch):
    path = plugin(tmp_path, "import os\nos._exit(9)\n")
    monkeypatch.setenv("ROLLAWAY_TRUST_PLUGINS", "1")
    preflight_import(path)                                  # not run at all (running it here would end pytest)


def test_cli_reports_it_with_exit_2(tmp_path, run_cli):
    path = plugin(tmp_path, "import os\nos._exit(0)\n")
    data = Path(__file__).resolve().parents[2] / "examples" / "identify" / "bench-hidden-effect.csv"
    code, out, err = run_cli("diagnose", data, "--effect-file", path)
    assert code == 2 and "exit code 0" in err and "Traceback" not in err
