"""Per-test offsets (a torque zero per test, ``torque_zero_offset``) beside or instead of a physical law.

Offsets are the bench's, not the drum's: each test's level its own.  Where the tests are short and each sits at its
own temperature, a temperature law's form mismatch — or the whole law — is a level error test by test, and offsets
take it up; their held-out score refits each held-out test's own offset (as it does T_0) and cannot fault them.  So
offsets are named beside an effect only where that effect re-formed (its hook as a linear spline) still leaves
per-test offsets (:func:`offsets_absorbed`, the forward step's gate
:func:`~rollaway.identify.selection.per_test_signature`), and where they are named, a physical law that re-formed
leaves none is flagged beside them (:func:`offsets_rival`).
"""
from __future__ import annotations

from rollaway.identify.calibrate import FitResult

ZERO_WORDS = ("a reading of each test's torque zero (the torque with the brake released, before the hold) or longer "
              "holds would: per-test offsets stay constant through a hold, a temperature law follows the drum as it "
              "cools")
LAWS_TRIED = 2               # the step-1 candidates re-formed beside an offsets verdict, best BIC first


def offsets_absorbed(name: str, reform: FitResult | None, nq) -> bool:
    """True where *name* has per-test parameters and the fit *reform* (the other effect re-formed) leaves no
    per-test offsets for them: its torque residual's test means do not differ (the first half of the forward step's
    gate, :func:`~rollaway.identify.selection.per_test_signature`; whatever else it leaves is not the offsets')."""
    from rollaway.identify.selection import has_per_test, per_test_signature
    return (has_per_test(name) and reform is not None and reform.jacobian is not None
            and not per_test_signature(reform, nq, within=False))


def offsets_rival(steps: list[dict], nq):
    """A rule for :func:`rollaway.identify.diagnose.diagnose`, called as the twin rules are
    (:mod:`rollaway.identify.twins`), that names per-test offsets' rivals beside the verdict while fewer than
    :data:`~rollaway.identify.ambiguity.MAX_RIVALS` are:

    * where :func:`~rollaway.identify.partner.own_evidence` left offsets out of a pair because the other effect
      re-formed leaves none for them (:func:`offsets_absorbed`), the pair (:func:`_dropped_pair`);
    * where the verdict is offsets alone, each of the best :data:`LAWS_TRIED` step-1 laws whose re-formed version
      leaves no per-test offsets either (:func:`_laws_instead`);
    * where the verdict is one law of the hand force alone and each hand force was tested once facing each way,
      offsets that fit the tests as well (:func:`_offsets_instead`).

    On short tests, each at its own temperature, a temperature law re-formed and per-test offsets write the same
    test levels: a quadratic friction law on 12 s tests at 100 Hz had offsets named beside it, a sigmoid modulus
    drop came out as offsets alone, and a friction law beside true offsets on 120 s tests at 10 Hz can be named alone.
    *nq*: the torque noise the structure tests use."""
    def rival(data, params, verdict, first_cands, tested: dict, noise_torque_Nm: float, inflation: float,
              rivalry: list[dict]) -> list[dict]:
        from rollaway.identify.ambiguity import MAX_RIVALS
        from rollaway.identify.selection import has_per_test
        if len(rivalry) >= MAX_RIVALS:
            return rivalry
        names = [e.name for e in verdict.model.effects]
        step = next((st for st in steps if st.get("offsets_pair") is not None), None)
        if step is not None:
            return rivalry + _dropped_pair(step, names, verdict, rivalry)
        if names and all(has_per_test(n) for n in names):
            return rivalry + _laws_instead(data, params, names, verdict, first_cands, nq, rivalry)[
                :MAX_RIVALS - len(rivalry)]
        if len(names) == 1 and _of_hand_force(names[0]) and once_per_force(data):
            return rivalry + _offsets_instead(data, params, verdict, first_cands, inflation, rivalry)
        return rivalry
    return rival


LEVEL_WORDS = ("a second test at a tested hand force would: per-test offsets differ from test to test, a law of the "
               "hand force gives it the same level")


def _of_hand_force(name: str) -> bool:
    """True for an effect whose shape-free form is a function of the hand force (``nonlinear_lining_stiffness``)."""
    from rollaway.effects import get_effect
    from rollaway.identify.shape import shape_hook
    hook = shape_hook(get_effect(name))
    return hook is not None and hook[1] == "hand_force_N"


def once_per_force(data) -> bool:
    """True when every test of *data* has a hand force of its own in its direction (no force tested twice facing
    one way): a law of the hand force then sets each test's level as a per-test offset does."""
    tests = {(round(float(f), 1), int(s)) for f, s in zip(data.hand_force_N, data.sign)}
    return len(tests) == data.n_tests and data.n_tests > 1


