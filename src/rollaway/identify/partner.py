"""A second effect on its own evidence, for :mod:`rollaway.identify.diagnose`.

Two effects that pass the forward steps are both named only when the second predicts held-out tests better than
the first *re-formed* (its hook as a linear spline: :func:`~rollaway.identify.beyond.beyond_reform`), with the pair ordered by what each
explains alone (:func:`own_evidence`).  Where the pair does not, a second effect is sought beside the re-formed
first (:func:`beside_reformed`): the first's catalogue form may be wrong and the forward step, beside it, may have
picked the wrong second effect, or the pair's gain may be split with the first's misfit although the second adds
what no spline of the first's hook can (a temperature law beside a creep).  It must also beat its own re-formed
version alone: one mis-formed effect is not a pair.  The tests each second
effect must pass, and the held-out rule they share, are :mod:`rollaway.identify.beyond`.
"""
from __future__ import annotations

from rollaway.identify.beyond import beyond_reform, beyond_second_term, heldout_preference, refit_words
from rollaway.identify.calibrate import FitResult, calibrate
from rollaway.identify.offsets import offsets_absorbed
from rollaway.identify.shape import reform_job
from rollaway.identify.workers import fit_all
from rollaway.identify.selection import BIC_THRESHOLD, REFORM_ITERATIONS, SCREEN_ITERATIONS, structure

