"""The Effect base class: neutrality through the amplitude parameter."""
from rollaway.effects import CATALOGUE


def test_an_effect_with_an_amplitude_is_neutral_whatever_its_time_constant():
    creep = CATALOGUE["lining_creep"]
    assert creep.amplitude == "relaxed_fraction"
    assert creep.is_neutral({"relaxed_fraction": 0.0, "relaxation_time_s": 5000.0})
    assert not creep.is_neutral({"relaxed_fraction": 0.05, "relaxation_time_s": 900.0})


def test_without_an_amplitude_every_parameter_must_be_neutral():
    cls = next(c for c in CATALOGUE.values() if not c.amplitude and len(c.parameters) > 1)
    values = cls.neutral_values()
    assert cls.is_neutral(values)
    p = cls.parameters[-1]
    assert not cls.is_neutral({**values, p.name: p.upper if p.upper != p.neutral else p.lower})
