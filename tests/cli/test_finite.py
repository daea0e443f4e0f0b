"""Every float option of every command refuses nan and inf: one line naming the option, exit 2."""
import pytest

from rollaway.cli.app import COMMANDS, load_command
from rollaway.cli.finite import Finite

FLOAT_OPTIONS = [(name, max(p.opts, key=len)) for name in COMMANDS for p in load_command(name).params
                 if isinstance(p.type, Finite)]


def test_every_float_option_is_finite_checked():
    from typer._click.types import FloatParamType
    for name in COMMANDS:
        for p in load_command(name).params:
            assert not isinstance(p.type, FloatParamType), (name, p.opts)
    assert ("compare", "--window-s") in FLOAT_OPTIONS and ("hold", "--grade-pct") in FLOAT_OPTIONS
    assert len(FLOAT_OPTIONS) >= 25


@pytest.mark.parametrize("command, flag", FLOAT_OPTIONS)
@pytest.mark.parametrize("value", ["nan", "inf", "-inf", "1e400"])
def test_non_finite_values_are_refused(run_cli, command, flag, value):
    code, out, err = run_cli(command, flag, value)
    assert code == 2 and "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    assert f"{flag} {value}: not a finite number" in err


def test_finite_values_still_pass_and_ranges_still_apply(run_cli):
    code, out, err = run_cli("hold", "--grade-pct", "20", "--hand-force-N", "300")
    assert code == 0, err
    code, _, err = run_cli("diagnose", "x.csv", "--noise-torque-Nm", "-1")
    assert code == 2 and "--noise-torque-Nm" in err
