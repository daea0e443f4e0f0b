"""A friction law and a lining-modulus law on tests facing one way, compared with the shoe arm ratio free.

μ and E_l enter the torque together (eq. 17b: μ_d·r_d·A·E), and differ only through the self-energising factor
k(μ, s) = l_f/(l_f − s·μ·l_fr) of eqs. (18)–(21), which a friction law changes with temperature and a modulus
law does not.  How much k bends with μ depends on the arm ratio l_fr/l_f — which tests facing one way do not test
(it shows only in the downhill/uphill ratio), so the drum calibration holds it at the set's value.  Compared at that
held value, one law can beat the other by more than the selection's bar for a reason the data never saw: held-out
names campaign 389 (a linear modulus law on two uphill tests, another drum) named friction 13.5 BIC ahead of the
modulus law; with the arm ratio free in both they are 0.5 apart, the modulus law ahead.

:func:`twin_rival` refits the verdict's law and its twin with the arm ratio free and names the twin beside the
verdict where the data then cannot tell them apart (BIC within
:data:`~rollaway.identify.ambiguity.INDISTINGUISHABLE_BIC`, held-out prediction not preferring the verdict beyond
:func:`~rollaway.identify.ambiguity.preference_margin`).
"""
from __future__ import annotations

TWINS = {"friction_temperature": "modulus_temperature", "modulus_temperature": "friction_temperature"}
ARM = "shoe_arm_ratio"


def twin_rival(data, params, verdict, tested: dict, noise_torque_Nm: float, inflation: float = 1.0) -> dict | None:
    """The verdict's twin law as a rival (``{"kind": "rival", "effects", "delta_bic", "heldout_elpd", "heldout_se",
    "why", "fit", "tell_apart"}``) where *verdict* (a one-effect fit with the brake parameters of *params*) is a
    friction or a modulus law, the bench tested one direction (*tested*: :func:`rollaway.uncertainty.bands.validity`)
    and the arm ratio was held; None otherwise, or where the data tell the two apart with the arm ratio free.
    *inflation*: the verdict's residual variance inflation (the BIC difference is divided by it, as for any rival)."""
    from rollaway.identify.ambiguity import INDISTINGUISHABLE_BIC, heldout_difference, preference_margin
    from rollaway.identify.model import DrumPlan
    from rollaway.identify.separating_test import tell_apart
    from rollaway.identify.workers import fit_all
    effects = list(getattr(verdict, "effects", ()))
    twin = TWINS.get(effects[0]) if len(effects) == 1 else None
    if twin is None or len(tested.get("directions", ())) != 1 or ARM in params.free or verdict.jacobian is None:
        return None
    plan = DrumPlan(params.params, tuple(params.free) + (ARM,))
    start = dict(verdict.values)
    mine, other = fit_all(data, [(effects, plan, dict(start=start)), ([twin], plan, dict(start=start))])
    if mine.jacobian is None or other.jacobian is None:
        return None
    dbic = (other.bic - mine.bic) / max(inflation, 1.0)
    elpd, se = heldout_difference(mine, other)
    if dbic >= INDISTINGUISHABLE_BIC or elpd <= -preference_margin(mine, se):
        return None
    held = (other.bic - verdict.bic) / max(inflation, 1.0)
    why = (f"with the shoe arm ratio held at the set's value (tests facing one way do not test it) BIC prefers "
           f"{effects[0]} by {held:.1f}; with it free in both they are {dbic:+.1f} apart and the held-out prediction "
           f"does not prefer either (Δ log score {elpd:+.1f} ± {se:.1f}): the self-energising factor that tells them "
           f"apart depends on that ratio")
    return {"kind": "rival", "effects": [twin], "delta_bic": float(dbic), "heldout_elpd": elpd, "heldout_se": se,
            "why": why, "fit": other, "tell_apart": tell_apart(verdict, other, tested, noise_torque_Nm)}


__all__ = ["ARM", "TWINS", "twin_rival"]
