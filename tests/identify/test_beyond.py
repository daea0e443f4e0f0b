"""rollaway.identify.beyond: the held-out rule a second effect must pass (per test, both channels, ties)."""
from types import SimpleNamespace

import numpy as np
import pytest

from rollaway.identify.beyond import TEST_WIN, preference, within_tests


def test_within_tests_removes_each_tests_level_in_the_named_channels_only():
    class Data:
        test_index, n_tests = np.array([0, 0, 1, 1, 1]), 2

        def __len__(self):
            return 5
    r = np.arange(10.0)
    out = within_tests(Data(), r, {"torque"})
    assert np.array_equal(out[:5], r[:5])                                   # temperature untouched
    assert np.allclose(out[5:], [-0.5, 0.5, -1.0, 0.0, 1.0])               # torque less each test's mean
    assert np.array_equal(r, np.arange(10.0))                               # the input is not changed


def test_held_out_ties_count_for_neither_side():
    """The partner rule counts a test as won or lost only beyond TEST_WIN in log score: two ties of +0.2 do not make a
    majority beside two wins and two losses; turned into wins of +2 they do."""

    class Data:
        test_index, n_tests = np.arange(6), 6

        def __len__(self):
            return 6
    fit = SimpleNamespace(model=SimpleNamespace(effects=[]))

    def held(gains):                      # residuals [temperature | torque] of (re-formed, pair) per test
        g = np.asarray(gains, float)
        temp = np.array([0.2, 0, 0, 0, 0, 0])
        reform = np.concatenate([temp, np.sqrt(2 * np.maximum(g, 0))])
        two = np.concatenate([np.zeros(6), np.sqrt(2 * np.maximum(-g, 0))])
        return [reform, two]
    ties = [0.16, -5.2, 24.4, 0.2, -5.3, 77.5]
    out = preference(Data(), fit, fit, held(ties))
    assert out["per_test"][2] == pytest.approx(24.4) and (out["better_tests"], out["worse_tests"]) == (2, 2)
    assert not out["passes"] and TEST_WIN > 0.2
    wins = [2.0, -5.2, 24.4, 2.0, -5.3, 77.5]
    out = preference(Data(), fit, fit, held(wins))
    assert (out["better_tests"], out["worse_tests"]) == (4, 2) and out["passes"], out
