"""The malformed effect-plugin files of the corpus, written from one template at test time.

Each case is a stand-alone user file that differs from a good plugin (``ok-effect.py``) in one
place; keeping them here as sources (not as 27 committed near-copies) keeps the template the
one place to change.  :func:`write_plugins` writes them into a folder under their file names,
so the messages under test name the file as a user would see it.
"""
from pathlib import Path

CASES = []


def case(name, content, expect, needles=(), effect=None):
    CASES.append({"file": f"plugin/{name}", "content": content, "expect": expect, "needles": list(needles),
                  "effect": effect, "note": ""})


def write_plugins(folder: Path) -> Path:
    """Write every plugin case into *folder* (created); return it."""
    folder.mkdir(parents=True, exist_ok=True)
    for c in CASES:
        data = c["content"] if isinstance(c["content"], bytes) else c["content"].encode("utf-8")
        (folder / Path(c["file"]).name).write_bytes(data)
    return folder


GOOD = '''import numpy as np
from rollaway.effects.base import Effect, EffectParameter


class Humidity(Effect):
    name = "humidity"
    summary = "moisture raises the lining friction while the drum is cold"
    physics = "mu = mu_d (1 + a exp(-(T_l - T_amb)/30 K))"
    signature = "torque residual at the cold end"
    reference = "corpus"
    parameters = (EffectParameter("a", "-", neutral=0.0, lower=0.0, upper=1.0, initial=0.05),)

    def friction(self, state, mu, v):
        return HOOK
'''
OKHOOK = 'mu * (1 + v["a"] * np.exp(-(state.lining_temp_C - state.ambient_C) / 30.0))'
def plug(**kw):
    hook = kw.pop("hook", OKHOOK)
    src = GOOD
    for k, v in kw.items():
        assert k in src, k
        src = src.replace(k, v)
    return src.replace("HOOK", hook)
case("ok-effect.py", plug(), "accept", effect="humidity")
case("exit-0.py", "import sys\nsys.exit(0)\n", "error", ["exit-0.py", "sys.exit(0)"], effect="humidity")
case("exit-3.py", plug() + "\nimport sys\nsys.exit(3)\n", "error", ["exit-3.py", "sys.exit(3)"], effect="humidity")
case("exit-string.py", "raise SystemExit('bye')\n", "error", ["exit-string.py"], effect="humidity")
case("base-exception.py", "class Boom(BaseException):\n    pass\n\n\nraise Boom('kaboom')\n", "error",
    ["base-exception.py", "line 5", "Boom"], effect="humidity")
case("generator-exit.py", "raise GeneratorExit\n", "error", ["generator-exit.py"], effect="humidity")
case("value-error.py", "x = 1\nraise ValueError('no')\n", "error", ["value-error.py", "line 2"], effect="humidity")
case("import-missing.py", "import numpyy\n", "error", ["import-missing.py", "numpyy"], effect="humidity")
case("syntax.py", "def f(:\n    pass\n", "error", ["syntax.py", "line 1"], effect="humidity")
case("name-int.py", plug(**{'name = "humidity"': "name = 42"}), "error", ["name-int.py", "'name'"], effect="humidity")
case("name-none.py", plug(**{'name = "humidity"': "name = None"}), "error", ["name-none.py", "'name'"],
    effect="humidity")
case("name-not-identifier.py", plug(**{'name = "humidity"': 'name = "hum idity"'}), "error",
    ["name-not-identifier.py", "'name'"], effect="hum idity")
case("name-taken.py", plug(**{'name = "humidity"': 'name = "friction_temperature"'}), "error",
    ["name-taken.py", "friction_temperature"], effect="friction_temperature")
case("no-parameters.py", plug(**{'parameters = (EffectParameter("a", "-", neutral=0.0, lower=0.0, upper=1.0, initial=0.05),)': "parameters = ()"}),
    "error", ["no-parameters.py", "humidity"], effect="humidity")
case("parameters-garbage.py", plug(**{'parameters = (EffectParameter("a", "-", neutral=0.0, lower=0.0, upper=1.0, initial=0.05),)': 'parameters = ("a",)'}),
    "error", ["parameters-garbage.py", "humidity"], effect="humidity")
case("parameter-bounds.py", plug(**{"upper=1.0": "upper=-1.0"}), "error", ["parameter-bounds.py"], effect="humidity")
case("parameter-nan-bounds.py", plug(**{"upper=1.0": "upper=float('nan')"}), "error",
    ["parameter-nan-bounds.py"], effect="humidity")
case("hook-not-callable.py", plug(**{"    def friction(self, state, mu, v):\n        return HOOK\n": "    friction = 3\n"}),
    "error", ["hook-not-callable.py", "'friction'"], effect="humidity")
case("no-effect-class.py", "X = 1\n", "error", ["no-effect-class.py", "Effect"], effect="humidity")
case("two-same-name.py", plug() + "\n\nclass Humidity2(Humidity):\n    pass\n", "error",
    ["two-same-name.py", "'humidity'"], effect="humidity")
case("not-utf8.py", b"# \xff\xfe\nX = 1\n", "error", ["not-utf8.py"], effect="humidity")
case("hook-nan.py", plug(hook="mu * np.nan"), "error", ["hook-nan.py", "humidity"], effect="humidity")
case("hook-inf.py", plug(hook="mu * np.inf"), "error", ["hook-inf.py", "humidity"], effect="humidity")
case("hook-shape.py", plug(hook="np.ones(3)"), "error", ["hook-shape.py", "humidity"], effect="humidity")
case("hook-raises.py", plug(hook="1 / 0"), "error", ["hook-raises.py", "humidity"], effect="humidity")
case("hook-exits.py", plug(hook="__import__('sys').exit(0)"), "error", ["hook-exits.py", "humidity"],
    effect="humidity")
case("hook-string.py", plug(hook="'fast'"), "error", ["hook-string.py", "humidity"], effect="humidity")
case("os-exit-0.py", "import os\nos._exit(0)\n", "error", ["os-exit-0.py", "exit code 0"], effect="humidity")
case("os-exit-plugin.py", plug() + "\nimport os\nos._exit(4)\n", "error", ["os-exit-plugin.py", "exit code 4"],
     effect="humidity")
case("segfault.py", "import os, signal\nos.kill(os.getpid(), signal.SIGSEGV)\n", "error", ["segfault.py", "SIGSEGV"],
     effect="humidity")
case("amplitude-unknown.py", plug(**{'    def friction': '    amplitude = "b"\n\n    def friction'}), "error",
     ["amplitude-unknown.py", "amplitude"], effect="humidity")
case("shape-scale-negative.py", plug(**{'    def friction': '    shape_scale = -1.0\n\n    def friction'}), "error",
     ["shape-scale-negative.py", "shape_scale"], effect="humidity")
