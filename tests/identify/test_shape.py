"""Shape-free forms in the selection: another effect's own form beside a verdict, on held-out campaigns of the
independent generator (tests/identify/heldout_names.py)."""
import pytest

from rollaway.identify.diagnose import diagnose
from tests.identify.heldout_names import campaign, judge


def test_an_effect_whose_catalogue_form_misses_is_named_beside_the_verdict_it_explains_better_in_its_own():
    """A friction rising with the square of the temperature, 5-min samples, 4 tests: the catalogue's linear
    friction loses to lining creep by 32 in BIC, and creep was named alone (a wrong name with no doubt).  In
    shape-free forms friction fits better than creep (BIC 4.3 lower) and predicts the held-out tests as well as
    creep's catalogue form: both are named, with the test that would tell them apart."""
    hidden, data = campaign(7)
    assert hidden == "friction_quadratic"
    d = diagnose(data)
    got = judge(hidden, d)
    assert got["right_or_alternative"] and not got["partner"], got
    alt = next(a for a in d.alternatives if a["effects"] == ["friction_temperature"])
    assert alt["form"] == "shape-free" and alt["heldout_elpd"] >= 0.0 and "tell_apart" in alt
    line = d.as_dict()["verdict_line"]
    assert line.startswith(f"{d.verdict} or friction_temperature: these data cannot tell them apart"), line


@pytest.mark.parametrize("i", [1, 2, 3, 13, 14, 15, 25, 27, 37, 39])
def test_no_other_form_beside_a_verdict_whose_catalogue_form_is_the_truth(i):
    """Friction linear in T, exponential creep, exponential cable relaxation (the catalogue's forms) on held-out
    campaigns: where the verdict is right, no effect is named beside it for its shape-free form."""
    hidden, data = campaign(i)
    d = diagnose(data)
    if not judge(hidden, d)["right"]:
        pytest.skip(f"campaign {i}: verdict {d.verdict} (the name is judged elsewhere)")
    assert not [a for a in d.alternatives if a.get("form") == "shape-free"], d.alternatives