def own_evidence(data, params, chosen, current, struct, fits, nq, nt, steps, ev, refree=(), names=(), departures=()):
    """Keep the second of two selected effects only if it predicts held-out tests better than the first
    re-formed, with the brake parameters *refree* (held as not needed by the bare drum) freed in both
    (:func:`~rollaway.identify.beyond.beyond_reform`) — and, where it does, still with *departures* freed too (held by the bare drum because
    the logs cannot tell them from another: :meth:`rollaway.identify.drum.DrumCalibration.departures`; a lining
    creep can stand in for a thicker, softer lining than the set's, which the gap imitates in eq. (16b); asked
    only of a pair that passes, since those fits are slow: the gap and μ_d are nearly one direction of the
    least-squares problem); else the effect of *names* that does beside the first re-formed
    (:func:`beside_reformed`, sought whether or not the re-formed first leaves structure: the structure tests at
    p < 0.001 miss what BIC and the held-out tests see), or none: keep the first alone.  A pair that passes is kept only if the first, in
    turn, predicts better than the second re-formed; else the second alone (the first only absorbed its form
    mismatch: a friction change beside a creep whose catalogue law flattens too early).  Logs to *steps*, explains in *ev*;
    returns (chosen, current fit, its structure, fits per step).

    The first is the one that explains more alone (lower BIC, both refitted with the same brake parameters): the
    order of the forward steps was decided with the drum of that step, which a later step may have freed further."""
    from rollaway.model.drum_parameters import FREE_PARAMETERS
    refree = tuple(refree)
    departures = tuple(n for n in departures if n not in refree and FREE_PARAMETERS[n].effect not in chosen)
    alone = fit_all(data, [([c], params, dict(start=current.values)) for c in chosen])
    by_name = dict(zip(chosen, alone))
    if alone[1].bic < alone[0].bic:
        chosen = [chosen[1], chosen[0]]
        fits = [alone[1], current]
        steps.append({"step": "order", "first": chosen[0], "delta_bic": float(alone[0].bic - alone[1].bic)})
        ev.append(f"With the drum both share, {chosen[0]} alone explains more than {chosen[1]} alone (BIC lower by "
                  f"{alone[0].bic - alone[1].bic:.1f}): it is the first of the two.")
    first = fits[0] if fits and fits[0] is not None and fits[0].effects == chosen[:1] else by_name[chosen[0]]
    ahead = reform_job(params, chosen[0], first) if names else None      # beside_reformed's first fit, ahead
    own = beyond_reform(data, params, chosen[:1], current, current, refree, also=[ahead] if ahead else ())
    if own is None:             # the first has no flexible form (per-test offsets): is it beyond the second re-formed?
        back = _offsets_beyond_reform(data, params, chosen, current, by_name[chosen[1]], refree, nq)
        if back is None or back["passes"]:
            return chosen, current, struct, fits
        return _second_alone(chosen, back, by_name, nq, nt, steps, ev, current)
    reform = own.pop("also")
    if own["passes"] and reform and offsets_absorbed(chosen[1], reform[0], nq):
        own = dict(own, passes=False, offsets=True)
    if own["passes"] and departures:
        wider = beyond_reform(data, params, chosen[:1], current, current, refree + departures)
        if wider is not None and not wider["passes"]:
            wider.pop("also", None)
            own, refree = dict(wider, departures=list(departures)), refree + departures
    steps.append({"step": "own evidence", "effect": chosen[1], "kept": own["passes"], "beyond_reform": own,
                  **({"offsets_pair": current} if own.get("offsets") else {})})
    if own["passes"]:
        back = beyond_reform(data, params, chosen[1:], current, current, refree)
        if back is not None and not back["passes"]:     # the first is not beyond the second re-formed: a partner too
            return _second_alone(chosen, back, by_name, nq, nt, steps, ev, current,
                                 f"{chosen[1]} predicts held-out tests better beside {chosen[0]} than {chosen[0]} "
                                 f"re-formed, but ")
        term = beyond_second_term(data, params, chosen[0], chosen[1], current)
        if term is None or term["passes"]:
            return chosen, current, struct, fits
        own = dict(own, passes=False, second_term=term)     # a second term of the first's own law says as much
        steps[-1].update(kept=False, beyond_reform=own)
    other = beside_reformed(data, params, chosen[0], first, names, reform=reform[0] if reform else None,
                            departures=refree + departures) if names else None
    if other is not None and not _beside_departures(data, params, chosen[0], first, other[0], other[1],
                                                    refree + departures):
        other = None
    if other is not None:
        name, pair, dbic, pref, reform = other
        steps.append({"step": "beside the re-formed first", "effect": name, "delta_bic": dbic, "heldout": pref,
                      "first": chosen[0], "reform": reform})
        ev.append(f"{chosen[1]} is not beyond {chosen[0]} re-formed, but beside {chosen[0]} re-formed (its hook as a "
                  f"linear spline) {name} lowers BIC by {-dbic:.1f} and predicts held-out tests better (log score "
                  f"{pref['heldout_elpd']:+.1f} ± {pref['heldout_se']:.1f}, better in {pref['better_tests']} of "
                  f"{pref['tests']} tests{refit_words(pref)}): a mis-formed {chosen[0]} hid it; {name} is named on "
                  f"that evidence.")
        return [chosen[0], name], pair, structure(pair, nq, nt), [first, pair]
    if "second_term" in own:
        t = own["second_term"]
        ev.append(f"{chosen[1]} predicts held-out tests better beside {chosen[0]} than {chosen[0]} re-formed, but adds "
                  f"too little beside {chosen[0]} with a second term of its own law ({t['term']}: BIC "
                  f"{t['delta_bic']:+.1f}, held-out log score {t['heldout_elpd']:+.1f} ± {t['heldout_se']:.1f}, better "
                  f"in {t['better_tests']} of {t['tests']} tests) — it only wrote {chosen[0]}'s law with one time "
                  f"constant more; not named.")
        return chosen[:1], first, structure(first, nq, nt), [first]
    score = (f"log score {own['heldout_elpd']:+.1f} ± {own['heldout_se']:.1f}, better in {own['better_tests']} of "
             f"{own['tests']} tests{refit_words(own)}")
    ev.append(f"{chosen[1]} lowers BIC and predicts held-out tests better beside {chosen[0]}, but "
              + (f"{chosen[0]} re-formed (its hook as a linear spline) leaves no per-test offsets for it to take (the "
                 f"held-out {score} fits each held-out test's own offsets and cannot fault them)"
                 if own.get("offsets") else
                 f"not beyond {chosen[0]} re-formed (its hook as a linear spline, no second effect"
                 + (f"; {', '.join(refree)} freed in both" if refree else "") + f"): held-out {score}")
              + " — a partner that only absorbs the first effect's form mismatch or a departure of the drum; not named.")
    return chosen[:1], first, structure(first, nq, nt), [first]


