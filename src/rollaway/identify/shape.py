"""The shape the data want: a flexible version of an effect's hook, drawn against the catalogue's form.

When a catalogue effect explains most of the misfit but leaves structure, its *physics* (which
quantity it changes) is probably right and its *form* wrong.  :func:`flexible_effect` builds an
effect that changes the same quantity by a factor ``1 + g(x)``, g a linear spline in the
effect's covariate x (time, lining or drum temperature, hand force) with knots over the
covariate's range (:func:`spline_knots`) and g = 0 at the lowest knot — no functional form assumed.  Fitting it
shows what the data want; :func:`shape_curves` evaluates both factors on a grid for a figure.
"""
from __future__ import annotations

import numpy as np

from rollaway.effects import get_effect
from rollaway.effects.base import Effect
from rollaway.effects.shape_free import (  # noqa: F401  (read from here too)
    HOOK_COVARIATE, TEMPERATURE_HOOKS, is_shape_free, shape_hook, spline_effect, spline_factor)

KNOTS = 8                     # spline segments (equal widths over the covariate's range)
PREDICTING_SEGMENT_SAMPLES = 2   # a shape-free form that competes in the bands (form and channel rivals) has no knot
                             # segment of one sample: its slope there passes through that sample, between samples
                             # of other tests, and holding that one test out cannot check it (the selection's
                             # re-formed first keeps every segment: the more flexible, the harder for a partner)
COVARIATE_UNITS = {"time_s": "s", "lining_temp_C": "°C", "drum_temp_C": "°C", "hand_force_N": "N"}


def spline_knots(x: np.ndarray, covariate: str, least: int = 1) -> np.ndarray:
    """At most KNOTS + 1 knots over the covariate's range: equally spaced, except in time, where they are
    spaced geometrically from the first sample after the start (at least 1 % of the span): creep and
    relaxation change fastest at the start of a hold, and equal 450 s segments of an hour cannot follow a
    logarithmic loss.  A time knot that would leave a segment without samples is skipped.  *least*: a segment of
    another covariate holding fewer samples is merged with its sparser neighbour (:func:`_filled`)."""
    lo, hi = float(np.min(x)), float(np.max(x))
    if not covariate == "time_s" or hi <= lo:
        knots = np.unique(np.linspace(lo, hi, KNOTS + 1))
        return _filled(np.asarray(x, float), knots, least) if least > 1 and knots.size > 3 else knots
    xs = np.unique(x)
    knots = [lo]
    first = max(float(xs[1] - lo) if xs.size > 1 else 0.0, 0.01 * (hi - lo))
    for k in lo + np.geomspace(first, hi - lo, KNOTS):
        if np.any((xs > knots[-1]) & (xs <= k)):        # every segment holds samples (else its slope is free)
            knots.append(float(k))
    knots[-1] = hi
    return np.unique(knots)


def _filled(x: np.ndarray, knots: np.ndarray, least: int) -> np.ndarray:
    """*knots* less those whose segments hold fewer than *least* samples of *x*: the sparsest segment is merged
    with its sparser neighbour until every one holds enough, or two segments are left."""
    knots = list(knots)
    while len(knots) > 3:
        counts = np.histogram(x, bins=knots)[0]
        j = int(np.argmin(counts))
        if counts[j] >= least:
            break
        if j == 0 or (j < len(counts) - 1 and counts[j + 1] <= counts[j - 1]):
            del knots[j + 1]         # merged with the segment above
        else:
            del knots[j]             # merged with the segment below
    return np.asarray(knots)


def flexible_effect(effect: Effect, covariate_values: np.ndarray, least: int = 1) -> type[Effect] | None:
    """*effect*'s shape-free version (:func:`rollaway.effects.shape_free.spline_effect`) with knots over the
    covariate's values (:func:`spline_knots`, *least* samples per segment at least); None when it has none or the
    values span fewer than two segments."""
    found = shape_hook(effect)
    if found is None:
        return None
    knots = spline_knots(np.asarray(covariate_values, float), found[1], least)
    return spline_effect(effect, knots) if len(knots) >= 3 else None


