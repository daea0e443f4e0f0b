"""The study's parts that need more than one estimator: MuJoCo at the boundary, a Dask cluster, the result."""
import json

import numpy as np

from rollaway.jsonsafe import to_jsonable
from rollaway.risk import load_population, run_study
from rollaway.risk.study import SIM_THRESHOLD, simulate_boundary

POP = "[vary]\nmu_drum = { uniform = [0.3, 0.6] }\n"


def test_mujoco_confirms_the_verdicts_near_the_boundary(write_population):
    pop = load_population(write_population(POP)).with_fixed("hand_force_N", 250.0)
    sim = simulate_boundary(pop, 2, seed=0)
    assert sim["simulated"] == 2 and sim["flipped_outside_threshold"] == 0
    for car in sim["cars"]:
        assert abs(min(car["brake_margin"], car["tyre_margin"]) - 1) < 0.01     # the nearest of 100 000 cars
        assert car["agree"] or car["inside_threshold"]
    assert sim["threshold"] == SIM_THRESHOLD


def test_a_fake_simulator_that_disagrees_outside_the_threshold_is_counted(write_population):
    pop = load_population(write_population(POP)).with_fixed("hand_force_N", 250.0)

    class Always:
        outcome = "held"
    sim = simulate_boundary(pop, 50, seed=0, simulate_fn=lambda s: Always())
    rolls = [c for c in sim["cars"] if c["analytic"] == "rolls"]
    assert rolls and sim["confirmed"] == 50 - len(rolls)
    assert sim["flipped_outside_threshold"] == sum(not c["inside_threshold"] for c in rolls)


def test_result_is_json_and_text(write_population, tmp_path):
    pop = load_population(write_population(POP + "heat_transfer_W_m2K = { lognormal = [40, 0.1] }\n"))
    r = run_study(pop, samples=10_000, method="mc", sensitivity=True, design="hand_force_N", target=0.01,
                  chart=tmp_path / "c.png")
    d = json.loads(json.dumps(to_jsonable(r.as_dict())))
    assert d["design"]["name"] == "hand_force_N" and np.isclose(d["ppm"], r.ppm)
    assert len(r.charts) == 2 and all((tmp_path / n).exists() for n in ("c.png", "c-design.png"))
    text = r.summary()
    assert "roll-away rate" in text and "design: least hand_force_N" in text and "mu_drum" in text
