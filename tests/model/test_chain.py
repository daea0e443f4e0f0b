"""The drum chain (rollaway.model.chain) step by step, against the reference values and through DrumModel."""
from __future__ import annotations

import numpy as np

from rollaway.model import chain
from rollaway.model.drum_model import DrumModel


def test_paper_chain_reproduces_the_reference_torques():
    m = DrumModel("paper")
    t = np.array([0.0, 3600.0])
    down = chain.evaluate(m, t, 400.0, "downhill").torque_Nm
    up = chain.evaluate(m, t, 400.0, "uphill").torque_Nm
    assert np.allclose(down, [1924.977, 1611.690], rtol=1e-6)
    assert np.allclose(up, [942.010, 788.699], rtol=1e-6)


def test_model_methods_are_the_chain_and_overrides_broadcast():
    m = DrumModel("paper", effects=["lining_creep"], values={"lining_creep.relaxed_fraction": 0.1})
    t = np.linspace(0.0, 3600.0, 7)
    a = m.evaluate(t, 300.0, "uphill").torque_Nm
    assert np.array_equal(a, chain.evaluate(m, t, 300.0, "uphill").torque_Nm)
    ratios = np.array([0.7, 0.857142857, 1.0])            # arm ratio draws: one per point
    s = chain.evaluate(m, 0.0, 300.0, "uphill", values={"shoe_arm_ratio": ratios}).torque_Nm
    assert s.shape == (3,) and s[0] > s[1] > s[2]          # a longer friction arm takes more facing uphill
    assert np.isclose(s[1], a[0], rtol=1e-8)


def test_drum_temperature_runs_a_temperature_hook_without_a_given_state():
    m = DrumModel("paper", effects=["radiation_cooling"], values={"radiation_cooling.emissivity": 0.8})
    t = np.array([0.0, 600.0, 3600.0])
    hot = chain.drum_temperature(m, t)
    plain = chain.drum_temperature(DrumModel("paper"), t)
    assert np.isclose(hot[0], plain[0]) and np.all(hot[1:] < plain[1:])      # radiation cools faster
