"""The report figures: plotly.js specifications that are valid JSON, name every test, and draw in a browser."""
import json
import re
import shutil
import subprocess

import numpy as np
import pytest

from rollaway.identify.calibrate import calibrate
from rollaway.identify.report import plot
from rollaway.identify.report_figures import (LEGEND_TESTS, legend_labels, num, residual_figure, signals_figure,
                                              unnum)
from rollaway.identify.synth import synth


@pytest.fixture(scope="module")
def creep_fit():
    return calibrate(synth({"lining_creep": {}}, seed=4), ["lining_creep"])


def test_num_is_plotly_typed_array_json_and_reads_back():
    spec = num([1234.5678, 0.0012345, np.nan, -2.0])
    assert spec["dtype"] == "f4" and isinstance(spec["bdata"], str)
    back = unnum(spec)
    np.testing.assert_allclose(back[[0, 1, 3]], [1234.5678, 0.0012345, -2.0], rtol=1e-7)
    assert np.isnan(back[2]) and unnum(num([])).size == 0


def test_signals_figure_names_every_test_and_every_model_once(creep_fit):
    fig = signals_figure([("calibrated", creep_fit), ("other", creep_fit)])
    json.dumps(fig, allow_nan=False)
    legend = [t["name"] for t in fig["data"] if t.get("showlegend", True)]
    assert legend == legend_labels(creep_fit.data) + ["calibrated", "other"]
    measured = [t for t in fig["data"] if t.get("mode") == "markers"]
    assert sum(unnum(t["x"]).size for t in measured) == 2 * len(creep_fit.data)     # every sample, both channels


def test_residual_figure_shares_traces_beyond_the_legend_limit(creep_fit):
    noise = {"torque": 3.0, "temperature": 0.5}
    few = residual_figure(creep_fit, noise)
    assert len(few["data"]) == 8 * creep_fit.data.n_tests
    assert len(few["layout"]["shapes"]) == 16 and few["layout"]["shapes"][0]["y1"] == pytest.approx(7.5)
    many = synth({}, seed=1, hand_forces_N=tuple(np.linspace(150, 400, LEGEND_TESTS // 2 + 1)))
    assert many.n_tests > LEGEND_TESTS
    fig = residual_figure(calibrate(many, []), noise)
    assert len(fig["data"]) == 8 and all(t["type"] == "scattergl" for t in fig["data"])
    assert unnum(fig["data"][0]["marker"]["color"]).size == len(many) == len(fig["data"][0]["text"])


def test_plot_cannot_close_its_script_early():
    fig = {"data": [{"type": "scatter", "x": [1], "y": [2], "name": "T1</script><script>alert(1)</script>"}],
           "layout": {}}
    html = plot(fig)
    assert html.count("</script>") == 1 and "<\\/script>" in html


@pytest.mark.skipif(not (shutil.which("chromium") or shutil.which("chromium-browser")), reason="no Chromium here")
def test_diagnose_report_draws_in_a_headless_browser(tmp_path, run_cli):
    csv = tmp_path / "d.csv"
    synth({"lining_creep": {}}, seed=3).to_csv(csv)
    code, _, err = run_cli("diagnose", csv, "--report", tmp_path / "d.html")
    assert code == 0, err
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    dom = subprocess.run([browser, "--headless", "--no-sandbox", "--disable-gpu", "--virtual-time-budget=15000",
                          "--dump-dom", (tmp_path / "d.html").as_uri()], capture_output=True, text=True,
                         timeout=120).stdout
    n_plots = len(re.findall(r"class=\"plot[ \"]", dom))
    assert n_plots == 4
    assert len(re.findall(r"<svg class=\"main-svg\"", dom)) >= n_plots          # plotly drew every figure
    assert dom.count("class=\"point\"") > len(synth({"lining_creep": {}}, seed=3))   # with its data points
