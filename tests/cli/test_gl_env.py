"""MUJOCO_GL is read when MuJoCo is imported, so these run the CLI in a fresh process."""
import os
import subprocess
import sys
from pathlib import Path

SCENARIO = Path(__file__).resolve().parents[2] / "scenarios" / "fmvss135-uphill.toml"


def run(*args):
    env = {**os.environ, "MUJOCO_GL": "bogus"}
    return subprocess.run([sys.executable, "-m", "rollaway", *map(str, args)], capture_output=True, text=True,
                          env=env, timeout=120)


def test_bogus_mujoco_gl_does_not_matter_without_render():
    p = run("simulate", SCENARIO)
    assert p.returncode == 0, p.stderr
    assert "held" in p.stdout and "Traceback" not in p.stderr


def test_bogus_mujoco_gl_with_render_is_one_line_error(tmp_path):
    p = run("simulate", SCENARIO, "--render", tmp_path / "x.png")
    assert p.returncode == 2
    assert p.stderr.count("\n") == 1 and "MUJOCO_GL='bogus'" in p.stderr and "Traceback" not in p.stderr