def _form_jobs(fit, params, least: int = PREDICTING_SEGMENT_SAMPLES) -> list:
    effects = list(fit.model.effects)
    jobs = []
    for k, eff in enumerate(effects):
        found = shape_hook(eff)
        flex = (None if found is None or is_shape_free(eff) else
                flexible_effect(eff, covariate_of(fit, found[1]), least))
        if flex is not None:
            jobs.append((effects[:k] + [flex] + effects[k + 1:], params, dict(start=fit.values)))
    return jobs


def _channel_jobs(fit, candidates, params) -> list:
    effects = list(fit.model.effects)
    names = {e.name for e in effects}
    jobs = []
    for k, eff in enumerate(effects):
        found = None if is_shape_free(eff) else shape_hook(eff)
        if found is None:
            continue
        for c in candidates:
            hook = shape_hook(get_effect(c.effect))
            if c.effect in names or hook is None or hook[1] != found[1] or hook[0] == found[0]:
                continue
            cls = flexible_effect(get_effect(c.effect), covariate_of(fit, hook[1]), PREDICTING_SEGMENT_SAMPLES)
            if cls is not None:
                jobs.append((effects[:k] + [cls] + effects[k + 1:], params, dict(start=fit.values)))
    return jobs


def _fitted(data, jobs) -> list:
    from rollaway.identify.workers import fit_all
    return [f for f in fit_all(data, jobs) if f.jacobian is not None] if jobs else []


def form_rivals(data, fits, params) -> list:
    """Each fit of *fits* (one fit or several) with each of its effects in turn replaced by its shape-free version
    (:func:`flexible_effect`), refitted with the brake parameters *params* frees (side by side on the machine's
    cores): the same physics in every form the data allow.  A catalogue form the residual cannot fault may still
    be wrong where the bench did not look (a creep law that flattens too early leaves its later loss to the
    cooling law, and the split of μ_d against the eq. (24) slope with it); these fits let the bands weigh that form
    against the catalogue's by held-out prediction."""
    return _fitted(data, [j for f in (fits if isinstance(fits, (list, tuple)) else [fits]) for j in _form_jobs(f, params)])


SHAPE_TOP = 4                 # step-1 candidates fitted shape-free where no catalogue form clears the structure


def candidate_shapes(data, candidates, params, nq, nt, top: int = SHAPE_TOP) -> dict:
    """The best *top* step-1 *candidates* that lowered BIC against the drum, each fitted alone in its shape-free
    form (:func:`flexible_effect`, brake parameters of *params*, side by side on the machine's cores):
    ``{effect: (fit, clears)}``, *clears* true when that fit's residual holds no structure
    (:func:`rollaway.identify.selection.structure` with the channel noises *nq*, *nt*).  Where no catalogue form
    clears the structure, the catalogue's ranking by BIC measures how well each *form* bends to the data, not
    which quantity changes: a friction that fades above a temperature, written linear, can lose to a three-parameter
    stiffness law that fits neither; its shape-free form clears the structure and says which quantity it is.
    A form this diagnosis has fitted before under the same plan (the first effect re-formed, to weigh a second
    effect) starts from where that fit ended (:func:`rollaway.identify.memo.same_model`): the same model and
    optimum, a quarter of the evaluations."""
    from rollaway.identify.selection import structure
    pool = [c for c in sorted(candidates, key=lambda c: c.delta_bic)
            if c.delta_bic < 0 and c.fit.jacobian is not None][:top]
    jobs = [(c.effect, job) for c in pool for job in _form_jobs(c.fit, params, 1)]
    from rollaway.identify import memo
    for _, job in jobs:           # a form fitted before (the re-formed first effect) starts from where it ended
        kept = memo.same_model(data, job[0], job[1])
        if kept is not None:
            job[2]["start"] = kept.values
    from rollaway.identify.workers import fit_all
    done = fit_all(data, [j for _, j in jobs]) if jobs else []
    return {e: (f, not structure(f, nq, nt)["structured"]) for (e, _), f in zip(jobs, done) if f.jacobian is not None}


