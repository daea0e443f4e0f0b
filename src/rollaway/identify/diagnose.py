"""Which physical effects is the model missing?  Calibrate, select forward, cross-validate, decide.

1. Noise of each channel without the physics (:mod:`rollaway.bench.noise`), or the
   instrument's figures; every fit weights the samples by it.  Each test's T_0 is a
   nuisance parameter of every fit (never the t = 0 reading taken as exact).
2. Forward selection: fit every remaining candidate jointly with the current model (the
   calibrated baseline first); rank by ΔBIC; candidates with ΔBIC < −10 are cross-validated
   K-fold by test (each held-out test predicted by a model calibrated on the others, only its
   own T_0 and per-test values fitted to it); the best one that predicts held-out tests
   better is added.  Stop when none passes or the residual holds no structure.
3. If structure remains, the selected effect whose catalogue form explains most of the
   baseline's excess error is refitted in a flexible form (a linear spline of its hook,
   :mod:`rollaway.identify.shape`); if that clears the structure the effect is named with
   ``form: "partial"`` and the shape the data want is returned (so is a one-effect verdict whose residual passes
   the structure tests but whose own spline lowers BIC by more than 10; both in :mod:`rollaway.identify.form`).
   Otherwise nothing is claimed: verdict ``none`` with ``remaining_structure: true`` (an effect outside the
   catalogue remains), and the closest candidates named beside it are ranked by their shape-free forms too
   (:func:`rollaway.identify.shape.candidate_shapes`): one whose shape-free form clears the structure first.
4. A second effect is named only on its own evidence (:func:`rollaway.identify.partner.own_evidence`); a
   ``none`` verdict may carry weak alternatives (:func:`rollaway.identify.ambiguity.weak_alternatives`).
5. The chosen model gets what the road bands draw: its predictive record and the competing effect sets
   (:mod:`rollaway.identify.predictive_set`).
"""
from __future__ import annotations

import numpy as np

from rollaway.effects import available_effects, get_effect
from rollaway.identify.ambiguity import (MAX_RIVALS, WEAK_BIC, alternative_words, closest, rivals, set_rivals,
                                        weak_alternatives)
from rollaway.identify.calibrate import FitResult, calibrate, evaluate
from rollaway.identify.coarse import MAX_WINDOW_S, coarsen
from rollaway.identify.drum import calibrate_drum, free_needed, predictive_covariance, recheck
from rollaway.identify.diagnosis import Diagnosis
from rollaway.identify.form import loose_shape, partial_ahead, partial_form
from rollaway.identify.fitting import single_blas_thread
from rollaway.identify.lookahead import PAIR_BIC, pair_path, reformed_alone, runner_up_path
from rollaway.identify.memo import memoised
from rollaway.identify.intervals import covariance_variances, ess_inflation, mixture_variances, restate
from rollaway.bench.measurements import Measurements
from rollaway.bench.noise import Noise, noise_estimate, sample_sigma
from rollaway.identify.detection import detection_limits, hidden_shifts, hidden_words, limits_words
from rollaway.identify.diagnose_words import (describe_residual, drum_words, no_candidate_words, noise_words,
                                             structure_words)
from rollaway.identify.offsets import offsets_rival
from rollaway.identify.partner import beside_partial, own_evidence, stood_for, unsure_second
from rollaway.identify.predictive_set import attach_predictive, interval_words
from rollaway.identify.shape import (candidate_shapes, channel_alternatives, channel_rivals, loose_form, pair_shapes,
                                     other_form_rivals, shape_rivals)
from rollaway.identify.workers import fit_all
from rollaway.identify.separating_test import tell_apart
from rollaway.identify.twins import TWINS, law_twin_rival, loss_twin_rival, partial_twin_pair, twin_rival
from rollaway.identify.selection import (BIC_THRESHOLD, SCREEN_ITERATIONS, Candidate, cv_score, eliminate, exchange,
                                         folds, forward_step, has_per_test, per_test_signature, structure)
from rollaway.uncertainty.bands import validity

MAX_EFFECTS = 2              # forward selection stops after this many effects (a third rarely survives CV)


