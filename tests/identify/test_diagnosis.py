"""rollaway.identify.diagnosis: the result object's views agree with each other and survive JSON."""
import json

import pytest

from rollaway.identify.diagnose import diagnose
from rollaway.identify.diagnosis import Diagnosis
from tests.identify.bench_generator import generate


@pytest.fixture(scope="module")
def ambiguous():
    """A lining modulus falling with temperature, tested downhill only at two forces (friction fits as well)."""
    return diagnose(generate(["modulus_linear"], sampling="5min", seed=301, directions=("downhill",), forces=[200, 300]))


def test_views_of_one_result_agree(ambiguous, tmp_path):
    d = ambiguous
    assert isinstance(d, Diagnosis)
    j = json.loads(d.to_json(tmp_path / "d.json"))
    assert json.loads((tmp_path / "d.json").read_text()) == j
    assert j["verdict"] == d.verdict and d.summary().startswith(f"verdict: {j['verdict_line']}")
    assert [a["effects"] for a in j["alternatives"]] == [a["effects"] for a in d.alternatives]
    assert all("fit" not in a and a["kind"] in ("rival", "closest", "weak") for a in j["alternatives"])
    weights = [a["weight"] for a in j["predictive"]["alternatives"]]
    assert all(0 < w < 1 for w in weights) and sum(weights) < 1
    assert j["refined"]["effects"] == [e.name for e in d.model.effects]      # the saved model is the refined fit


def test_again_diagnoses_other_data_with_the_defaults(ambiguous):
    other = ambiguous.again(generate([], sampling="5min", seed=302, directions=("downhill",), forces=[200, 300]))
    assert isinstance(other, Diagnosis) and other.verdict == "none"
