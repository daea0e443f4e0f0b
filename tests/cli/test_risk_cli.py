"""``rollaway risk``: the JSON keys, the text summary, charts, and one-line errors with exit 2."""
import json

import pytest

import rollaway

POP = """grade_pct = 20
direction = "uphill"
occupants = 5
hand_force_N = 250
duration_s = 300
initial_drum_temp_C = 200
[vary]
mu_drum = { uniform = [0.3, 0.6] }
heat_transfer_W_m2K = { lognormal = [40, 0.15] }
"""


@pytest.fixture
def pop(tmp_path):
    p = tmp_path / "pop.toml"
    p.write_text(POP, encoding="utf-8")
    return p


def test_json_has_the_keys_of_the_issue(run_cli, pop, tmp_path):
    code, out, err = run_cli("risk", pop, "--json", "--samples", "20000", "--sensitivity", "--design",
                             "hand_force_N", "--target", "0.01", "--chart", tmp_path / "c.png")
    assert code == 0, err
    d = json.loads(out)
    for k in ("probability", "ci95", "ppm", "method", "samples", "brake", "tyres", "sensitivity", "design"):
        assert k in d, k
    assert d["ci95"][0] <= d["probability"] <= d["ci95"][1] and d["ppm"] == pytest.approx(d["probability"] * 1e6)
    assert d["method"] == "mc" and d["samples"] == 20000
    assert set(d["sensitivity"]) == {"mu_drum", "heat_transfer_W_m2K"}
    assert set(d["sensitivity"]["mu_drum"]) >= {"first", "total"}
    assert set(d["design"]) >= {"name", "value", "probability"} and d["design"]["name"] == "hand_force_N"
    assert (tmp_path / "c.png").exists() and (tmp_path / "c-design.png").exists()


def test_text_summary_and_the_api_agree(run_cli, pop):
    code, out, _ = run_cli("risk", pop, "--samples", "20000", "--seed", "3")
    assert code == 0 and "roll-away rate" in out and "95 % interval" in out and "method mc" in out
    r = rollaway.risk(pop, samples=20000, seed=3)
    assert f"{r.probability:.3%}" in out
    assert callable(rollaway.risk) and rollaway.risk.load_population is not None   # the package is callable


@pytest.mark.parametrize("text, args, words", [
    (POP.replace("uniform = [0.3, 0.6]", "uniform = [0.6, 0.3]"), [], ["vary.mu_drum.uniform", "impossible"]),
    (POP.replace("mu_drum =", "mu_drm ="), [], ["vary.mu_drm", "mu_drum"]),
    (POP + "[[correlation]]\nbetween = [\"mu_drum\", \"x\"]\nrho = 0.1\n", [], ["correlation[0].between"]),
    (POP, ["--method", "magic"], ["--method", "auto"]),
    (POP, ["--design", "hand_force_N"], ["--target"]),
    (POP, ["--design", "mu_drum.middle", "--target", "0.01"], ["NAME.lower"]),
    (POP, ["--samples", "10"], ["--samples"]),
    (POP, ["--executor", "spark"], ["--executor", "local"]),
    (POP, ["--chart", "x.png"], ["--sensitivity"]),
])
def test_bad_input_is_one_line_and_exit_2(run_cli, tmp_path, text, args, words):
    p = tmp_path / "bad.toml"
    p.write_text(text, encoding="utf-8")
    code, out, err = run_cli("risk", p, "--samples", "1000", *args)
    assert code == 2 and "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    for w in words:
        assert w in err, (w, err)


def test_missing_file_is_one_line(run_cli, tmp_path):
    code, _, err = run_cli("risk", tmp_path / "none.toml")
    assert code == 2 and len(err.strip().splitlines()) == 1
