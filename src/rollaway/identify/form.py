"""Is a verdict's catalogue form the data's?  The form "partial" of :func:`rollaway.identify.diagnose.diagnose`.

A selected effect is named with ``form: "partial"`` when its catalogue law explains most of what the drum alone
leaves but not its shape: where the residual stays structured and the effect's shape-free form (a linear spline of
its hook, :mod:`rollaway.identify.shape`) clears it (:func:`partial_form`), and where the residual passes the
structure tests but the verdict's own spline still lowers BIC by more than 10 (:func:`loose_shape`, found by
:func:`rollaway.identify.shape.loose_form`).  Either way the shape the data want is returned for the report.
"""
from __future__ import annotations

from rollaway.bench.noise import Noise
from rollaway.effects import get_effect
from rollaway.identify.calibrate import FitResult, calibrate
from rollaway.identify.selection import BIC_THRESHOLD, structure, weighted_chi2

PARTIAL_SHARE = 0.5          # "explains most of the baseline's excess error"


def explained_share(base: FitResult, refined: FitResult) -> float | None:
    """The share of the baseline's excess error (χ² beyond its degrees of freedom) that *refined* explains."""
    excess = weighted_chi2(base) - (2 * len(base.data) - sum(base.effective_parameters.values()))
    return None if excess <= 0 else float((weighted_chi2(base) - weighted_chi2(refined)) / excess)


def loose_shape(entry: dict, base: FitResult, refined: FitResult, loose: FitResult, ev: list[str]) -> dict:
    """Mark the one-effect verdict *entry* "partial" where its shape-free form *loose* beats its catalogue form by BIC
    (:func:`rollaway.identify.shape.loose_form`); says so in *ev*; returns the shape the data want."""
    from rollaway.identify.shape import shape_curves
    name, flex = entry["effect"], loose.model.effects[0]
    shape = shape_curves(get_effect(name), refined, loose, type(flex) if not isinstance(flex, type) else flex)
    shape["effect"] = name
    share = explained_share(base, refined)
    entry.update(form="partial", **({"explained_share": min(share, 1.0)} if share is not None else {}))
    ev.append(f"{name}'s catalogue form is not the data's, though the residual passes the structure tests: its "
              f"shape-free form (a linear spline of its {shape['hook']} hook in {shape['covariate']}) lowers BIC by "
              f"{refined.bic - loose.bic:.1f} against it (more than {-BIC_THRESHOLD:g}): form \"partial\" — the data "
              f"want the shape shown (write it as a plugin).")
    return shape


def partial_form(data, params, base: FitResult, refined: FitResult, chosen: list[str], nq: Noise, nt: Noise):
    """The selected effect whose form is only partly right: (name, share, shape, structure) or None."""
    from rollaway.identify.shape import shape_curves
    share = explained_share(base, refined)
    if share is None or share < PARTIAL_SHARE:
        return None
    for name, (effects, _, kwargs) in _flex_jobs(params, refined, chosen):
        fit = calibrate(data, effects, params, **kwargs)
        s = structure(fit, nq, nt)
        if not s["structured"]:
            return name, float(share), shape_curves(get_effect(name), refined, fit, effects[-1]), s
    return None


def _flex_jobs(params, refined: FitResult, chosen: list[str]) -> list:
    """(name, fit job) of each effect of *chosen* with a flexible form: *chosen* with that effect re-formed last,
    started from *refined*'s values (what :func:`partial_form` fits, in its order)."""
    from rollaway.identify.shape import covariate_of, flexible_effect, shape_hook
    jobs = []
    for name in chosen:
        eff = get_effect(name)
        found = shape_hook(eff)
        flex = None if found is None else flexible_effect(eff, covariate_of(refined, found[1]))
        if flex is not None:
            jobs.append((name, ([c for c in chosen if c != name] + [flex], params, dict(start=refined.values))))
    return jobs


def partial_ahead(data, params, base: FitResult, refined: FitResult, chosen: list[str]) -> None:
    """Start :func:`partial_form`'s first fit of the one effect *chosen* in the background
    (:func:`rollaway.identify.workers.ahead`) while the next forward step runs, where it will be asked for if that
    step adds nothing: *refined*'s residual is structured (the caller's test) and it explains at least
    :data:`PARTIAL_SHARE` of the baseline's excess error.  Then the same effect re-formed with the re-formed fits'
    budget (:func:`rollaway.identify.shape.reform_job`), which the search beside the partial first starts from
    (:func:`rollaway.identify.partner.beside_partial`) and the partner test fits beside its first batch.  On a
    100 Hz log of 12 s tests these are the longest fits left that nothing runs beside."""
    from rollaway.identify.shape import reform_job
    from rollaway.identify.workers import ahead
    share = explained_share(base, refined)
    if len(chosen) == 1 and share is not None and share >= PARTIAL_SHARE:
        ahead(data, [job for _, job in _flex_jobs(params, refined, chosen)[:1]]
              + [job for job in [reform_job(params, chosen[0], refined)] if job is not None])


__all__ = ["PARTIAL_SHARE", "explained_share", "loose_shape", "partial_ahead", "partial_form"]