def _offsets_instead(data, params, verdict, first_cands, inflation: float, rivalry: list[dict]) -> list[dict]:
    """Beside a verdict of one law of the hand force on a bench that tested each force once facing each way: per-test
    offsets alone (the step-1 fit, or one fitted here) where their noise-weighted torque sum of squares is within
    :data:`~rollaway.identify.ambiguity.INDISTINGUISHABLE_BIC` (× *inflation*) of the verdict's — they write the same
    test levels, with a value per test the law spares (BIC's penalty prefers the law; that is parsimony, not a
    measurement).  Zero offsets on 1-Hz tests facing one way, one test per force, were named
    ``nonlinear_lining_stiffness`` alone.  Named, not drawn in the bands (offsets are the bench's)."""
    from rollaway.identify.ambiguity import INDISTINGUISHABLE_BIC
    from rollaway.identify.workers import fit_all
    name = "torque_zero_offset"
    if any(name in a["effects"] for a in rivalry):
        return []
    fit = next((c.fit for c in first_cands if c.effect == name and c.fit.jacobian is not None), None)
    if fit is None:
        fit = fit_all(data, [([name], params, dict(start=verdict.values))])[0]
    gap = (fit.rss_torque_weighted - verdict.rss_torque_weighted) / max(inflation, 1.0)
    if fit.jacobian is None or gap > INDISTINGUISHABLE_BIC:
        return []
    law = verdict.model.effects[0].name
    return [{"kind": "rival", "form": "exact", "effects": [name], "fit": fit, "bands": False,
             "delta_bic": float(fit.bic - verdict.bic), "heldout_elpd": None, "heldout_se": None,
             "why": (f"each hand force was tested once facing each way: per-test offsets set the tests' levels as "
                     f"{law} does (noise-weighted torque sum of squares {gap:+.1f} against it; BIC "
                     f"{fit.bic - verdict.bic:+.1f} counts the value per test the law spares, and the held-out score "
                     f"fits each held-out test's own offset and cannot judge them)"),
             "tell_apart": {"test": None, "words": LEVEL_WORDS}}]


def _dropped_pair(step: dict, names: list[str], verdict, rivalry: list[dict]) -> list[dict]:
    """The pair of *step* (offsets beside the verdict's effects), unless the verdict is not the pair less the
    offsets or the pair is named already.  It is named, not drawn in the bands (``"bands": False``): offsets are the
    bench's (a zero per test), and where they took up the tests' levels the pair's brake parameters stayed at their
    assumed values — its road torque is not what the data measured."""
    pair, own = step["offsets_pair"], step["beyond_reform"]
    if (pair.jacobian is None or not set(names) < set(pair.effects)
            or any(sorted(a["effects"]) == sorted(pair.effects) for a in rivalry)):
        return []
    offsets = next(e for e in pair.effects if e not in names)
    return [{"kind": "rival", "form": "exact", "effects": list(pair.effects), "fit": pair, "bands": False,
             "delta_bic": float(pair.bic - verdict.bic), "heldout_elpd": float(own["heldout_elpd"]),
             "heldout_se": float(own["heldout_se"]),
             "why": (f"{' + '.join(names)} re-formed leaves no per-test offsets, but on these tests a re-formed law "
                     f"and {offsets} write the same test levels: the pair is not ruled out"),
             "tell_apart": {"test": None, "words": ZERO_WORDS}}]


def _laws_instead(data, params, names: list[str], verdict, first_cands, nq, rivalry: list[dict]) -> list[dict]:
    """Beside a verdict of offsets alone: the :data:`LAWS_TRIED` step-1 candidates without per-test values that fit
    the torque best (its noise-weighted sum of squares: the offsets take up torque levels; BIC would rank last a law
    whose fit traded the temperature channel for the torque, :func:`~rollaway.identify.selection.nested_shortfall`
    — a friction and a modulus law beside true friction + sigmoid modulus on 12-s tests), each re-formed (its hook
    as a linear spline, one fit each, side by side), that leave no per-test offsets — a law that writes the tests'
    levels as the offsets do, with no value per test.  In the bands with the others named beside a verdict."""
    from rollaway.identify.shape import reform_job
    from rollaway.identify.selection import has_per_test
    from rollaway.identify.workers import fit_all
    named = {e for a in rivalry for e in a["effects"]}
    laws = [c for c in sorted(first_cands, key=lambda c: c.fit.rss_torque_weighted)
            if not has_per_test(c.effect) and c.effect not in named and c.fit.jacobian is not None][:LAWS_TRIED]
    jobs = [(c, reform_job(params, c.effect, c.fit)) for c in laws]
    jobs = [(c, j) for c, j in jobs if j is not None]
    out = []
    for (c, _), fit in zip(jobs, fit_all(data, [j for _, j in jobs])):
        if offsets_absorbed(names[0], fit, nq):
            out.append({"kind": "rival", "form": "shape-free", "effects": [c.effect], "fit": fit,
                        "delta_bic": float(fit.bic - verdict.bic), "heldout_elpd": None, "heldout_se": None,
                        "why": (f"{c.effect} re-formed (its hook as a linear spline) leaves no per-test offsets: it "
                                f"writes the tests' levels as {' + '.join(names)} {'do' if len(names) > 1 else 'does'} "
                                f"(BIC {fit.bic - verdict.bic:+.1f}; the held-out score fits each held-out test's own "
                                f"offsets and cannot judge them)"),
                        "tell_apart": {"test": None, "words": ZERO_WORDS}})
    return out
