"""Subset simulation (OpenTURNS) against a quadrature truth."""
import numpy as np

from rollaway.risk import load_population
from rollaway.risk.estimators import estimate
from tests.risk.truths import rate_two_normals


def test_subset_simulation_holds_a_rare_truth(write_population):
    path = write_population("[vary]\nmu_drum = { normal = [0.42, 0.03] }\nhand_force_N = { normal = [400, 40] }\n")
    truth = rate_two_normals(0.42, 0.03, 400.0, 40.0)
    e = estimate(load_population(path), "subset", 200_000, seed=3)
    assert e.method == "subset" and e.total.ci95[0] <= truth <= e.total.ci95[1], (e.total, truth)
    assert np.isnan(e.brake.probability)          # the budget goes to the rate alone
    assert abs(e.total.probability / truth - 1) < 0.5