def _offsets_beyond_reform(data, params, chosen, current: FitResult, second: FitResult, refree, nq):
    """For a pair whose first effect has no flexible form: :func:`~rollaway.identify.beyond.beyond_reform` of the
    first beside the second re-formed, and where the first has per-test parameters (offsets, whose held-out score
    fits each held-out test's own values as it does T_0, so it cannot fault them) it passes only where the residual
    of the second re-formed is per-test offsets and nothing else (:func:`~rollaway.identify.selection.per_test_signature`,
    the forward step's gate): where the tests are short a temperature law's form mismatch is a level error test by
    test, which offsets take up.  None where the second has no flexible form either."""
    back = beyond_reform(data, params, chosen[1:], current, current, refree)
    if back is None or not back["passes"]:
        return back
    job = reform_job(params, chosen[1], second)
    reform = None if job is None else calibrate(data, *job[:2], **job[2])
    return dict(back, passes=False, offsets=True) if offsets_absorbed(chosen[0], reform, nq) else back


def _second_alone(chosen, back: dict, by_name: dict, nq, nt, steps: list, ev: list, pair: FitResult, lead: str = ""):
    """:func:`own_evidence`'s answer where the first of *chosen* does not predict held-out tests better than the
    second re-formed (*back*, :func:`~rollaway.identify.beyond.beyond_reform`): the first only absorbed the second's
    form mismatch, and the second is named alone — also where the first has no flexible form of its own (per-test
    offsets, which take up a temperature law's misfit test by test where the tests are short)."""
    back.pop("also", None)
    steps.append({"step": "own evidence of the first", "effect": chosen[0], "kept": False, "beyond_reform": back,
                  **({"offsets_pair": pair} if back.get("offsets") else {})})
    second = by_name[chosen[1]]
    score = (f"log score {back['heldout_elpd']:+.1f} ± {back['heldout_se']:.1f}, better in "
             f"{back['better_tests']} of {back['tests']} tests{refit_words(back)}")
    why = (f"{chosen[1]} re-formed (its hook as a linear spline, no second effect) leaves no per-test offsets for "
           f"{chosen[0]} to take (the held-out score, {score}, fits each held-out test's own offsets and cannot fault "
           f"them)" if back.get("offsets") else
           f"{chosen[0]} does not predict held-out tests better beside {chosen[1]} re-formed (its hook as a linear "
           f"spline, no second effect): held-out {score}")
    ev.append(f"{lead}{why} — {chosen[0]} only absorbed {chosen[1]}'s form mismatch; {chosen[1]} is named alone.")
    return [chosen[1]], second, structure(second, nq, nt), [second]


def stood_for(steps: list[dict]) -> tuple[str, ...]:
    """The calibratable brake parameters a dropped second effect stood in for: the departures of the drum that
    :func:`own_evidence` freed when it found the pair no better than the first re-formed (``()`` when it did
    not need them).  The gap is left out: it stays held, the logs cannot tell it from μ_d."""
    from rollaway.model.drum_parameters import FREE_PARAMETERS
    own = next((s["beyond_reform"] for s in steps[::-1] if s.get("step") == "own evidence"), {})
    return tuple(n for n in own.get("departures") or () if FREE_PARAMETERS[n].automatic)


def beside_partial(data, params, first: str, first_fit: FitResult, names, departures=()):
    """A second effect beside a first whose shape-free form clears the structure (a verdict of form "partial"):
    :func:`beside_reformed` — the structure tests miss at p < 0.001 what BIC and the held-out tests still show (a
    radiating drum's temperature law beside a creep the catalogue writes wrongly) — and, where it finds one, asked again with the drum's *departures* freed in both fits it compares
    (:meth:`rollaway.identify.drum.DrumCalibration.departures`: a radial contraction can stand in for a thicker
    lining beside a spline).  Returns :func:`beside_reformed`'s answer or None."""
    found = beside_reformed(data, params, first, first_fit, names, departures=departures)
    if found is None or not _beside_departures(data, params, first, first_fit, found[0], found[1], departures):
        return None
    return found


def _beside_departures(data, params, first: str, first_fit: FitResult, name: str, pair: FitResult,
                       departures=()) -> bool:
    """Does *name*, found beside *first* re-formed (:func:`beside_reformed`), still lower BIC below
    :data:`BIC_THRESHOLD` and predict held-out tests better with the drum's *departures* freed in both fits
    (those *params* holds, but not a parameter of *name* itself: the gap beside an installation gap)?  A gap or a
    radial contraction can stand in for a lining of another thickness, a friction change beside a spline for the
    arm ratio the bare drum could not identify.  True where nothing is left to free or a fit fails."""
    jobs = _departure_jobs(params, first, first_fit, name, pair, departures)
    if not jobs:
        return True
    reform, both = fit_all(data, jobs)
    if reform.jacobian is None or both.jacobian is None:
        return True
    return both.bic - reform.bic < BIC_THRESHOLD and heldout_preference(data, both, reform)["passes"]