def pair_shapes(data, shapes: dict, params, nq, nt) -> list:
    """Pairs of the shape-free fits *shapes* (:func:`candidate_shapes`) along different covariates (a function of
    temperature beside one of time), each fitted together (brake parameters of *params*, side by side on the
    machine's cores), that clear the structure (:func:`rollaway.identify.selection.structure` with the channel
    noises *nq*, *nt*) and lower BIC below every one of them alone: where no catalogue form clears the
    structure, two effects in forms the catalogue lacks may have changed two quantities, which no one spline
    follows beyond the tested conditions.  Two splines along one covariate are left out: they trade one
    quantity for the other within the tested conditions (held-out predictions of such pairs run away), and so is
    a spline in hand force: its knots are the tested forces, each pinned by the test the other way at that force
    whichever test is held out, so no held-out prediction checks it (beside a friction spline, one drew bands 20 %
    from the truth inside the tested range).  A pair is abandoned once it cannot come below the best of them alone
    (``give_up_bic``, :func:`rollaway.identify.solver.futile`): it would not be kept, and two splines along a flat
    valley of the least-squares problem can crawl for hundreds of iterations first (0.1–2.7 s for one pair of a
    10 Hz log, as the last bits of its start fell)."""
    from rollaway.identify.selection import structure
    from rollaway.identify.workers import fit_all
    solo = {e: f for e, (f, _) in shapes.items() if f.jacobian is not None}
    free = {e: next(x for x in f.model.effects if is_shape_free(x)) for e, f in solo.items()}
    hook = {e: shape_hook(get_effect(e)) for e in free}          # the catalogue effect's: the spline's own
    names = [e for e in solo if hook[e][1] != "hand_force_N"]
    best = min((f.bic for f in solo.values()), default=np.inf)
    bar = {} if not np.isfinite(best) else {"give_up_bic": float(best)}      # above it a pair is not kept
    jobs = [([type(free[a]), type(free[b])], params, dict(start=solo[a].values, **bar)) for i, a in enumerate(names)
            for b in names[i + 1:] if hook[a][1] != hook[b][1] and hook[a][0] != hook[b][0]]
    done = fit_all(data, jobs) if jobs else []
    return [f for f in done if f.jacobian is not None and f.bic < best and not structure(f, nq, nt)["structured"]]


def channel_rivals(data, fit, candidates, params) -> list:
    """*fit*'s effect set with one effect in turn replaced by the shape-free version of another effect that changes
    another quantity along the same covariate (a friction and a lining modulus, both functions of the lining
    temperature; a cable relaxation and a lining creep, both of time), for each step-1 *candidate* — whether or not
    its catalogue form lowered BIC against the drum: where no catalogue form fits, a misfit fit can bend the
    temperature channel to ease the torque and score worse than the drum it contains (a friction fade on one
    direction), and its quantity is still the verdict's rival — refitted with the brake parameters *params* frees.  Where the verdict's catalogue form leaves
    structure, the data say that *something* changes along that covariate, not through which quantity; a spline in
    the verdict's own quantity then fits the tested conditions whichever it is, and errs only where the quantities
    part (the other direction, another hand force).  These fits put the other quantity's spline into the bands,
    weighed by its held-out prediction."""
    return _fitted(data, _channel_jobs(fit, candidates, params))


def shape_rivals(data, fit, params, candidates=()) -> tuple[list, list]:
    """(:func:`form_rivals`, :func:`channel_rivals` of *candidates*) of *fit*, fitted in one batch on the machine's
    cores."""
    from rollaway.identify.workers import fit_all
    forms, channels = _form_jobs(fit, params), _channel_jobs(fit, candidates, params)
    done = fit_all(data, forms + channels) if forms or channels else []
    ok = [f.jacobian is not None for f in done]
    return ([f for f, g in zip(done[:len(forms)], ok) if g],
            [f for f, g in zip(done[len(forms):], ok[len(forms):]) if g])


OTHER_FORM_BIC = 2.0          # below "positive" evidence (Kass & Raftery 1995: 2–6): two shapes this close are a tie


