"""An independent bench-data generator for testing diagnose (written from the paper's equations,
not from the model code: it imports neither rollaway.effects nor rollaway.identify.synth/model).

Only Table 1's values are taken from :func:`rollaway.model.parameters.paper`; the physics below is
written out again: eq. (10) cooling (or a radiating drum integrated by RK4), eq. (24) lever
displacement, eq. (16a/b) clamp force, eqs. (18)–(21) self-energising, eq. (17b) torque.

Hidden effects come in three kinds (see ``EFFECTS``): the catalogue's physics in the
catalogue's form ("exact"), the catalogue's physics in other forms ("other": friction
quadratic in T, fade above a temperature, a sigmoid modulus drop, creep as a power law, cable
creep logarithmic in time), and
physics the catalogue lacks ("outside": a ratchet step, a periodic disturbance).  Sampling
every 1, 5 or 15 min or irregular (each test its own grid), Student-t noise (heavy tails),
T_0 spread over 100–300 °C, one direction or both.
"""
from __future__ import annotations

import numpy as np

from rollaway.bench.measurements import Measurements
from rollaway.model.parameters import paper

SAMPLING = {"1min": 60.0, "5min": 300.0, "15min": 900.0, "irregular": None}
HIGH_RATE = {"1Hz": 1.0, "10Hz": 0.1, "100Hz": 0.01}     # bench logs as rigs write them (tests of the reduction)
SIGMA_SB = 5.670374419e-8

# name: (kind, catalogue effect the diagnosis should name or None)
EFFECTS = {
    "friction_linear": ("exact", "friction_temperature"),
    "creep_exponential": ("exact", "lining_creep"),
    "cable_exponential": ("exact", "cable_relaxation"),
    "gap": ("exact", "installation_gap"),
    "modulus_linear": ("exact", "modulus_temperature"),
    "radiation": ("exact", "radiation_cooling"),
    "zero_offset": ("exact", "torque_zero_offset"),
    "friction_quadratic": ("other", "friction_temperature"),
    "friction_fade_above": ("other", "friction_temperature"),
    "modulus_sigmoid": ("other", "modulus_temperature"),
    "creep_power_law": ("other", "lining_creep"),
    "cable_log": ("other", "cable_relaxation"),
    "ratchet_step": ("outside", None),
    "periodic_disturbance": ("outside", None),
}


def _times(rng, scheme: str, duration: float) -> np.ndarray:
    if scheme in HIGH_RATE:
        return np.round(np.arange(0.0, duration + 1e-9, HIGH_RATE[scheme]), 6)
    if SAMPLING[scheme] is not None:
        return np.arange(0.0, duration + 1e-9, SAMPLING[scheme])
    gaps = rng.uniform(60.0, 600.0, 200)
    t = np.concatenate([[0.0], np.cumsum(gaps)])
    return np.round(t[t <= duration], 1)


def _drum_temperature(t, t0, amb, h, p, emissivity=0.0):
    cap = p.drum_density_kg_m3 * p.drum_specific_heat_J_kgK * p.drum_volume_m3
    if emissivity == 0.0:
        return amb + (t0 - amb) * np.exp(-t * h * p.cooled_area_m2 / cap)
    # RK4 on a 5 s grid, all samples at once, then interpolated at the sample times
    grid = np.arange(0.0, t.max() + 5.0, 5.0)
    temp = np.empty((grid.size, t.size))
    y = np.array(t0, float)

    def rate(y_):
        return -(h * p.cooled_area_m2 * (y_ - amb)
                 + emissivity * SIGMA_SB * p.cooled_area_m2 * ((y_ + 273.15) ** 4 - (amb + 273.15) ** 4)) / cap
    for i in range(grid.size):
        temp[i] = y
        k1 = rate(y)
        k2 = rate(y + 2.5 * k1)
        k3 = rate(y + 2.5 * k2)
        k4 = rate(y + 5.0 * k3)
        y = y + 5.0 / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
    idx = np.minimum((t / 5.0).astype(int), grid.size - 2)
    frac = t / 5.0 - idx
    cols = np.arange(t.size)
    return temp[idx, cols] * (1 - frac) + temp[idx + 1, cols] * frac


# Drums that are not the paper's: ordinary departures a bench engineer meets (keys: Table 1 names,
# plus "u6_slope"/"u6_offset" for eq. (24) and "ambient_C" for the lab's air).
OTHER_DRUMS = {
    "radius_100mm": {"drum_radius_m": 0.100},
    "arm_80mm": {"shoe_arm_normal_m": 0.080},
    "eq24_own": {"u6_slope": 4.3e-7, "u6_offset": -2.4e-5},
    "thick_soft_lining": {"lining_thickness_m": 0.005, "lining_modulus_Pa": 1.7e8},
    "heavy_drum": {"drum_volume_m3": 9.5e-4},
    "all_together": {"drum_radius_m": 0.095, "shoe_arm_normal_m": 0.075, "u6_slope": 3.6e-7, "u6_offset": -1.0e-5,
                     "lining_thickness_m": 0.0045, "lining_modulus_Pa": 2.4e8, "drum_volume_m3": 8.4e-4,
                     "ambient_C": 21.0},
}