def _departure_jobs(params, first: str, first_fit: FitResult, name: str, pair: FitResult, departures=()) -> list:
    """:func:`_beside_departures`'s two fit jobs ``(effects, params, kwargs)`` — *first* re-formed alone and beside
    *name*, with the drum's *departures* freed — or ``[]`` where nothing is left to free or *first* has no
    flexible form."""
    from rollaway.identify.model import DrumPlan
    from rollaway.model.drum_parameters import FREE_PARAMETERS
    wider = tuple(n for n in departures if n not in getattr(params, "free", ()) and FREE_PARAMETERS[n].effect != name)
    job = reform_job(params, first, first_fit) if wider else None
    if job is None:
        return []
    plan = DrumPlan(params.params, tuple(params.free) + tuple(dict.fromkeys(wider)))
    return [([job[0][0]], plan, dict(start=first_fit.values, max_iterations=REFORM_ITERATIONS)),
            ([job[0][0], name], plan, dict(start=pair.values, max_iterations=REFORM_ITERATIONS))]


def beside_reformed(data, params, first: str, first_fit: FitResult, names, reform=None, departures=()):
    """:func:`_beside_reformed`, asked once per diagnosis for the same data, first effect at the same values (the
    partner test and the partial verdict ask it of the same fit), candidates, brake parameters and departures: the
    answer is kept (:func:`rollaway.identify.memo.remember`), its catalogue pair returned as a copy."""
    from rollaway.identify import memo
    k = memo.key(data, [first, *names], params, {"start": first_fit.values})
    tag = "beside_reformed " + " ".join(departures)
    got = memo.recall(tag, k)
    if got is memo.ABSENT:
        got = _beside_reformed(data, params, first, first_fit, names, reform, departures)
        memo.remember(tag, k, got)
    return None if got is None else (got[0], memo.copy_fit(got[1]), got[2], dict(got[3]), memo.copy_fit(got[4]))


def _beside_reformed(data, params, first: str, first_fit: FitResult, names, reform=None, departures=()):
    """A second effect on the evidence it has beside the first effect *first* re-formed (its hook as a linear
    spline, :func:`rollaway.identify.shape.flexible_effect`), for when the first's catalogue form is wrong: then
    the pair keeps the first's misfit and the first re-formed absorbs part of the second, and a forward step on
    the catalogue form can pick the wrong second effect.
    Each effect of *names* is screened beside the re-formed first (:data:`SCREEN_ITERATIONS`, the spline held where
    the re-formed first put it: its effect parameters and the brake parameters fitted); the best by BIC
    is refitted with everything free and must lower BIC below :data:`BIC_THRESHOLD` and predict held-out tests better by
    :func:`~rollaway.identify.beyond.beyond_reform`'s rule.  *reform*: that re-formed first, when already fitted (:func:`~rollaway.identify.shape.reform_job`).
    Sought whether or not the re-formed first leaves structure.  *departures*: the brake parameters the caller
    frees next in :func:`_beside_departures`; its fits run beside the second term's (kept by
    :mod:`rollaway.identify.memo`).
    Returns (name, the catalogue pair's fit, ΔBIC, held-out comparison, the re-formed first's fit) or None."""
    from rollaway.effects import get_effect
    job = reform_job(params, first, first_fit)
    if job is None:
        return None
    flex = job[0][0]
    if reform is None:
        reform = calibrate(data, *job[:2], **job[2])
    if reform.jacobian is None:
        return None
    others = [c for c in names if c != first and not get_effect(c).per_test_parameters()]
    jobs = [([flex, c], params, dict(start=reform.values, free=_all_but(params, flex, c), statistics=False,
                                     max_iterations=SCREEN_ITERATIONS)) for c in others]
    screened = list(zip(fit_all(data, jobs), others))
    if not screened:
        return None
    screen, name = min(screened, key=lambda t: t[0].bic)
    both = calibrate(data, [flex, name], params, start=screen.values,       # on from where its screen stopped,
                     max_iterations=REFORM_ITERATIONS)                      # with the re-formed first's budget
    if both.jacobian is None or both.bic - reform.bic >= BIC_THRESHOLD:
        return None
    alone = reform_job(params, name, both)         # asked next where the comparison passes: fitted beside it
    pair_job = ([first, name], params, dict(start=both.values))     # ... and the catalogue pair after it
    pref = heldout_preference(data, both, reform, also=[j for j in (alone, pair_job) if j])
    if not pref["passes"] or not _beyond_own_reform(data, params, name, both):
        return None
    pair = calibrate(data, *pair_job[:2], **pair_job[2])
    term = beyond_second_term(data, params, first, name, pair, give_up=True,
                              also=_departure_jobs(params, first, first_fit, name, pair, departures))
    if term is not None and not term["passes"]:
        return None
    return name, pair, float(both.bic - reform.bic), pref, reform


