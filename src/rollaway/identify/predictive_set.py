"""The predictive side of a diagnosis: what the saved model carries into the road bands.

:func:`attach_predictive` gives the chosen fit its predictive record (model error, tested range) and the
competing effect sets the data do not rule out, each with its weight and its own record
(:mod:`rollaway.uncertainty.bands`); :func:`interval_words` says what the parameter intervals count.
"""
from __future__ import annotations

from rollaway.identify.calibrate import FitResult
from rollaway.identify.drum import DrumCalibration, predictive_covariance
from rollaway.identify.intervals import ess_inflation
from rollaway.identify.selection import structure
from rollaway.uncertainty.bands import validity


def attach_predictive(data, refined: FitResult, pool: list[FitResult], n_effects: int, drum: DrumCalibration,
                      misfit: bool | str = False, keep=(), forms=(), ties=(), noise=None) -> None:
    """Attach the predictive record (model error, tested range) and the competing effect sets with their
    weights to *refined* (``fit_info``), for the saved model (:mod:`rollaway.uncertainty.bands`).  *misfit*:
    the saved model's form is known to leave structure (``"partial"``: an effect named "partial";
    ``"unexplained"``: structure no catalogue form clears): its model error is widened
    (:func:`rollaway.uncertainty.bands.model_error`).  *keep*: fits the data
    cannot tell from *refined* (named beside the verdict): always among the alternatives, those of them named as
    rivals (*ties*) with at least their BIC weight (:func:`rollaway.uncertainty.bands.alternatives`); *forms*: *refined*'s set
    with each effect shape-free (:func:`rollaway.identify.shape.form_rivals`; where *misfit* is set, also with an
    effect exchanged for a spline of another quantity along its covariate, :func:`rollaway.identify.shape.
    channel_rivals`), competing too.  A fit competes when
    its BIC is within :data:`rollaway.uncertainty.bands.COMPETING_BIC` of *refined*'s or the held-out prediction
    does not rule it out (BIC alone is overconfident where residuals are autocorrelated); not a fit with per-test
    values (a zero offset per test): its held-out score refits the held-out test's own values.  Each alternative
    carries its own model error: widened as "partial" when its residual is structured (*noise*: the channels'
    :class:`~rollaway.bench.noise.Noise`, for the test); a catalogue form never below *refined*'s when *misfit* is
    set (the structure the verdict leaves says no catalogue form is right), and, where no catalogue form clears
    the structure (*misfit* ``"unexplained"``), no set errs less than it either — but a pair of shape-free forms
    whose residual is clean (:func:`rollaway.identify.shape.pair_shapes`: two quantities changed, along different
    covariates, and together they explain what no catalogue form did).  A shape-free set errs by its own held-out
    record otherwise: which quantity changes is carried by the channel rivals' weights, not by a floor."""
    from rollaway.effects.shape_free import is_shape_free
    from rollaway.identify.ambiguity import not_ruled_out
    from rollaway.uncertainty.bands import COMPETING_BIC, alternatives, model_error
    from rollaway.model.predictive_record import record
    val = validity(data)
    refined.fit_info["predictive"] = record(model_error(refined, misfit), val)
    if not pool:                  # the alternatives were weighed on the selection's rows (already attached)
        return
    comp = [f for f in pool if f is not refined and f.jacobian is not None and len(f.effects) <= 1
            and not has_per_test_values(f)                 # refits the held-out test's own values: no fair score
            and (f.bic - refined.bic < COMPETING_BIC or not_ruled_out(refined, f))] if n_effects <= 1 else []
    comp += [f for f in forms if not has_per_test_values(f) and all(f is not g for g in keep)]   # the data's own form
    mix = alternatives(refined, comp + [f for f in keep if all(f is not g for g in comp)], keep=keep, ties=ties)
    alts = []
    for w, f in mix:
        if f is refined:
            continue
        f.covariance = predictive_covariance(f, drum.fixed_priors(), ess_inflation(f))
        structured = noise is None or structure(f, *noise)["structured"]
        own = misfit if noise is None else (misfit or "partial") if structured else False
        err = model_error(f, own)
        pair = not structured and sum(map(is_shape_free, f.model.effects)) >= 2    # two forms clear the structure
        if misfit == "unexplained" and not pair or misfit and not has_shape_free(f):   # no catalogue form errs less
            err["rel_sd"] = max(err["rel_sd"], refined.fit_info["predictive"]["model_error_rel_sd"])
        f.fit_info["predictive"] = record(err, val)
        f.fit_info["calibration"] = drum.record()
        alts.append((w, f))
    refined.fit_info["alternatives"] = alts


def has_shape_free(fit: FitResult) -> bool:
    """True when an effect of *fit* is a shape-free form (:mod:`rollaway.effects.shape_free`)."""
    from rollaway.effects.shape_free import is_shape_free
    return any(is_shape_free(e) for e in fit.model.effects)


def has_per_test_values(fit: FitResult) -> bool:
    """True when an effect of *fit* has values per test (each test's T_0, which every fit has, aside)."""
    return any(p.per_test for e in fit.model.effects for p in e.parameters)


def interval_words(fit: FitResult, drum: DrumCalibration, alts) -> str:
    """The evidence line on what the parameter intervals count: autocorrelated residuals, the held brake
    parameters' assumed spread, the competing effect sets *alts* ``[(weight, fit)]`` of the mixture."""
    k = ess_inflation(fit)
    fixed = sorted(drum.fixed_priors())
    return ("Parameter intervals count " + "; ".join(filter(None, [
        "autocorrelated residuals (variance × " + ", ".join(f"{v:.2g} {ch}" for ch, v in k.items()) + ")",
        f"the assumed spread of {', '.join(fixed)} (held, not known)" if fixed else "",
        f"{len(alts)} competing effect set{'s' if len(alts) > 1 else ''} (mixture, also in the bands: "
        + ", ".join(f"{' + '.join(f.effects) or 'the drum alone'} {w:.0%}" for w, f in alts)
        + f", {' + '.join(fit.effects) or 'the drum alone'} the rest)" if alts else ""]))
        + " (rollaway.identify.intervals).")


__all__ = ["attach_predictive", "has_per_test_values", "has_shape_free", "interval_words"]