# More drums, first used after every calibration and band rule was written (held out from that work): a wider and
# heavier drum with more lining, longer shoe arms, a shorter friction arm (a weaker self-energising ratio), a thin
# stiff lining, an eq. (24) law that bears later, and a light drum with every departure at once.
MORE_DRUMS = {
    "wide_drum": {"drum_radius_m": 0.115, "drum_volume_m3": 1.1e-3, "lining_area_m2": 0.0062},
    "long_arms": {"shoe_arm_normal_m": 0.09, "shoe_arm_friction_m": 0.065},
    "short_friction_arm": {"shoe_arm_friction_m": 0.05},
    "thin_stiff_lining": {"lining_thickness_m": 0.0035, "lining_modulus_Pa": 3.0e8},
    "eq24_late": {"u6_slope": 3.4e-7, "u6_offset": -3.2e-5},
    "light_mixed": {"drum_radius_m": 0.085, "drum_volume_m3": 6.5e-4, "shoe_arm_normal_m": 0.065,
                    "shoe_arm_friction_m": 0.058, "lining_thickness_m": 0.0045, "lining_modulus_Pa": 1.9e8,
                    "ambient_C": 12.0},
}


def truth_parameters(drum: dict | None = None):
    """The paper's set with *drum*'s departures (Table 1 names); eq. (24) and ambient returned apart."""
    import dataclasses
    d = dict(drum or {})
    slope, offset, amb = d.pop("u6_slope", 3.89e-7), d.pop("u6_offset", -1.5e-5), d.pop("ambient_C", 27.0)
    return dataclasses.replace(paper(), **d), slope, offset, amb


def true_torque(F, t, direction, *, drum=None, mu=0.37, h=34.0, t0=200.0, effects=()):
    """The generator's noiseless torque of one drum at hand force *F* over times *t* (hidden *effects* included,
    per-test transducer offsets excluded: they are not on the road)."""
    p, slope, offset, amb = truth_parameters(drum)
    t = np.asarray(t, float)
    e = set(effects)
    temp = _drum_temperature(t, np.full(t.shape, t0), np.full(t.shape, amb), h, p, 0.8 if "radiation" in e else 0.0)
    n = t.shape
    return _torque(p, slope, offset, np.full(n, float(F)), t, np.full(n, t0), temp, np.full(n, amb),
                   np.full(n, direction), e, mu)


def _torque(p, u6_slope, u6_offset, F, t, t0, temp, amb, dirs, e, mu):
    """Noiseless torque of one drum with the hidden effects *e* (the road's torque: no per-test offsets)."""
    dT = temp - t0
    u6 = u6_slope * F + u6_offset                               # eq. (24)
    if "cable_exponential" in e:
        u6 = u6 - 8e-6 * (1 - np.exp(-t / 600.0))
    if "cable_log" in e:                                        # logarithmic creep of the cable (no end value)
        u6 = u6 - 1.2e-6 * np.log1p(t / 120.0)
    if "ratchet_step" in e:
        u6 = u6 - 7e-6 * (t >= 1650.0)
    e_l = np.full_like(t, p.lining_modulus_Pa)
    if "modulus_linear" in e:
        e_l = e_l * np.maximum(1 - 1e-3 * (temp - amb), 0.05)
    if "modulus_sigmoid" in e:
        e_l = e_l * (1 - 0.35 / (1 + np.exp(-(temp - 170.0) / 15.0)))
    gap = 1e-3 if "gap" in e else 0.0
    k_d, k_l = p.drum_area_m2 * p.drum_modulus_Pa, p.lining_area_m2 * e_l
    ll = p.lining_thickness_m + gap
    f0 = k_d * (p.drum_expansion_per_K * dT + (u6 * k_l + k_l * p.lining_expansion_per_K * dT * ll
                                               - k_d * p.drum_expansion_per_K * dT * ll)
                / (k_l * p.drum_thickness_m + k_d * ll))        # eq. (16a/b)
    if "creep_exponential" in e:
        f0 = f0 * (1 - 0.1 * (1 - np.exp(-t / 900.0)))
    if "creep_power_law" in e:
        f0 = f0 * (1 - 0.12 * (t / 3600.0) ** 0.35)
    m = np.full_like(t, mu)
    if "friction_linear" in e:
        m = m * (1 + 1.2e-3 * (temp - 100.0))
    if "friction_quadratic" in e:
        m = m * (1 + 4e-6 * (temp - 27.0) ** 2) / (1 + 4e-6 * 73.0 ** 2)
    if "friction_fade_above" in e:
        m = m * (1 - 1.5e-3 * np.maximum(temp - 150.0, 0.0))
    s = np.where(dirs == "downhill", 1.0, -1.0)
    fl = np.maximum(f0 * p.shoe_arm_normal_m / (p.shoe_arm_normal_m - s * m * p.shoe_arm_friction_m), 0.0)
    torque = m * fl * p.drum_radius_m                            # eq. (17b)
    if "periodic_disturbance" in e:
        torque = torque * (1 + 0.04 * np.sin(2 * np.pi * t / 1500.0))
    return torque

