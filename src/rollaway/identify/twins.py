"""Twin laws the data tell apart only through something they did not test or a partner's form.

A friction law and a lining-modulus law on tests facing one way, compared with the shoe arm ratio free
(:func:`twin_rival`); the same two laws beside another effect, each re-formed (:func:`law_twin_rival`); a lining
creep and a cable relaxation beside a law whose form is not the catalogue's (:func:`loss_twin_rival`); a law whose
form is not the data's beside its twin re-formed, for the bands (:func:`partial_twin_pair`).

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
LOSSES = {"lining_creep": "cable_relaxation", "cable_relaxation": "lining_creep"}
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


def loss_twin_rival(data, params, verdict, candidates, tested: dict, noise_torque_Nm: float, inflation: float = 1.0,
                    rivalry=()) -> list[dict]:
    """*rivalry* with the set that exchanges the verdict's loss with time for its twin (:data:`LOSSES`) first, where
    *verdict* (a fit of two effects with the brake parameters of *params*) holds one loss beside another law and,
    with that law re-formed (its hook as a linear spline, :func:`rollaway.identify.shape.flexible_effect`) in both,
    the twin fits within :data:`~rollaway.identify.ambiguity.INDISTINGUISHABLE_BIC` of the loss or better, and the
    held-out prediction does not prefer the loss beyond :func:`~rollaway.identify.ambiguity.preference_margin`.

    A lining creep loses a fraction of the clamp force, a cable relaxation a displacement: the two differ only in
    how the loss scales with hand force.  Beside a temperature law whose catalogue form is not the data's, that
    law's misfit also falls with time as the drum cools and can be taken up by one loss better than by the other —
    two-effect band campaign 389 (a quadratic friction law beside an exponential lining creep, one direction)
    named the cable 14.7 BIC ahead; with the friction law re-formed, the creep leads by 13.4.  The exchanged set is
    first fitted from the verdict's values and from the twin's own first-step fit (*candidates*), the better kept
    (from the verdict's values alone the twin's size stays at zero).  The rival's fit is the twin beside the
    re-formed law: in the bands it competes as the set the data do not rule out.  *rivalry* unchanged where there
    is no such rival or it is already named."""
    from rollaway.effects import available_effects, get_effect
    from rollaway.identify.ambiguity import INDISTINGUISHABLE_BIC
    from rollaway.identify.shape import covariate_of, flexible_effect, shape_hook
    from rollaway.identify.workers import fit_all
    effects, rivalry = list(getattr(verdict, "effects", ())), list(rivalry)
    losses = [e for e in effects if e in LOSSES]
    if (len(effects) != 2 or len(losses) != 1 or verdict.jacobian is None
            or not all(e in available_effects() for e in effects)):        # a shape-free form is re-formed already
        return rivalry
    loss = losses[0]
    law, twin = next(e for e in effects if e != loss), LOSSES[loss]
    swap = [twin if e == loss else e for e in effects]
    found = shape_hook(get_effect(law))
    flex = None if found is None else flexible_effect(get_effect(law), covariate_of(verdict, found[1]))
    if flex is None or any(set(a["effects"]) == set(swap) for a in rivalry):
        return rivalry
    alone = next((c.fit for c in candidates if c.effect == twin and c.fit is not None), None)
    starts = [dict(verdict.values)] + ([{**alone.values, **{n: v for n, v in verdict.values.items()
                                                           if n.startswith(law + ".")}}] if alone else [])
    cat = min(fit_all(data, [(swap, params, dict(start=s)) for s in starts]), key=lambda f: f.bic)
    got = _compared(data, params, [flex if e == law else e for e in effects], verdict.values,
                    [flex if e == law else e for e in swap], cat.values, inflation)
    if got is None:
        return rivalry
    other, dbic, elpd, se, margin = got
    behind = (cat.bic - verdict.bic) / max(inflation, 1.0)   # the exchanged set with the catalogue law (> 0: behind)
    why = (f"with {law}'s form freed (a linear spline in {found[1]}) in both, {twin} fits "
           + (f"better than {loss}" if dbic <= -INDISTINGUISHABLE_BIC else f"as well as {loss}") + f" (BIC {dbic:+.1f})"
           + (f" where {law}'s catalogue law put {loss} {behind:.1f} ahead" if behind > 0 else
              f", as with {law}'s catalogue law (BIC {behind:+.1f}, from a start the selection's exchange did not take)")
           + ", and the held-out prediction " + (f"prefers {twin}" if elpd > margin else "does not prefer either")
           + f" (Δ log score {elpd:+.1f} ± {se:.1f}): a clamp fraction and a cable displacement lost with time differ "
           f"in how the loss scales with hand force, which {law}'s form can take up")
    return _named_first(rivalry, swap, other, (dbic, elpd, se), why, verdict, tested, noise_torque_Nm)


def law_twin_rival(data, params, verdict, candidates, tested: dict, noise_torque_Nm: float, inflation: float = 1.0,
                   rivalry=()) -> list[dict]:
    """*rivalry* with the set that exchanges the verdict's friction or modulus law for its twin (:data:`TWINS`)
    first, where *verdict* (a fit of two effects with the brake parameters of *params*) holds one of them beside an
    effect of another kind and, with each law re-formed (its hook as a linear spline along its covariate) beside
    that effect, the twin fits within :data:`~rollaway.identify.ambiguity.INDISTINGUISHABLE_BIC` of the verdict's
    law or better, and the held-out prediction does not prefer the verdict's beyond
    :func:`~rollaway.identify.ambiguity.preference_margin`.

    The two laws differ through the downhill/uphill ratio (a friction law bends the self-energising factor, a
    modulus law does not); a friction change confined to part of the tested temperatures (a fade above 150 °C)
    written as the catalogue's straight line bends that ratio where the data show no change, and the modulus law,
    which has no such signature, fits better — two-effect band campaign 649 (a fade beside a radiating drum, both
    directions) named `modulus_temperature + radiation_cooling`; re-formed, the friction law is 79.7 BIC ahead.
    The twin's set starts from the twin's own first-step fit (*candidates*) with the other effect's values of
    *verdict*.  The rival's fit is the re-formed twin beside the other effect.  *rivalry* unchanged where there is
    no such rival or it is already named."""
    from rollaway.effects import available_effects, get_effect
    from rollaway.identify.ambiguity import INDISTINGUISHABLE_BIC
    from rollaway.identify.shape import covariate_of, flexible_effect, shape_hook
    effects, rivalry = list(getattr(verdict, "effects", ())), list(rivalry)
    laws = [e for e in effects if e in TWINS]
    if (len(effects) != 2 or len(laws) != 1 or verdict.jacobian is None
            or not all(e in available_effects() for e in effects)):
        return rivalry
    law = laws[0]
    other, twin = next(e for e in effects if e != law), TWINS[law]
    swap = [twin if e == law else e for e in effects]
    found = [shape_hook(get_effect(n)) for n in (law, twin)]
    flex = [None if f is None else flexible_effect(get_effect(n), covariate_of(verdict, f[1]))
            for n, f in zip((law, twin), found)]
    if None in flex or any(set(a["effects"]) == set(swap) for a in rivalry):
        return rivalry
    alone = next((c.fit for c in candidates if c.effect == twin and c.fit is not None), None)
    start = {**(alone.values if alone else verdict.values),
             **{n: v for n, v in verdict.values.items() if n.startswith(other + ".")}}
    got = _compared(data, params, [flex[0] if e == law else e for e in effects], verdict.values,
                    [flex[1] if e == law else e for e in effects], start, inflation)
    if got is None:
        return rivalry
    fit, dbic, elpd, se, margin = got
    why = (f"with both laws re-formed (linear splines in {found[0][1]}) beside {other}, {twin} fits "
           + (f"better than {law}" if dbic <= -INDISTINGUISHABLE_BIC else f"as well as {law}") + f" (BIC {dbic:+.1f})"
           + ", and the held-out prediction " + (f"prefers {twin}" if elpd > margin else "does not prefer either")
           + f" (Δ log score {elpd:+.1f} ± {se:.1f}): the catalogue's straight line in temperature decided between "
           f"them, not the downhill/uphill ratio that tells a friction law from a modulus law")
    return _named_first(rivalry, swap, fit, (dbic, elpd, se), why, verdict, tested, noise_torque_Nm)


def partial_twin_pair(data, params, verdict, forms: list, misfit, inflation: float = 1.0) -> list:
    """``[fit]`` of the law in its catalogue form beside its twin re-formed (a linear spline along the same covariate,
    the knots of the verdict's own spline), for the bands, where the verdict *verdict* is one friction or modulus law
    whose catalogue form is not the data's (*misfit*: the diagnosis' flag, false where nothing is named; *forms*: the
    shape-free forms for the bands, among them the verdict's own, :func:`rollaway.identify.shape.form_rivals`) and
    that pair lowers BIC against the verdict's own spline by
    :data:`~rollaway.identify.selection.BIC_THRESHOLD` or more (divided by the residual variance *inflation*) and
    predicts held-out tests better (:func:`rollaway.identify.beyond.heldout_preference`); else ``[]``.

    One law's spline writes a lining modulus and a friction that both change with temperature as one quantity,
    which the two directions do not follow: a straight modulus law beside a friction fading above 110 °C was named
    `modulus_temperature` (partial), its spline 13.4 BIC behind the pair, and its bands ran 3 % below the truth at
    450 N and from 280 °C (two-effect band campaign 123).  The pair competes in the bands by its held-out score; it
    is not named: over the held-out names campaigns, a twin's spline beside the law stood as often for a loss that
    goes on as the drum cools (a cable relaxation: two-effect campaigns 25, 165 and 348 of
    ``tests/identify/heldout_names.py --two``) or for nothing (one-effect short logs 43 and 85) as for the twin."""
    effects = list(getattr(verdict, "effects", ()))
    if not misfit or len(effects) != 1 or effects[0] not in TWINS:
        return []
    from rollaway.effects import get_effect
    from rollaway.effects.shape_free import is_shape_free
    from rollaway.identify.beyond import heldout_preference
    from rollaway.identify.calibrate import calibrate
    from rollaway.identify.selection import BIC_THRESHOLD, REFORM_ITERATIONS
    from rollaway.identify.shape import PREDICTING_SEGMENT_SAMPLES, covariate_of, flexible_effect, shape_hook
    own = next((f for f in forms if len(f.effects) == 1 and is_shape_free(f.model.effects[0]) and f.jacobian is not None
                and getattr(f.model.effects[0], "base", None) == effects[0]), None)
    if own is None:
        return []
    hook = shape_hook(get_effect(TWINS[effects[0]]))
    flex = None if hook is None else flexible_effect(get_effect(TWINS[effects[0]]), covariate_of(verdict, hook[1]),
                                                     PREDICTING_SEGMENT_SAMPLES)
    if flex is None:
        return []
    pair = calibrate(data, [verdict.model.effects[0], flex], params, start=verdict.values,
                     max_iterations=REFORM_ITERATIONS)
    if pair.jacobian is None or (pair.bic - own.bic) / max(inflation, 1.0) > -BIC_THRESHOLD:
        return []
    return [pair] if heldout_preference(data, pair, own)["passes"] else []


def _named_first(rivalry: list, effects: list, fit, evidence: tuple, why: str, verdict, tested: dict,
                 noise_torque_Nm: float) -> list[dict]:
    """*rivalry* with the rival set *effects* (its *fit*, *evidence* = (ΔBIC, held-out difference, its standard
    error), *why*) first, and the test that would tell it from *verdict*; at most
    :data:`~rollaway.identify.ambiguity.MAX_RIVALS`."""
    from rollaway.identify.ambiguity import MAX_RIVALS
    from rollaway.identify.separating_test import tell_apart
    dbic, elpd, se = evidence
    return ([{"kind": "rival", "effects": effects, "delta_bic": float(dbic), "heldout_elpd": elpd, "heldout_se": se,
              "why": why, "fit": fit, "verdict_effects": list(verdict.effects),
              "tell_apart": tell_apart(verdict, fit, tested, noise_torque_Nm)}] + rivalry)[:MAX_RIVALS]


def _compared(data, params, mine: list, mine_start: dict, theirs: list, theirs_start: dict, inflation: float):
    """*mine* and *theirs* (effect lists, shape-free forms among them) fitted from their starts with a re-formed
    fit's budget: (their fit, ΔBIC theirs − mine divided by *inflation*, held-out difference, its standard error,
    the preference margin), or None where a fit fails or *theirs* is ruled out (ΔBIC beyond
    :data:`~rollaway.identify.ambiguity.INDISTINGUISHABLE_BIC`, or the held-out prediction prefers *mine* beyond
    the margin)."""
    from rollaway.identify.ambiguity import INDISTINGUISHABLE_BIC, heldout_difference, preference_margin
    from rollaway.identify.selection import REFORM_ITERATIONS
    from rollaway.identify.workers import fit_all
    a, b = fit_all(data, [(mine, params, dict(start=mine_start, max_iterations=REFORM_ITERATIONS)),
                          (theirs, params, dict(start=theirs_start, max_iterations=REFORM_ITERATIONS))])
    if a.jacobian is None or b.jacobian is None:
        return None
    dbic = (b.bic - a.bic) / max(inflation, 1.0)
    elpd, se = heldout_difference(a, b)
    margin = preference_margin(a, se)
    if dbic >= INDISTINGUISHABLE_BIC or elpd <= -margin:
        return None
    return b, dbic, elpd, se, margin


__all__ = ["ARM", "LOSSES", "TWINS", "law_twin_rival", "loss_twin_rival", "partial_twin_pair", "twin_rival"]
