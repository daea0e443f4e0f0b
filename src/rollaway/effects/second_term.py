"""A second term of an effect's own kind: the same physics with its own amplitude and time constant.

A catalogue law with one time constant (a lining's stress relaxation, a cable's loss) is the first term of a
series: a viscoelastic lining relaxes with a spectrum of times (the generalised Maxwell model, a Prony series:
Ferry, *Viscoelastic Properties of Polymers*, 3rd ed. 1980, ch. 3; Park & Schapery 1999, "Methods of
interconversion between linear viscoelastic material functions", Int. J. Solids Struct. 36, §2), and a power-law
or logarithmic loss is well approximated by two such terms.  :mod:`rollaway.identify.partner` fits the effect with
this second term to ask whether a second *catalogue* effect beside it says more than the first effect's own law
written with one term more.  Only for effects with a parameter besides their amplitude (a single-parameter law
twice is the same law).
"""
from __future__ import annotations

from rollaway.effects.base import Effect

SUFFIX = "_2"                  # "lining_creep" → "lining_creep_2"


def has_second_term(effect) -> bool:
    """True when *effect* can carry a second term: two or more parameters, none per test."""
    return len(effect.parameters) >= 2 and not any(p.per_test for p in effect.parameters)


def second_term(effect) -> type[Effect]:
    """An Effect class: *effect*'s own law under the name ``NAME_2`` (its parameters ``NAME_2.…``), applied after
    *effect* in the chain.  Raises ValueError where :func:`has_second_term` is false."""
    if not has_second_term(effect):
        raise ValueError(f"effect '{effect.name}' has no second term (one parameter, or per-test parameters)")
    base = type(effect) if isinstance(effect, Effect) else effect
    return type(f"SecondTerm_{base.__name__}", (base,), {
        "__reduce__": lambda self: (_instance, (base.name,)),        # pickled as its base's name
        "name": f"{base.name}{SUFFIX}", "summary": f"a second term of {base.name} (its own amplitude and times)",
        "base": base.name})


def _instance(base: str) -> Effect:
    """An instance of *base*'s second term (how one is unpickled: its class is built at run time)."""
    from rollaway.effects import get_effect
    return second_term(get_effect(base))()


__all__ = ["SUFFIX", "has_second_term", "second_term"]