# -- noise ----------------------------------------------------------------------------------
def channel_noise(data: Measurements, fit: FitResult, noise_torque_Nm=None, noise_temp_C=None) -> tuple[Noise, Noise]:
    """Noise of both channels: the instrument's figures where given, else the model-free estimate."""
    tau = fit.model.state(data, fit.values).cooling_time_constant_s
    nq = Noise.instrument(noise_torque_Nm) if noise_torque_Nm else noise_estimate(data, data.torque_Nm, tau, True)
    nt = Noise.instrument(noise_temp_C) if noise_temp_C else noise_estimate(data, data.drum_temp_C, tau)
    return nq, nt


# -- the decision ---------------------------------------------------------------------------
@single_blas_thread
@memoised
def diagnose(data: Measurements, params=None, effects=None, *, noise_torque_Nm: float | None = None,
             noise_temp_C: float | None = None, max_effects: int = MAX_EFFECTS, free=None, fix=()) -> Diagnosis:
    """Calibrate the user's drum, then select effects from *effects* (default: the catalogue plus
    registered plugins) for what it leaves unexplained.

    *noise_torque_Nm*, *noise_temp_C*: the instrument's noise figures (σ), used instead of the
    estimate from the data.  *free*, *fix*: brake parameters to free or hold instead of the
    automatic choice (:func:`rollaway.identify.drum.calibrate_drum`).
    """
    names = list(available_effects()) if effects is None else [get_effect(e).name for e in effects]
    data = data.subset(np.ones(len(data), bool))          # a copy that carries the noise model
    first = calibrate(data, (), params)
    nq, nt = channel_noise(data, first, noise_torque_Nm, noise_temp_C)
    data.torque_sigma_Nm = np.maximum(sample_sigma(nq, data, data.torque_Nm), 1e-9)
    data.temp_sigma_C = np.maximum(sample_sigma(nt, data, data.drum_temp_C), 1e-9)
    full, data = data, coarsen(data)                      # selection on a coarser copy of a dense log
    if data is not full:
        data.torque_sigma_Nm = np.maximum(sample_sigma(nq, data, data.torque_Nm), 1e-9)
        data.temp_sigma_C = np.maximum(sample_sigma(nt, data, data.drum_temp_C), 1e-9)
    paper = evaluate(data, (), params)
    drum = calibrate_drum(data, params, free=free, fix=fix, start=first.values)
    params = drum.plan                                     # every later fit frees what the data identify
    base, base_struct = drum.fit, structure(drum.fit, nq, nt)
    ev = [f"Noise: {noise_words('torque', nq, 'N·m', '--noise-torque-Nm')}; "
          f"{noise_words('drum temperature', nt, '°C', '--noise-temp-C')}.",
          f"Each test's start temperature T_0 is fitted with the rest (t = 0 readings are measurements, "
          f"not exact values).",
          f"Paper defaults: torque RMSE {paper.rmse_torque_Nm:.3g} N·m, temperature RMSE {paper.rmse_temp_C:.3g} °C. "
          f"Calibrated drum ({drum_words(base, drum.free)}): "
          f"{base.rmse_torque_Nm:.3g} N·m and {base.rmse_temp_C:.3g} °C; "
          + describe_residual(base, "torque") + "; " + describe_residual(base, "temperature") + "."]
    current, chosen, steps, fits, first_cands, base_cv, indist, struct = base, [], [], [], [], None, [], base_struct
    for step in range(1, max_effects + 1):
        if step == 2 and struct["structured"]:      # the partial form's fit, beside this step, if it adds nothing
            partial_ahead(data, params, base, current, chosen)
        per_test_ok = per_test_signature(current, nq)
        cands, strong, passing, cur_cv = forward_step(data, params, names, current, chosen, step, per_test_ok,
                                                      held_brake=drum.held())
        if not per_test_ok and any(has_per_test(n) for n in names if n not in chosen):
            ev.append(f"Step {step}: per-test effects ({', '.join(n for n in names if has_per_test(n))}) not "
                      f"tried: the torque residual is not a constant offset within each test (its test means "
                      f"{'do not differ' if not _test_offsets(current, nq) else 'differ, but structure remains within the tests'}).")
        if step == 1:
            first_cands, base_cv = cands, cur_cv
        up = None if passing else runner_up_path(data, params, names, first_cands, base_cv, chosen, current, cur_cv,
                                                 nq, drum.held())
        if up is not None:                                   # beside the first step's runner-up, a pair beats it
            up, (cands, strong, passing, cur_cv), was_cv = up
            steps.append({"step": "runner-up first", "replaced": chosen[0], "by": up.effect,
                          "delta_bic": float(passing[0].fit.bic - current.bic), "cv_score": passing[0].cv_score,
                          "current_cv": was_cv})
            ev.append(f"Step {step}: nothing passes beside {chosen[0]}, but beside {up.effect} (the first step's "
                      f"runner-up, {up.fit.bic - current.bic:+.1f} BIC from it) {passing[0].effect} does, and the "
                      f"pair lowers BIC below {chosen[0]} alone by {current.bic - passing[0].fit.bic:.1f} with "
                      f"held-out error {was_cv:.1f} → {passing[0].cv_score:.1f}: "
                      + (f"the pair the second step beside {chosen[0]} did not reach from its values"
                         if passing[0].effect == chosen[0] else
                         f"{chosen[0]} had taken part of the second effect's signature; {up.effect} replaces it")
                      + " (runner_up_path).")
            chosen, current, fits = [up.effect], up.fit, [up.fit]
        if not passing:
            steps.append({"step": step, "added": None, "best": cands[0].effect if cands else None,
                          "delta_bic": cands[0].delta_bic if cands else None,
                          "cv_score": strong[0].cv_score if strong else None, "current_cv": cur_cv})
            if step == 1:
                ev.append(no_candidate_words(cands, strong, cur_cv))
            break
        best = passing[0]
        chosen.append(best.effect)
        known = cands                                        # the step that added the last effect (exchange)
        struct = structure(best.fit, nq, nt)
        steps.append({"step": step, "added": best.effect, "delta_bic": best.delta_bic, "cv_score": best.cv_score,
                      "current_cv": cur_cv, "cv_better_tests": best.cv_better_tests,
                      "structured": struct["structured"]})
        ev.append(f"Step {step}: adding {best.effect} lowers BIC by {-best.delta_bic:.1f} (threshold "
                  f"{-BIC_THRESHOLD:g}); torque RMSE {current.rmse_torque_Nm:.3g} → {best.fit.rmse_torque_Nm:.3g} N·m, "
                  f"temperature RMSE {current.rmse_temp_C:.3g} → {best.fit.rmse_temp_C:.3g} °C; held-out error "
                  f"{cur_cv:.1f} → {best.cv_score:.1f} (better in {best.cv_better_tests} of {data.n_tests} tests).  "
                  f"Expected signature: {get_effect(best.effect).signature}.")
        current = best.fit
        freed = [n for n in current.model.free if n not in params.free]
        if freed:                                            # fitted with its channel's held brake parameters free
            drum.refree(current, f"freed to compare {best.effect}, which changes the law they set")
            params = drum.plan
            ev.append(f"{best.effect} changes a law the bare drum held: it was compared with "
                      f"{', '.join(freed)} free (the bare drum held {'them' if len(freed) > 1 else 'it'} as not "
                      f"needed), the penalty for {'them' if len(freed) > 1 else 'it'} counted in its BIC.")
        refit = free_needed(drum, data, chosen, current)     # the bare drum held them under a model without
        if refit is not None:                                # this effect: its misfit may have hidden their need
            params, current, struct = drum.plan, refit, structure(refit, nq, nt)
            ev.append(f"With {' + '.join(chosen)} in the model the drum needs "
                      f"{', '.join(n for n in drum.free if n not in base.model.free)} fitted (BIC lower): freed.")
        fits.append(current)      # a clean residual does not stop the search: a second effect the calibrated
                                  # drum partly absorbed must still pass ΔBIC < −10 and the held-out test
    pair_first = not chosen and base_struct["structured"] and max_effects >= 2
    found = pair_path(data, params, names, base, base_cv) if pair_first else None
    if found is not None:                    # nothing alone, a pair together (pair_path)
        fit, cv, base_cv = found
        chosen, current, fits, known = list(fit.effects), fit, [None, fit], []
        struct = structure(fit, nq, nt)
        steps.append({"step": "pair", "effects": list(chosen), "delta_bic": float(fit.bic - base.bic),
                      "cv_score": cv, "current_cv": base_cv})
        ev.append(f"No effect passes alone, but {' + '.join(chosen)} together lower BIC by {base.bic - fit.bic:.1f} "
                  f"(a pair needs {-PAIR_BIC:g}) with held-out error {base_cv:.1f} → {cv:.1f} (pair_path): each may "
                  f"have pulled the free drum against the other's signature.  The pair faces the tests of any pair.")
    if len(chosen) >= 2:
        chosen, current, struct, swaps = exchange(data, params, names, chosen, current, struct, nq, nt, known=known)
        chosen, current, struct, removed = eliminate(data, params, chosen, current, struct, nq, nt)
        swaps += [(a, "nothing", d) for a, d in removed]
        if swaps:
            fits = [None] * (len(chosen) - 1) + [current]
            steps.append({"step": "exchange", "swaps": swaps})
            ev.append("Exchange step: " + "; ".join(f"{a} replaced by {b} (BIC {d:+.1f})" for a, b, d in swaps)
                      + " — an effect picked early had absorbed part of a later one's signature.")
    partner = None                  # a second effect dropped for want of its own evidence, that cleared the residual
    if len(chosen) == 2:
        pair, pair_clean, pair_fit = list(chosen), not struct["structured"], current
        chosen, current, struct, fits = own_evidence(data, params, chosen, current, struct, fits, nq, nt, steps, ev,
                                                     drum.held(), names, drum.departures())
        partner = next((e for e in pair if e not in chosen), None) if len(chosen) == 1 and pair_clean else None
        if found is not None and len(chosen) == 1 and not reformed_alone(data, params, chosen[0], base, base_cv):
            ev.append(f"{chosen[0]}, left of the pair, has no evidence of its own: even re-formed it does not clear "
                      f"the selection's bar against the drum alone: not named.")
            chosen, current, struct, fits, partner = [], base, base_struct, [], None
    if partner or (len(chosen) >= 2 and struct["structured"]):
        # a partner that cleared the residual, or structure left by two effects each with evidence of its own, may
        # stand in for a brake parameter the bare drum held as not needed, or could not identify where the partner
        # was dropped with it freed: free those the model with them needs
        refit = free_needed(drum, data, chosen, current, names=drum.held() + (stood_for(steps) if partner else ()))
        if refit is not None:
            params, current, struct = drum.plan, refit, structure(refit, nq, nt)
            fits = [None] * (len(chosen) - 1) + [refit]
            ev.append(f"With {' + '.join(chosen)} in the model the drum needs "
                      f"{', '.join(n for n in drum.free if n not in base.model.free)} fitted (BIC lower): freed.")
    refined = current
    selected = [{"effect": e, "form": "exact"} for e in chosen]
    shape = None
    if not chosen:
        verdict, remaining, struct = "none", base_struct["structured"], base_struct
        ev.append(f"The baseline residual is structured ({structure_words(base_struct)}) but no catalogue effect "
                  f"explains it: an unknown effect remains." if remaining else
                  "The baseline residual is consistent with noise: no missing effect is detected.")
    elif not struct["structured"]:
        verdict, remaining = chosen[0], False
        ev.append(f"The refined residual is consistent with noise ({structure_words(struct)}).")
    else:
        remaining = True
        part = None
        for j in range(1, len(chosen) + 1):       # the fewest effects whose flexible form clears the residual
            if fits[j - 1] is None:
                continue
            part = partial_form(data, params, base, fits[j - 1], chosen[:j], nq, nt)
            if part is not None:
                break
        if part is None and partner is not None:
            verdict = chosen[0]
            ev.append(f"The residual of baseline + {chosen[0]} is still structured ({structure_words(struct)}) and "
                      f"no flexible version of {chosen[0]} removes it; {partner} does, but without evidence of its "
                      f"own (above).  {chosen[0]} is named on its own evidence; what the data still want is left "
                      f"unnamed (remaining structure): an effect outside the catalogue, or a departure of the drum "
                      f"the free brake parameters do not cover (a lining of another thickness).")
        elif part is None:
            verdict, selected, indist = "none", [], []
            ev.append(f"But the residual of baseline + {' + '.join(chosen)} is still structured "
                      f"({structure_words(struct)}), and no flexible version of these effects removes it: none "
                      f"of the catalogue explains the data.  An effect outside the catalogue remains — write it "
                      f"as a plugin and refit.")
        else:
            name, share, shape, flex_struct = part
            shape["effect"] = name
            refined = fits[j - 1]
            struct = structure(refined, nq, nt)
            dropped = chosen[j:]
            beside = next((st["effect"] for st in steps if st.get("step") == "beside the re-formed first"), None)
            keep = j == 1 and dropped == [beside]     # found beside this form re-formed (partner.own_evidence)
            dropped = [] if keep else dropped
            selected = [{"effect": e, "form": "partial" if e == name else "exact"} for e in chosen[:j]]
            for e in selected:
                if e["effect"] == name:
                    e["explained_share"] = share
            verdict = chosen[0]
            ev.append(f"{name} explains {share:.0%} of the baseline's excess error but its catalogue form leaves "
                      f"structure ({structure_words(struct)}); a flexible version of its {shape['hook']} hook "
                      f"(linear spline in {shape['covariate']}) leaves none: form \"partial\" — the data want "
                      f"the shape shown (write it as a plugin)."
                      + (f"  {', '.join(dropped)} only absorbed part of this form mismatch and is not kept."
                         if dropped else ""))
            if keep:
                refined = fits[1]
                struct = structure(refined, nq, nt)
                selected.append({"effect": beside, "form": "exact"})
            other = (beside_partial(data, params, name, refined, names, drum.departures())
                     if len(chosen) == 1 and max_effects > 1 else None)
            if other is not None:                   # a second effect beside the partial one, on its own evidence
                second, refined, dbic, pref, reform = other
                selected.append({"effect": second, "form": "exact"})
                struct = structure(refined, nq, nt)
                steps.append({"step": "beside the partial first", "effect": second, "delta_bic": dbic,
                              "heldout": pref, "first": name, "reform": reform})
                ev.append(f"Beside {name} re-formed, {second} lowers BIC by {-dbic:.1f} and predicts held-out "
                          f"tests better (log score {pref['heldout_elpd']:+.1f} ± {pref['heldout_se']:.1f}, "
                          f"better in {pref['better_tests']} of {pref['tests']} tests, worse in "
                          f"{pref['worse_tests']}), also with the drum's departures freed: {second} is named beside "
                          f"it.")
    refined = recheck(drum, data, refined, [e["effect"] for e in selected]) if selected else refined
    misfit = ("unexplained" if remaining and not any(e["form"] == "partial" for e in selected) else
              "partial" if remaining or any(e["form"] != "exact" for e in selected) else False)
    # shape-free: the bands, other forms; where the form leaves structure, the other quantities' splines too
    forms, channels = shape_rivals(data, refined, drum.plan, first_cands if misfit else ()) if selected else ([], [])
    loose = (loose_form(refined, forms, -BIC_THRESHOLD) if len(selected) == 1 and selected[0]["form"] == "exact"
             and not remaining else None)
    if loose is not None:                    # the structure tests pass, BIC does not: the form is not the data's
        shape, misfit = loose_shape(selected[0], base, refined, loose, ev), "partial"
        channels = channel_rivals(data, refined, first_cands, drum.plan)
    rivalry = _rivals(selected, _same_drum(data, params, base, first_cands), base_cv, validity(full), nq)
    infl, named = max(ess_inflation(refined).values()), {e for a in rivalry for e in a["effects"]}
    twin = (twin_rival(data, params, refined, validity(full), nq.sigma, infl)
            if len(selected) == 1 and not misfit and TWINS.get(selected[0]["effect"]) not in named else None)
    rivalry = ([twin] + rivalry)[:MAX_RIVALS] if twin else rivalry      # facing one way (rollaway.identify.twins)
    if (len(selected) == 1 and (selected[0]["form"] == "exact" or loose is not None) and not remaining
            and len(rivalry) < MAX_RIVALS):
        own = next((f for f in forms if len(f.effects) == 1), None)
        named = {e for a in rivalry for e in a["effects"]}
        for a in other_form_rivals(data, refined, own, [c for c in first_cands if c.effect not in named],
                                   drum.plan)[:MAX_RIVALS - len(rivalry)]:
            a["tell_apart"] = tell_apart(refined, a["fit"], validity(full), nq.sigma)
            rivalry.append(a)
    if misfit and selected and len(rivalry) < MAX_RIVALS:      # the form is wrong: is the quantity known?
        for a in channel_alternatives(refined, forms, channels, infl):
            if len(rivalry) < MAX_RIVALS and all(set(a["effects"]) != set(r["effects"]) for r in rivalry):
                a["tell_apart"] = tell_apart(refined, a["fit"], validity(full), nq.sigma)
                rivalry.append(a)
    if len(selected) == 1 and partner is not None:                # dropped beside a second term of the first's law
        rivalry = (_second_term_rival(steps, refined, pair_fit, validity(full), nq) + rivalry)[:MAX_RIVALS]
    if len(selected) >= 2 and not remaining:
        rivalry = set_rivals(data, params, names, [e["effect"] for e in selected], refined, infl, SCREEN_ITERATIONS)
        for a in rivalry:
            a["tell_apart"] = tell_apart(refined, a["fit"], validity(full), nq.sigma)
    for rule in (() if verdict == "none" else (law_twin_rival, loss_twin_rival, unsure_second(steps), offsets_rival(steps, nq))):
        rivalry = rule(data, params, refined, first_cands, validity(full), nq.sigma, infl, rivalry)
    if verdict == "none" and remaining and not rivalry:
        shapes = candidate_shapes(data, first_cands, drum.plan, nq, nt)    # which quantity, whatever its form
        rivalry = closest(base, first_cands, base_cv, BIC_THRESHOLD, validity(full), nq.sigma, shapes)
        forms = [a["shape_fit"] for a in rivalry if "shape_fit" in a] + pair_shapes(data, shapes, drum.plan, nq, nt)
    weak = weak_alternatives(params, base, first_cands, validity(full), nq.sigma) if not chosen and not remaining else []
    indist = [" + ".join(a["effects"]) for a in rivalry + weak]
    ev += alternative_words(verdict, rivalry + weak, [e["effect"] for e in selected])
    limits = detection_limits(data, base) if verdict == "none" and not remaining else []
    ev += [limits_words(limits)] if limits else []
    forms += channels + partial_twin_pair(data, drum.plan, refined, forms, selected and misfit, infl)   # bands
    pool = [base] + [c.fit for c in first_cands]
    kept = [a["fit"] for a in rivalry + weak if a.get("bands", True)]   # named beside the verdict: in the bands
    ties = [a["fit"] for a in rivalry if a.get("kind") == "rival" and not a.get("channel") and a.get("bands", True)]
    if data is not full:                                  # the chosen model, refitted on every row
        attach_predictive(data, refined, pool, len(selected), drum, misfit, kept, forms, ties, (nq, nt))
        alts, pool = refined.fit_info.get("alternatives", []), []
        refined = calibrate(full, refined.effects, params, start=refined.values)
        refined.fit_info["alternatives"] = alts
        ev.append(f"Selection ran on {len(data)} rows (consecutive rows of each test merged, windows ≤ "
                  f"{MAX_WINDOW_S:g} s); the chosen model was refitted on all {len(full)} rows.")
        data = full
    refined.covariance = predictive_covariance(refined, drum.fixed_priors(), ess_inflation(refined))
    attach_predictive(data, refined, pool, len(selected), drum, misfit, kept, forms, ties, (nq, nt))
    alts = refined.fit_info.get("alternatives") or []
    restate(refined, mixture_variances(refined, alts) or covariance_variances(refined))
    # the covariance keeps the held gap: the bands condition on the set's gap, except facing an untested direction
    # (rollaway.uncertainty.draws.draw_values)
    drum.update(refined)
    refined.fit_info["calibration"] = drum.record()
    ev.append(interval_words(refined, drum, alts))
    hidden = hidden_shifts(data, refined)
    if hidden_words(refined, hidden):
        ev.append(hidden_words(refined, hidden))
    return Diagnosis(data, paper, base, nq, nt, first_cands, verdict, indist, refined,
                     remaining, struct, base_cv, ev, selected, steps, shape, drum, rivalry + weak, diagnose,
                     detection=limits, hidden=hidden)