def other_form_rivals(data, fit, own_shape, candidates, params) -> list[dict]:
    """Effects that a one-effect verdict *fit* (its catalogue form explains the data) does not rule out once their
    form is freed too: a step-1 candidate whose physics the catalogue writes in a form the data do not follow (a
    friction rising with the square of the temperature, written linear) can lose to another effect in its
    catalogue form and still be the better explanation.  Each step-1 candidate whose shape-free form has another
    covariate than the verdict's (a function of temperature against one of time: two functions of time are the
    same shape, a test of physics they are not) is fitted shape-free (:func:`flexible_effect`, no knot segment of
    fewer than :data:`PREDICTING_SEGMENT_SAMPLES` samples, as the verdict's own, since it competes in the bands;
    brake parameters of *params*), whatever its catalogue form scored against the drum (a friction that fades above
    a temperature, written linear, scored +2.4 on two-effect campaign 194 of
    ``tests/uncertainty/band_questions.py`` while its spline fits within 2.3 of the shoe thermal lag named).  It is
    not ruled out when its BIC is
    - no more than :data:`OTHER_FORM_BIC` above that of the verdict's own shape-free form *own_shape* (freedom for
      freedom; lower, or a tie: where time and temperature fall together, a function of either fits, and the
      verdict's catalogue form fitting only says the catalogue wrote that one well),
    - less than the selection's bar (10, "very strong") above the verdict's catalogue form *fit*, the difference
      divided by *fit*'s residual variance inflation as :func:`~rollaway.identify.ambiguity.rivals` does (a spline
      the verdict's form beats that clearly is ruled out by it, however poorly the verdict's own spline bends: a
      radiating drum's law written as a spline in time lost to a spline in hand force, 57–190 behind the law),
    and the held-out prediction does not prefer the verdict's shape-free form
    (:func:`rollaway.identify.ambiguity.not_ruled_out`).  Best first: ``{"kind": "rival", "form": "shape-free",
    "effects", "delta_bic" (against *fit*), "heldout_elpd", "heldout_se" (against *fit*), "why", "fit"}`` (*fit*
    the shape-free one)."""
    from rollaway.identify.ambiguity import heldout_difference, not_ruled_out
    from rollaway.identify.intervals import ess_inflation
    from rollaway.identify.selection import BIC_THRESHOLD
    from rollaway.identify.workers import fit_all
    found = shape_hook(fit.model.effects[0])
    if own_shape is None or own_shape.jacobian is None or found is None:
        return []
    verdict = fit.effects[0]
    inflation = max(1.0, *ess_inflation(fit).values())
    flex = []
    for c in candidates:
        eff = get_effect(c.effect)
        other = shape_hook(eff)
        if c.effect != verdict and other is not None and other[1] != found[1]:
            cls = flexible_effect(eff, covariate_of(fit, other[1]), PREDICTING_SEGMENT_SAMPLES)
            if cls is not None:
                flex.append((c.effect, cls))
    out = []
    shapes = fit_all(data, [([cls], params, dict(start=fit.values)) for _, cls in flex])
    for (name, cls), shaped in zip(flex, shapes):
        if (shaped.jacobian is None or shaped.bic > own_shape.bic + OTHER_FORM_BIC
                or (shaped.bic - fit.bic) / inflation >= -BIC_THRESHOLD or not not_ruled_out(own_shape, shaped)):
            continue
        elpd, se = heldout_difference(fit, shaped)
        out.append({"kind": "rival", "form": "shape-free", "effects": [name], "delta_bic": float(shaped.bic - fit.bic),
                    "heldout_elpd": elpd, "heldout_se": se, "fit": shaped,
                    "why": (f"{name} in a shape-free form (a spline in {cls.covariate}) fits "
                            + (f"better than {verdict} in one (BIC lower by {own_shape.bic - shaped.bic:.1f})"
                               if shaped.bic < own_shape.bic else
                               f"as well as {verdict} in one (BIC within {OTHER_FORM_BIC:g}: "
                               f"{shaped.bic - own_shape.bic:+.1f})")
                            + f" and the held-out tests do not prefer {verdict}'s (Δ log score against {verdict} "
                            f"{elpd:+.1f} ± {se:.1f}): its catalogue form does not fit, another form of it would")})
    return sorted(out, key=lambda a: a["delta_bic"])


