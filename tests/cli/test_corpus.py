"""The malformed-input corpus (tests/corpus/manifest.json) through the CLI, in-process.

Every file is either accepted (exit 0, no NaN printed) or refused with exit 2 and a message
whose first line names the file and the key or line (the manifest's ``needles``) — never a
traceback.  Cases marked ``xfail`` need the hook guard of the model chain.  The plugin cases
(``tests/corpus/plugin_cases.py``) are written from one template into a temporary folder.
"""
import json
import re
from pathlib import Path

import pytest

from tests.corpus.plugin_cases import CASES as PLUGIN_CASES
from tests.corpus.plugin_cases import write_plugins

CORPUS = Path(__file__).resolve().parents[1] / "corpus"
CASES = json.loads((CORPUS / "manifest.json").read_text(encoding="utf-8"))["cases"] + PLUGIN_CASES


@pytest.fixture(scope="module")
def plugins(tmp_path_factory):
    return write_plugins(tmp_path_factory.mktemp("corpus") / "plugin")
NAN = re.compile(r"\b-?nan\b", re.IGNORECASE)


def command(case: dict, tmp_path: Path, plugins: Path) -> list:
    path = CORPUS / case["file"]
    kind = case["file"].split("/")[0]
    if kind == "scenario":
        return ["simulate", path]
    if kind == "params":
        return ["params", path]
    if kind == "sweep":
        return ["sweep", path, "--out", tmp_path / "out", "--simulate", "none", "--no-plots", "--quiet"]
    if kind == "bench":                 # a file or a folder, with the case's own flags
        return ["compare", path, *(a.replace("{corpus}", str(CORPUS)) for a in case.get("args", ()))]
    if kind == "plugin":
        return ["compare", CORPUS / "plugin" / "data.csv", "--effect-file", plugins / path.name,
                "--effect", case["effect"]]
    raise AssertionError(f"unknown corpus folder {kind}")


@pytest.fixture(autouse=True)
def _fresh_plugin_registry():
    from rollaway import effects
    before = dict(effects._USER)
    yield
    effects._USER.clear()
    effects._USER.update(before)


def _params(case):
    marks = [pytest.mark.xfail(strict=False, reason=case["xfail"])] if case.get("xfail") else []
    return pytest.param(case, id=case["file"], marks=marks)


def test_corpus_is_large_and_covers_every_loader(plugins):
    kinds = {c["file"].split("/")[0] for c in CASES}
    assert kinds == {"scenario", "params", "sweep", "bench", "plugin"}
    assert len(CASES) >= 100
    for c in CASES:
        assert (plugins / Path(c["file"]).name if c in PLUGIN_CASES else CORPUS / c["file"]).exists(), c["file"]
        assert c["expect"] in ("accept", "error")
        assert c["expect"] == "accept" or c["needles"], f"{c['file']}: an error case must say what it names"


@pytest.mark.parametrize("case", [_params(c) for c in CASES])
def test_corpus_case(case, run_cli, tmp_path, plugins):
    code, out, err = run_cli(*command(case, tmp_path, plugins))
    assert "Traceback" not in out + err
    if case["expect"] == "accept":
        assert code == 0, err
        assert not NAN.search(out), out
        return
    assert code == 2, (code, out, err)
    first = err.strip().splitlines()[0] if err.strip() else ""
    assert first.startswith("rollaway "), err
    name = Path(case["file"]).name
    assert name in first, f"message does not name the file {name}: {first}"
    for needle in case["needles"]:
        assert needle in first, f"message lacks {needle!r}: {first}"