def _all_but(params, flex, name: str) -> list[str]:
    """The parameters of the effects *flex* and *name* on the drum of *params* that a screen fits: all but *flex*'s
    own (its spline ordinates stay where the re-formed first put them)."""
    from rollaway.identify.model import BenchModel
    return [n for n in BenchModel(params, [flex, name]).parameter_names() if not n.startswith(flex.name + ".")]


def _beyond_own_reform(data, params, name: str, both: FitResult) -> bool:
    """The pair *both* (the first re-formed beside *name*) also predicts held-out tests better than *name* re-formed
    alone: else one mis-formed effect, *name*, is the story and the first was its stand-in."""
    job = reform_job(params, name, both)
    if job is None:
        return True
    alone = calibrate(data, job[0], job[1], **job[2])
    return alone.jacobian is None or heldout_preference(data, both, alone)["passes"]


def unsure_second(steps: list[dict]):
    """A rule for :func:`rollaway.identify.diagnose.diagnose`, called as the twin rules are
    (:mod:`rollaway.identify.twins`): where a verdict of two effects named its second beside the first re-formed
    (:func:`own_evidence`'s step "beside the re-formed first", or "beside the partial first") on a held-out gain
    within :data:`~rollaway.identify.ambiguity.HELDOUT_SE` standard errors of the paired difference, the first
    re-formed alone (its hook as a linear spline) is named beside the verdict while fewer than
    :data:`~rollaway.identify.ambiguity.MAX_RIVALS` are: the second passed the naming rule, but the held-out tests
    do not rule out that one mis-formed effect is all there is (a sigmoid modulus drop beside an installation gap
    named a friction change at 1.4 standard errors, two-effect campaign 339 of
    ``tests/uncertainty/band_questions.py``).  Its fit in the bands is the re-formed first.  Only a second found
    beside the re-formed first: it is the best of every catalogue effect screened there, a choice its held-out
    score does not count, and the first's catalogue form was already found wrong (on the 360 two-effect band
    campaigns 0–359, 1 of 38 such seconds was false, against 1 of 81 named by the forward steps, that one flagged)."""
    def rival(data, params, verdict, first_cands, tested: dict, noise_torque_Nm: float, inflation: float,
              rivalry: list[dict]) -> list[dict]:
        from rollaway.identify.ambiguity import HELDOUT_SE, MAX_RIVALS
        from rollaway.identify.separating_test import tell_apart
        names = [e.name for e in verdict.model.effects]
        step = next((s for s in steps if s.get("step") in ("beside the re-formed first", "beside the partial first")
                     and s.get("reform") is not None and sorted(names) == sorted([s["first"], s["effect"]])), None)
        if step is None or len(rivalry) >= MAX_RIVALS or any(a["effects"] == [step["first"]] for a in rivalry):
            return rivalry
        pref, reform = step["heldout"], step["reform"]
        if reform.jacobian is None or not pref["heldout_elpd"] < HELDOUT_SE * pref["heldout_se"]:
            return rivalry
        return rivalry + [{
            "kind": "rival", "form": "shape-free", "effects": [step["first"]], "fit": reform,
            "delta_bic": float(-step["delta_bic"]), "heldout_elpd": -float(pref["heldout_elpd"]),
            "heldout_se": float(pref["heldout_se"]),
            "why": (f"{step['effect']} is named beside {step['first']} re-formed on a held-out gain within "
                    f"{HELDOUT_SE:g} standard errors (log score {pref['heldout_elpd']:+.1f} ± {pref['heldout_se']:.1f}, "
                    f"better in {pref['better_tests']} of {pref['tests']} tests): {step['first']} alone, its hook as "
                    f"a linear spline, is not ruled out"),
            "tell_apart": tell_apart(verdict, reform, tested, noise_torque_Nm)}]
    return rival
