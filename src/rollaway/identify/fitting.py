"""Joint two-channel least squares with per-test parameters profiled out (variable projection).

The objective is the sum of squared *standardised* residuals of both measured channels,
``Σ ((T_model − T_meas)/σ_T)² + Σ ((M_model − M_meas)/σ_M)²`` over every sample (the t = 0
temperature reading included: it measures T_0 like any other reading).  Parameters are of
two kinds:

* global ones (μ_d, h, effect parameters) — fitted by :func:`scipy.optimize.least_squares`
  (trust-region reflective, bounds, variables scaled to order one);
* per-test ones (each test's T_0, per-test effect parameters) — they touch only their own
  test's rows, so their Jacobian is block diagonal and one model evaluation per family gives
  all of it (every test perturbed at once).  For given globals they are eliminated by one
  Gauss–Newton step per test (exact where the model is linear in them, as it is in T_0 for
  eqs. 10 and 16), and the globals see the *projected* residual (Golub & Pereyra 1973,
  Kaufman 1975).  Outer passes repeat until the per-test values stop moving.

The projected Jacobian of the globals gives their covariance with the per-test parameters
already accounted for (the Schur complement of the full normal matrix).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import optimize

from rollaway.identify.measurements import Measurements
from rollaway.identify.model import INITIAL_TEMP, BenchModel

MAX_OUTER = 4


@dataclass
class Solution:
    values: dict                  # all values (globals as floats, per-test families as arrays)
    residual: np.ndarray          # standardised residuals (model − measured), [temperature | torque]
    jac: np.ndarray | None        # projected Jacobian of the globals in scaled variables (rows as residual)
    scale: np.ndarray             # variable scales: x = z·scale
    local_grad: list[np.ndarray]  # per family: ∂residual/∂(own test's value), one entry per row
    local_normal: np.ndarray | None   # (tests, m, m) per-test normal matrices of the families
    nfev: int


class Problem:
    """The standardised residual of one model on one data set, with its free parameters."""

    def __init__(self, model: BenchModel, data: Measurements, names, families, values: dict,
                 w_temp: np.ndarray, w_torque: np.ndarray):
        self.model, self.data = model, data
        self.names, self.families = list(names), list(families)
        self.values = dict(values)
        self.w_temp, self.w_torque = np.asarray(w_temp, float), np.asarray(w_torque, float)
        self.rows_test = np.concatenate([data.test_index, data.test_index])
        self.nfev = 0
        self.step = {f: 1e-4 * (model.bounds(f)[1] - model.bounds(f)[0]) for f in self.families}

    def raw(self, vals: dict) -> np.ndarray:
        self.nfev += 1
        p = self.model.predict(self.data, vals)
        with np.errstate(invalid="ignore"):
            r = np.concatenate([(p.drum_temp_C - self.data.drum_temp_C) * self.w_temp,
                                (p.torque_Nm - self.data.torque_Nm) * self.w_torque])
        return np.where(np.isfinite(r), r, 1e6)

    def profile(self, vals: dict):
        """Residual with the per-test families at their best values (one Gauss–Newton step)."""
        r0 = self.raw(vals)
        if not self.families:
            return r0, {}, [], None
        grads = []
        for f in self.families:
            g = (self.raw({**vals, f: vals[f] + self.step[f]}) - r0) / self.step[f]
            grads.append(g)
        gm = np.stack(grads, axis=1)                       # rows × m
        nt, m = self.data.n_tests, len(self.families)
        normal = np.zeros((nt, m, m))
        rhs = np.zeros((nt, m))
        for a in range(m):
            rhs[:, a] = np.bincount(self.rows_test, gm[:, a] * r0, nt)
            for b in range(a, m):
                normal[:, a, b] = normal[:, b, a] = np.bincount(self.rows_test, gm[:, a] * gm[:, b], nt)
        ridge = 1e-12 * np.maximum(np.trace(normal, axis1=1, axis2=2), 1e-300)[:, None, None] * np.eye(m)
        d = -np.linalg.solve(normal + ridge + 1e-300 * np.eye(m), rhs[..., None])[..., 0]
        step = {}
        for a, f in enumerate(self.families):
            lo, hi = self.model.bounds(f)
            new = np.clip(vals[f] + d[:, a], lo, hi)
            d[:, a] = new - vals[f]
            step[f] = new
        r = r0 + np.einsum("ij,ij->i", gm, d[self.rows_test])
        return r, step, grads, normal

    def solve(self, start: dict, tol: float = 1e-9) -> Solution:
        model, names = self.model, self.names
        vals = {**self.values, **{n: start[n] for n in names if n in start}}
        for f in self.families:
            vals[f] = np.array(vals[f], float, copy=True)
        lo = np.array([model.bounds(n)[0] for n in names])
        hi = np.array([model.bounds(n)[1] for n in names])
        x0 = np.clip(np.array([vals[n] for n in names], float), lo, hi)
        x0 = np.where(x0 <= lo, lo + 1e-6 * (hi - lo), np.where(x0 >= hi, hi - 1e-6 * (hi - lo), x0))
        scale = np.maximum(np.abs(x0), 1e-3 * (hi - lo)) if names else np.zeros(0)
        jac = None
        z = x0 / scale if names else x0
        for _ in range(MAX_OUTER):
            fixed = dict(vals)

            def fun(zz):
                v = dict(fixed)
                v.update(zip(names, zz * scale))
                return self.profile(v)[0]

            if names:
                res = optimize.least_squares(fun, z, bounds=(lo / scale, hi / scale), method="trf", x_scale=1.0,
                                             xtol=tol, ftol=tol, gtol=tol, max_nfev=100 * (len(names) + 1))
                z, jac = res.x, res.jac
                vals.update(zip(names, z * scale))
            r_lin, step, _, _ = self.profile(vals)
            if not self.families:
                break
            vals.update(step)
            r_new = self.raw(vals)
            lin, new = float(r_lin @ r_lin), float(r_new @ r_new)
            if abs(new - lin) <= 1e-7 * lin + 1e-9:     # the model is linear in the per-test values here
                break
        r, _, grads, normal = self.profile(vals)
        r_true = self.raw(vals)
        if names and jac is None:
            jac = np.zeros((r.size, len(names)))
        return Solution(vals, r_true, jac, scale, grads, normal, self.nfev)
