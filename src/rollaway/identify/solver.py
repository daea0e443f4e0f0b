"""The minimiser under the fits: MINPACK's Levenberg–Marquardt with forward differences evaluated side by side
(:func:`levenberg_marquardt`), and the test that gives up a fit which cannot reach what its caller needs
(:func:`futile`).  The residual, its bounded coordinates and the per-test families are
:mod:`rollaway.identify.fitting`'s."""
from __future__ import annotations

import math

import numpy as np

from rollaway.scipy_direct import optimize_extension

_REL_STEP = float(np.finfo(float).eps) ** 0.5     # SciPy's forward-difference step for float64 ('2-point')


FUTILE_MARGIN = 20.0         # a fit that only matters below a known BIC is abandoned when even its generous
                             # projected end (futile) stays this far above that BIC [assumed]
FALLS = 3                    # a futile fit is judged by the largest of its last this many falls (see futile)


class _GiveUp(Exception):
    """Raised inside MINPACK's Jacobian call to abandon a futile fit (:func:`futile`)."""


def futile(give_up_loglik: float, later_calls: int = 0):
    """The test :func:`levenberg_marquardt` applies at each iterate of a fit that only matters if it comes below
    *give_up_loglik* (the information criteria's log-likelihood term L = n·ln(S_T/n) + n·ln(S_Q/n) of the
    temperature and torque halves of the standardised residual): ``stop(history, r, calls_left) → bool``, true when
    L would stay above the bar even if it kept falling, for every residual call left (*calls_left* in this pass
    plus *later_calls* of the passes after it), at the largest of its last :data:`FALLS` falls between iterates —
    or at what the largest of the last falls of the sum of squares S = S_T + S_Q (*history*: S at each iterate)
    would take off it, whichever is more.  Both, since MINPACK lowers S while L, the criteria's term, can rise or
    fall faster as the two halves trade.  A crawl along a valley (a misfit model) falls ever more slowly, so the
    projection is generous: a fit it gives up would have ended above the bar.  Several falls, not the last: a step
    can stall for an iterate (a shrunken trust region) and then fall by hundreds again (measured on two-effect
    fits)."""
    terms: list = []

    def stop(history: list, r: np.ndarray, calls_left: int) -> bool:
        n = r.size // 2
        s_t, s_q = float(r[:n] @ r[:n]), float(r[n:] @ r[n:])
        if min(s_t, s_q) <= 0.0:
            terms.clear()
            return False
        terms.append(n * math.log(s_t / n) + n * math.log(s_q / n))
        if len(history) <= FALLS or len(terms) <= FALLS:
            return False
        calls = calls_left + later_calls

        def fall(x):
            return max(max(a - b for a, b in zip(x[-FALLS - 1:-1], x[-FALLS:])), 0.0) * calls
        reach = history[-1] - fall(history)
        if reach <= 0.0:
            return False
        return terms[-1] - max(fall(terms), 2 * n * math.log(history[-1] / reach)) > give_up_loglik
    return stop


def levenberg_marquardt(fun, columns, z0: np.ndarray, tol: float, max_nfev: int,
                        stop=None, used: list | None = None) -> tuple[np.ndarray, bool]:
    """The minimiser of ‖fun(z)‖² from *z0* by MINPACK's Levenberg–Marquardt (``lmder``, called as
    :func:`scipy.optimize.leastsq` calls it), exactly as :func:`scipy.optimize.least_squares` runs it with ``method="lm"``,
    ``x_scale=1.0`` (MINPACK's ``diag`` all ones), ``max_nfev`` and *tol* as ``ftol``, ``xtol`` and ``gtol``: the same
    forward differences (step √ε·max(1, |z|), signed like z), their evaluations side by side through
    ``columns(z, points)`` (*z* the point they are taken at).  ``least_squares`` evaluates the Jacobian once more after MINPACK returns, for its
    result's gradient: one (k + 1)-column evaluation per fit that nothing here reads.  The last residual and the
    last Jacobian are kept, so MINPACK asking again at the same point costs nothing.  Fewer residuals than
    parameters: :func:`scipy.optimize.least_squares` (and its error).

    *stop* (:func:`futile`), asked at each iterate (where MINPACK wants its Jacobian), abandons the fit there.
    *used*: gets the residual calls made appended (the shape check's among them): a budget *max_nfev* above that
    number never bound, and any such budget gives the same minimiser.
    Returns (the minimiser, or the iterate where *stop* abandoned it; whether it did)."""
    last: dict = {}
    history: list = []
    calls = [0]

    def counted(zz):
        calls[0] += 1
        return f(zz)

    def f(zz):
        if "z" in last and np.array_equal(last["z"], zz):
            return last["f"]
        r = fun(zz)
        last["z"], last["f"] = np.array(zz, float), r
        return r

    def jac(zz):
        if "jz" in last and np.array_equal(last["jz"], zz):
            return last["j"]
        f0 = f(zz)
        if stop is not None:
            history.append(float(f0 @ f0))
            if stop(history, f0, max_nfev - calls[0]):
                last["gave_up"] = np.array(zz, float)
                raise _GiveUp
        h = _REL_STEP * ((zz >= 0).astype(float) * 2 - 1) * np.maximum(1.0, np.abs(zz))
        points = []
        for i in range(zz.size):
            x1 = np.array(zz, float)
            x1[i] = zz[i] + h[i]
            points.append(x1)
        j = np.empty((np.size(f0), zz.size))
        for i, fi in enumerate(columns(zz, points)):
            j[:, i] = (fi - f0) / ((zz[i] + h[i]) - zz[i])
        last["jz"], last["j"] = np.array(zz, float), j
        return j

    z0 = np.asarray(z0, float).ravel()
    if np.size(counted(z0)) < z0.size:     # counted: as leastsq's own check of the function's shape
        from scipy import optimize
        if used is not None:
            used.append(max_nfev)          # not counted there: as if the budget bound
        return optimize.least_squares(fun, z0, method="lm", xtol=tol, ftol=tol, gtol=tol, x_scale=1.0,
                                      max_nfev=max_nfev).x, False
    try:                                    # scipy.optimize.leastsq's calls, without its covariance and messages
        jac(z0)                             # its check of the Jacobian's shape (kept: MINPACK asks for it next)
        x, info = optimize_extension("_minpack")._lmder(counted, jac, z0, (), 0, 0, tol, tol, tol, max_nfev, 100.0, np.ones(z0.size))
    except _GiveUp:
        return last["gave_up"], True
    finally:
        if used is not None:
            used.append(calls[0])
    if info == 0:
        raise TypeError("MINPACK lmder: improper input parameters")
    return x, False


__all__ = ["FUTILE_MARGIN", "futile", "levenberg_marquardt"]
