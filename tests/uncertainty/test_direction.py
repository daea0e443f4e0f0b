"""rollaway.uncertainty.direction: a direction the bench did not test, against the posterior written out here."""
import numpy as np
import pytest

from rollaway.model.drum_model import DrumModel
from rollaway.uncertainty.direction import FRICTION_PRIOR, SCALE_REL_SD, carried_over, untested_direction_factor


def test_the_untested_direction_carries_the_torque_over_with_a_friction_coefficient_drawn_apart_from_mu_d():
    """A μ_d fitted at 0.15 on downhill tests (the torque scale of a softer, thicker lining): facing uphill the
    torque is carried over by the direction ratio of a friction coefficient drawn from its posterior given the scale
    (log-normal: the prior's and the fit's logs weighted by their inverse variances), written out here apart from the
    code; the tested direction and a bench of both directions are left as they are."""
    m = DrumModel("paper")
    m.predictive = {"tested_directions": ["downhill"]}
    n, mu_d = 20000, 0.15
    f = untested_direction_factor(m, {"mu_drum": np.full(n, mu_d)}, n, -1.0, seed=3)
    w0, w1 = FRICTION_PRIOR[1] ** -2, SCALE_REL_SD ** -2
    mu_median = np.exp((w0 * np.log(FRICTION_PRIOR[0]) + w1 * np.log(mu_d)) / (w0 + w1))
    l_f, l_fr = m.params.shoe_arm_normal_m, m.params.shoe_arm_friction_m

    def down_over_up(mu):                                   # eqs. (18)-(21): l_f / (l_f - s*mu*l_fr)
        return (l_f / (l_f - mu * l_fr)) / (l_f / (l_f + mu * l_fr))
    assert np.median(f) == pytest.approx(down_over_up(mu_d) / down_over_up(mu_median), rel=0.01)
    assert np.median(f) < 0.85 and np.all(f > 0)            # a larger μ: a larger ratio, less torque uphill
    lo = np.exp(np.log(mu_median) - 1.645 / np.sqrt(w0 + w1))
    assert np.mean(f > down_over_up(mu_d) / down_over_up(lo)) == pytest.approx(0.05, abs=0.01)
    assert carried_over(m, -1.0) and not carried_over(m, 1.0)
    assert list(carried_over(m, np.array([1.0, -1.0]))) == [False, True]
    m.predictive = {"tested_directions": ["downhill", "uphill"]}
    assert not carried_over(m, -1.0)