def _rivals(selected: list[dict], first: list[Candidate], base_cv, tested: dict, nq: Noise) -> list[dict]:
    """The one-effect sets the data do not rule out against a one-effect verdict, each with the test that would
    tell it from the verdict (:mod:`rollaway.identify.ambiguity`)."""
    if len(selected) != 1 or base_cv is None:
        return []
    best = next((c for c in first if c.effect == selected[0]["effect"]), None)
    if best is None:
        return []
    out = rivals(best, [c for c in first if c.cv_score is not None or c.delta_bic < WEAK_BIC], BIC_THRESHOLD,
                 max(ess_inflation(best.fit).values()))
    for a in out:
        a["tell_apart"] = tell_apart(best.fit, a["fit"], tested, nq.sigma)
    return out


def _second_term_rival(steps: list[dict], verdict: FitResult, pair: FitResult, tested: dict, nq: Noise) -> list[dict]:
    """The pair of effects dropped because the second adds too little beside the first with a second term of its
    own law (:func:`rollaway.identify.beyond.beyond_second_term`), as an alternative the data cannot rule out:
    a second term of one law and a second effect write the same curve on these tests."""
    own = next((s["beyond_reform"] for s in steps[::-1] if s.get("step") == "own evidence"), {})
    term = own.get("second_term")
    if term is None or pair.jacobian is None:
        return []
    names = [e.name for e in pair.model.effects]
    return [{"kind": "rival", "effects": names, "delta_bic": float(term["delta_bic"]), "heldout_elpd": term["heldout_elpd"],
             "heldout_se": term["heldout_se"], "fit": pair,
             "why": (f"beside the first with a second term of its own law ({term['term']}) the second changes BIC by "
                     f"{term['delta_bic']:+.1f} and the held-out log score by {term['heldout_elpd']:+.1f} ± "
                     f"{term['heldout_se']:.1f}: one law written with two time constants and two laws write the same "
                     f"curve here"),
             "tell_apart": tell_apart(verdict, pair, tested, nq.sigma)}]


def _same_drum(data, params, base: FitResult, first: list[Candidate]) -> list[Candidate]:
    """The step-1 candidates that passed the held-out test or lowered BIC by more than :data:`WEAK_BIC`, refitted
    with the brake parameters *params* frees when a later step freed more than the bare drum (*base*) did: a verdict
    and its rivals compared with one drum."""
    if tuple(params.free) == tuple(base.model.free):
        return first
    kept = [c for c in first if c.cv_score is not None or c.delta_bic < WEAK_BIC]
    fits = fit_all(data, [([c.effect], params, dict(start=c.fit.values)) for c in kept])      # side by side
    return [Candidate(c.effect, fit, fit.bic - base.bic, fit.aic - base.aic, c.cv_score, c.cv_better_tests, c.step)
            for c, fit in zip(kept, fits) if fit.jacobian is not None]


def _test_offsets(fit: FitResult, nq: Noise) -> bool:
    from rollaway.identify.residuals import STRUCTURE_P
    return structure(fit, nq, nq)["torque"]["test_offsets"]["p"] < STRUCTURE_P


__all__ = ["Candidate", "Diagnosis", "diagnose", "cv_score", "structure", "channel_noise", "folds"]