def channel_alternatives(fit, forms, channels, inflation: float = 1.0) -> list[dict]:
    """Other quantities a verdict whose catalogue form leaves structure (*fit*) does not rule out: each channel
    rival (:func:`channel_rivals`: an effect of *fit* exchanged for the spline of another effect along the same
    covariate) compared, freedom for freedom, with the verdict's own spline (its form rival in *forms*, the same
    knots): named when their BIC differs by less than :data:`~rollaway.identify.ambiguity.INDISTINGUISHABLE_BIC`
    (divided by the residual variance *inflation*, as :func:`~rollaway.identify.ambiguity.rivals`) and the
    held-out prediction does not prefer the verdict's spline beyond
    :func:`~rollaway.identify.ambiguity.preference_margin`.  A friction and a lining modulus falling with the lining
    temperature differ only through the self-energising factor (the downhill/uphill ratio, eqs. (18)–(21)): on one
    direction or few forces a spline in either fits.  Best first: ``{"kind": "rival", "form": "shape-free",
    "channel": True, "effects", "delta_bic" (against the verdict's spline), "heldout_elpd", "heldout_se", "why",
    "fit"}``; in the bands such a fit keeps its held-out weight beside the verdict's own spline (no BIC floor: the
    catalogue form it would be weighed against is the one the structure faults)."""
    from rollaway.identify.ambiguity import INDISTINGUISHABLE_BIC, heldout_difference, preference_margin
    names = [e.name for e in fit.model.effects]
    own = {}
    for f in forms:                        # the verdict with its k-th effect shape-free, by k
        k = [i for i, e in enumerate(f.model.effects) if e.name != names[i]]
        if len(f.model.effects) == len(names) and len(k) == 1:
            own[k[0]] = f
    out = []
    for c in channels:
        k = [i for i, e in enumerate(c.model.effects) if e.name != names[i]] if len(c.model.effects) == len(names) else []
        if len(k) != 1 or k[0] not in own:
            continue
        mine, other = own[k[0]], getattr(c.model.effects[k[0]], "base", c.model.effects[k[0]].name)
        dbic = (c.bic - mine.bic) / max(inflation, 1.0)
        elpd, se = heldout_difference(mine, c)
        margin = preference_margin(mine, se)
        if dbic >= INDISTINGUISHABLE_BIC or elpd <= -margin:
            continue
        effects = names[:k[0]] + [other] + names[k[0] + 1:]
        out.append({"kind": "rival", "form": "shape-free", "channel": True, "effects": effects,
                    "delta_bic": float(dbic), "heldout_elpd": elpd, "heldout_se": se, "fit": c,
                    "why": (f"with a spline in {c.model.effects[k[0]].covariate} in place of {names[k[0]]}'s form, "
                            f"{other} fits {'better than' if dbic <= -INDISTINGUISHABLE_BIC else 'as well as'} "
                            f"{names[k[0]]} (BIC {dbic:+.1f}) and the held-out prediction "
                            f"{'prefers ' + other if elpd > margin else 'does not prefer either'} "
                            f"(Δ log score {elpd:+.1f} ± {se:.1f}): the data say that something "
                            f"changes with {c.model.effects[k[0]].covariate}, not which quantity")})
    return sorted(out, key=lambda a: a["delta_bic"])


def loose_form(fit, forms, threshold: float):
    """The shape-free form of a one-effect *fit* among *forms* (:func:`form_rivals`) when it lowers BIC by more than
    *threshold* against the catalogue form, else None.  The structure tests look for what a residual does against
    time, temperature and the tests at p < 0.001; a catalogue law a little off everywhere (a creep that flattens too
    early, a modulus drop written linear that is sigmoid) can pass them and still lose by tens to its own spline,
    which costs one BIC penalty per knot segment.  Measured on the held-out campaigns of
    ``tests/identify/heldout_names.py`` (0–935): with the catalogue's own form hidden the spline never gained more
    than 2.8; with another form hidden it gained more than 10 in 46 of 78 "exact" verdicts."""
    if len(fit.model.effects) != 1:
        return None
    own = next((f for f in forms if len(f.effects) == 1 and f.jacobian is not None
                and is_shape_free(f.model.effects[0])), None)
    return own if own is not None and own.bic < fit.bic - threshold else None


