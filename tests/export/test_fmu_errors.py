"""What cannot be exported is a one-line error with exit 2, before any compiler or FMPy is needed."""
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "identify"


def one_line_error(run_cli, *args):
    code, _, err = run_cli(*args)
    assert code == 2 and "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    return err


def test_a_plugin_effect_cannot_be_exported(run_cli, tmp_path):
    plugin = tmp_path / "ratchet_slip_effect.py"
    plugin.write_text((EXAMPLES / "ratchet_slip_effect.py").read_text())
    model = tmp_path / "with-plugin.toml"
    model.write_text('extends = "paper"\n\n[effects.ratchet_slip]\nplugin = "ratchet_slip_effect.py"\nslip_m = 5e-6\n')
    err = one_line_error(run_cli, "export-fmu", "--params", model, tmp_path / "x.fmu")
    assert "ratchet_slip" in err and "ratchet_slip_effect.py" in err and "plugin" in err
    assert not (tmp_path / "x.fmu").exists()


def test_a_shape_free_form_cannot_be_exported(run_cli, tmp_path):
    model = tmp_path / "shape.toml"
    model.write_text('extends = "paper"\n\n[effects.lining_creep_shape]\nknots = [0.0, 300.0, 3600.0]\nc0 = -0.05\n')
    err = one_line_error(run_cli, "export-fmu", "--params", model, tmp_path / "x.fmu")
    assert "lining_creep_shape" in err and "shape-free form of lining_creep" in err
    assert not (tmp_path / "x.fmu").exists()


def test_without_gcc_a_one_line_error(run_cli, tmp_path, monkeypatch):
    monkeypatch.setenv("PATH", str(tmp_path))
    err = one_line_error(run_cli, "export-fmu", tmp_path / "x.fmu")
    assert "gcc" in err and "install" in err


@pytest.mark.parametrize("args, words", [
    (["x.zip"], [".fmu"]),
    (["--params", "paper", "--stop-time-s", "0", "x.fmu"], ["--stop-time-s"]),
    (["--fmi-version", "1.0", "x.fmu"], ["FMI version", "2.0", "3.0"]),
])
def test_bad_arguments(run_cli, tmp_path, args, words):
    err = one_line_error(run_cli, "export-fmu", *[str(tmp_path / a) if a.startswith("x.") else a for a in args])
    for w in words:
        assert w in err


def test_a_self_locking_model_is_refused(run_cli, tmp_path):
    model = tmp_path / "locks.toml"
    model.write_text('extends = "paper"\nmu_drum = 1.3\n')
    err = one_line_error(run_cli, "export-fmu", "--params", model, tmp_path / "x.fmu")
    assert "self-locks" in err and "mu_drum" in err
