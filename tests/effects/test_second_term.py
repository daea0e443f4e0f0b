"""A second term of an effect's own law (rollaway.effects.second_term)."""
import pickle

import numpy as np
import pytest

from rollaway.effects import get_effect
from rollaway.effects.second_term import has_second_term, second_term
from rollaway.identify.model import BenchModel
from tests.identify.bench_generator import generate


def test_only_laws_with_a_shape_parameter_have_a_second_term():
    assert has_second_term(get_effect("lining_creep")) and has_second_term(get_effect("cable_relaxation"))
    assert not has_second_term(get_effect("friction_temperature"))        # one slope twice is one slope
    assert not has_second_term(get_effect("torque_zero_offset"))          # per-test values
    with pytest.raises(ValueError, match="no second term"):
        second_term(get_effect("friction_temperature"))


def test_the_second_term_is_the_same_law_under_its_own_name_and_survives_pickling():
    two = second_term(get_effect("lining_creep"))()
    assert two.name == "lining_creep_2" and [p.name for p in two.parameters] == ["relaxed_fraction",
                                                                                 "relaxation_time_s"]
    assert pickle.loads(pickle.dumps(two)).name == "lining_creep_2"
    d = generate([], sampling="5min", seed=1, forces=np.array([200.0, 300.0]))
    one = BenchModel(None, ["lining_creep"])
    both = BenchModel(None, ["lining_creep", two])
    v1 = {"lining_creep.relaxed_fraction": 0.08, "lining_creep.relaxation_time_s": 300.0}
    v2 = {**v1, "lining_creep_2.relaxed_fraction": 0.05, "lining_creep_2.relaxation_time_s": 2000.0}
    f1, f2 = one.predict(d, v1).torque_Nm, both.predict(d, v2).torque_Nm     # the second term multiplies the first
    np.testing.assert_allclose(f2 / f1, 1 - 0.05 * (1 - np.exp(-d.time_s / 2000.0)), rtol=1e-9)