def covariate_of(fit, name: str) -> np.ndarray:
    """The covariate at every sample of a fit (lining temperature from the fitted model)."""
    if name == "time_s":
        return fit.data.time_s
    if name == "hand_force_N":
        return fit.data.hand_force_N
    if name == "lining_temp_C":
        return np.asarray(fit.prediction.lining_temp_C, float)
    return np.asarray(fit.prediction.drum_temp_C, float)


def shape_curves(effect: Effect, catalogue_fit, flex_fit, flex_cls, points: int = 40) -> dict:
    """Both factors against the covariate: the catalogue form (its hook's output over its input at
    the fitted values, on the samples) and the flexible spline (on a grid)."""
    hook, cov = flex_cls.hook, flex_cls.covariate
    data = catalogue_fit.data
    model = catalogue_fit.model
    values = {**model.neutral_values(), **catalogue_fit.values}     # a brake parameter held (μ_d, …) at its value
    st = model.state(data, values)
    pred = catalogue_fit.prediction
    st.drum_temp_C = np.asarray(pred.drum_temp_C, float)
    st.lining_temp_C = np.asarray(pred.lining_temp_C, float)
    st.extra["series_stiffness_N_per_m"] = np.ones_like(st.time_s)
    v = {p.name: float(values.get(f"{effect.name}.{p.name}", p.neutral)) for p in effect.parameters}
    probe = {"friction": np.full_like(st.time_s, values["mu_drum"]),
             "lining_modulus": np.full_like(st.time_s, model.params.lining_modulus_Pa),
             "gap": np.full_like(st.time_s, max(model.params.gap_m, 1e-3)),
             "displacement": np.full_like(st.time_s, 1e-4), "clamp_force": np.full_like(st.time_s, 1e3),
             "torque": np.full_like(st.time_s, 1e3)}
    x = covariate_of(catalogue_fit, cov)
    if hook in TEMPERATURE_HOOKS:
        base = np.asarray(pred.drum_temp_C, float)
        out = getattr(effect, hook)(st, base, v) if hook == "lining_temperature" else base
        cat = (out - st.ambient_C) / np.where(np.abs(base - st.ambient_C) > 1e-9, base - st.ambient_C, 1.0)
    else:
        q = probe[hook]
        cat = np.asarray(getattr(effect, hook)(st, q, v), float) / q
    order = np.argsort(x)
    grid = np.linspace(float(x.min()), float(x.max()), points)
    coef = [flex_fit.values[f"{flex_cls.name}.c{j}"] for j in range(len(flex_cls.knots) - 1)]
    flex = spline_factor(grid, flex_cls.knots, coef)
    if getattr(flex_cls, "scale", 0.0) and hook not in TEMPERATURE_HOOKS:   # an absolute change, as a factor on
        flex = 1.0 + flex_cls.scale * (flex - 1.0) / probe[hook][0]         # the probe the catalogue form is drawn at
    # put both on the same footing: factor 1 at the spline's reference (lowest covariate)
    cat_ref = float(np.interp(grid[0], x[order], np.broadcast_to(cat, x.shape)[order]))
    return {"hook": hook, "covariate": cov, "unit": COVARIATE_UNITS.get(cov, ""),
            "catalogue": {"x": x[order].tolist(), "factor": (np.broadcast_to(cat, x.shape)[order] / cat_ref).tolist()},
            "flexible": {"x": grid.tolist(), "factor": flex.tolist(), "knots": list(map(float, flex_cls.knots))}}


def reform_job(params, name: str, fit):
    """The fit job ``(effects, params, kwargs)`` of the effect *name* re-formed (its hook as a linear spline along the
    covariate *fit* predicts: :func:`flexible_effect`), started from *fit*'s values with the re-formed fits' budget
    (:data:`~rollaway.identify.selection.REFORM_ITERATIONS`), or None without a flexible form."""
    from rollaway.identify.selection import REFORM_ITERATIONS
    found = shape_hook(get_effect(name))
    flex = None if found is None else flexible_effect(get_effect(name), covariate_of(fit, found[1]))
    return None if flex is None else ([flex], params, dict(start=fit.values, max_iterations=REFORM_ITERATIONS))
