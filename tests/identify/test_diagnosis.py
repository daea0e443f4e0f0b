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


@pytest.mark.parametrize("source,index,kind", [("names", 9, "closest"), ("names", 47, "weak"), ("names", 33, "rival"),
                                               ("two", 202, "rival")])
def test_every_kind_of_verdict_writes_whole_outputs(tmp_path, source, index, kind):
    """Held-out campaigns whose verdicts carry each kind of alternative (closest effects with their shape-free fits,
    a weak suggestion, a rival beside a partial form, two effects): the JSON parses, the HTML report and the model
    file are written, and the saved model answers a road question with its band."""
    import rollaway
    from tests.identify.heldout_names import campaign
    from tests.uncertainty.band_questions import two_effect_data
    data = campaign(index)[1] if source == "names" else two_effect_data(index)[5]
    d = diagnose(data)
    assert kind in {a.get("kind") for a in d.alternatives}, d.verdict
    j = json.loads(d.to_json())
    assert j["verdict_line"] and len(j["alternatives"]) == len(d.alternatives)
    d.report(tmp_path / "d.html")
    assert (tmp_path / "d.html").stat().st_size > 10_000
    path = d.save_model(tmp_path / "m.toml")
    v = rollaway.hold(str(path), grade_pct=20, hand_force_N=300, direction="uphill", uncertainty=50)
    assert 0.0 <= v.rollaway_probability <= 1.0