def generate(effects=(), *, sampling="5min", seed=0, n_forces=4, directions=("downhill", "uphill"),
             duration_s=3600.0, t0_range=(100.0, 300.0), noise_torque_Nm=8.0, noise_torque_rel=0.0,
             noise_temp_C=1.5, tail_dof=4.0, mu=0.37, h=34.0, ambient_drift_C=0.0, drum: dict | None = None,
             forces=None) -> Measurements:
    """Bench data with *effects* hidden (names of ``EFFECTS``); Student-t noise with *tail_dof*
    degrees of freedom scaled to the given standard deviations (``tail_dof=None``: Gaussian).
    *drum*: departures from the paper's drum (see ``OTHER_DRUMS``); *forces*: the hand forces [N]."""
    p, u6_slope, u6_offset, amb0 = truth_parameters(drum)
    rng = np.random.default_rng(seed)
    forces = np.linspace(190.0, 350.0, n_forces) if forces is None else np.asarray(forces, float)
    rows = {k: [] for k in ("id", "dir", "F", "t", "t0", "amb")}
    for d in directions:
        for f in forces:
            t = _times(rng, sampling, duration_s)
            t0 = rng.uniform(*t0_range)
            rows["id"] += [f"{d[0].upper()}{int(f)}"] * t.size
            rows["dir"] += [d] * t.size
            rows["F"] += [f] * t.size
            rows["t"] += list(t)
            rows["t0"] += [t0] * t.size
            rows["amb"] += list(amb0 + ambient_drift_C * (t / duration_s - 0.5))
    ids, dirs = np.array(rows["id"]), np.array(rows["dir"])
    F, t, t0, amb = (np.array(rows[k], float) for k in ("F", "t", "t0", "amb"))
    tests, test_of = np.unique(ids, return_inverse=True)
    e = set(effects)
    # drum temperature: eq. (10), or with radiation; a drifting ambient enters through the ODE (Euler, 1 s)
    if ambient_drift_C:
        temp = np.empty_like(t)
        cap = p.drum_density_kg_m3 * p.drum_specific_heat_J_kgK * p.drum_volume_m3
        for k in range(len(tests)):
            r = np.flatnonzero(test_of == k)
            fine = np.arange(0.0, t[r].max() + 1.0, 1.0)
            a = np.interp(fine, t[r], amb[r])
            y = np.empty_like(fine)
            y[0] = t0[r[0]]
            for i in range(1, fine.size):
                y[i] = y[i - 1] - h * p.cooled_area_m2 * (y[i - 1] - 0.5 * (a[i] + a[i - 1])) / cap
            temp[r] = np.interp(t[r], fine, y)
    else:
        temp = _drum_temperature(t, t0, amb, h, p, 0.8 if "radiation" in e else 0.0)
    torque = _torque(p, u6_slope, u6_offset, F, t, t0, temp, amb, dirs, e, mu)
    if "zero_offset" in e:
        torque = torque + rng.normal(0.0, 25.0, len(tests))[test_of]

    def noise(n):
        if tail_dof is None:
            return rng.standard_normal(n)
        return rng.standard_t(tail_dof, n) / np.sqrt(tail_dof / (tail_dof - 2.0))
    torque_m = torque + noise(t.size) * np.hypot(noise_torque_Nm, noise_torque_rel * torque)
    temp_m = temp + noise(t.size) * noise_temp_C
    out = Measurements(ids, dirs, F, t, np.round(temp_m, 3), np.round(torque_m, 3),
                       amb if ambient_drift_C else None, source=f"independent({sampling}, seed={seed})")
    out.truth = {"mu_drum": mu, "heat_transfer_W_m2K": h, "initial_temp_C": t0, "effects": list(effects),
                 "drum": dict(drum or {}),
                 "noise_torque_Nm": noise_torque_Nm, "noise_temp_C": noise_temp_C}
    return out
