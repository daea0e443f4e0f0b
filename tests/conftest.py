import os
from pathlib import Path

import pytest

os.environ.setdefault("MUJOCO_GL", "egl")
DATA = Path(__file__).parent / "data"
ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(autouse=True)
def _effect_registry():
    """Each test leaves the user-effect registry as it found it: an effect a test registers (a plugin file,
    ``register_effect``) would otherwise join every later ``diagnose``'s candidates in this process and change its
    answer (a plugin of tests/model/test_model_file.py turned a band campaign's mixture weights 0.89 → 0.45)."""
    from rollaway import effects
    before = dict(effects._USER)
    yield
    effects._USER.clear()
    effects._USER.update(before)


@pytest.fixture
def run_cli(capsys):
    """Run the CLI in-process; return (exit code, stdout, stderr)."""
    from rollaway.cli import main

    def _run(*args):
        code = main([str(a) for a in args])
        out = capsys.readouterr()
        return code, out.out, out.err
    return _run
