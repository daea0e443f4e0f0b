"""The bench reports and JSON: decision first, real tables, fit statistics, design consequence."""
import json
import re

import pytest

from rollaway.identify.synth import synth


def visible(page: str) -> str:
    """The page without its scripts (plotly.js is inlined and contains every word)."""
    return re.sub(r"<script>.*?</script>", "", page, flags=re.S)


@pytest.fixture(scope="module")
def creep_csv(tmp_path_factory):
    path = tmp_path_factory.mktemp("bench") / "creep.csv"
    synth({"lining_creep": {}}, seed=3).to_csv(path)
    return path


def test_compare_json_and_report(run_cli, creep_csv, tmp_path):
    code, out, err = run_cli("compare", creep_csv, "--format", "json", "--report", tmp_path / "c.html")
    assert code == 0, err
    d = json.loads(out)
    assert d["within_noise"] is False and d["verdict"].startswith("The paper model does not match")
    page = visible((tmp_path / "c.html").read_text())
    assert "<pre>" not in page and "baseline" not in page and "Design consequence" in page
    assert page.index("class='verdict") < page.index("<table>")


def test_fit_json_has_a_verdict(run_cli, creep_csv):
    code, out, _ = run_cli("fit", creep_csv, "--effect", "lining_creep", "--format", "json")
    d = json.loads(out)
    assert code == 0 and d["effects_supported"] is True and "BIC" in d["verdict"]


def test_diagnose_report_statistics(run_cli, creep_csv, tmp_path):
    code, out, err = run_cli("diagnose", creep_csv, "--format", "json", "--report", tmp_path / "d.html")
    assert code == 0, err
    assert json.loads(out)["verdict"] == "lining_creep"
    page = visible((tmp_path / "d.html").read_text())
    for needle in ("Correlation of the joint (temperature + torque) stage", "reduced χ²", "evaluations", "initial",
                   "Leave-one-test-out score", "Missing effect found: lining_creep", "Predictive record",
                   "lowest tested force predicted from the others"):
        assert needle in page, needle
    assert "*relative*" not in page and not re.search(r"font-size:\s*[0-9]px", page)


def test_repr_html(creep_csv):
    from rollaway.identify.calibrate import calibrate
    from rollaway.bench.measurements import load_measurements
    fit = calibrate(load_measurements(creep_csv), ["lining_creep"])
    h = fit._repr_html_()
    assert "<table>" in h and "lining_creep.relaxed_fraction" in h


def test_the_design_case_says_when_its_hold_lies_beyond_the_benchs(tmp_path):
    """The design sentence of a campaign of 2-min tests says the 300 s case lies beyond them; hour-long tests not."""
    from rollaway.identify.calibrate import calibrate
    from rollaway.identify.report import design_section
    short = calibrate(synth(seed=5, dt_s=10.0, duration_s=120.0))
    long = calibrate(synth(seed=5))
    said = design_section([("calibrated paper model", short)])[0]
    assert "Beyond the bench data: its tests lasted at most 120 s" in said, said
    assert "Beyond the bench data" not in design_section([("calibrated paper model", long)])[0]
