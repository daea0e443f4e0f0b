"""Make the bundled bench data set with a hidden effect, independently of rollaway's model code.

The truth: the paper's drum (its equations written out here) whose clamp force relaxes by 12 %
with a 20-minute time constant (lining creep), μ_d = 0.37, h = 38 W/(m² K); 8 tests (4 hand
forces × 2 directions), a sample every 2 minutes for an hour, start temperatures around
200 °C, torque noise 6 N·m and temperature noise 1 °C.  rollaway is not told the effect.

    python examples/identify/make_bench_data.py > examples/identify/bench-hidden-effect.csv
"""
import sys

import numpy as np

# Ishak et al. 2018 Table 1 and the eq. (24) fit; arms and h as assumed in docs/model.md
RHO, CP, VOL, A_CONV, T_AMB = 7100.0, 586.0, 7.7e-4, 0.08, 27.0
A_D, E_D, A_L, E_L = 2.2e-3, 1.1e11, 4.8e-3, 2.1e8
ALPHA_D, ALPHA_L, L_OD, L_OL = 1.1e-5, 1.2e-5, 0.008, 0.004
R_D, L_F, L_FR = 0.09, 0.07, 0.06
MU, H = 0.37, 38.0
CREEP_FRACTION, CREEP_TAU_S = 0.12, 1200.0


def torque_Nm(t, force, sign, t0):
    tau = RHO * CP * VOL / (H * A_CONV)
    temp = T_AMB + (t0 - T_AMB) * np.exp(-t / tau)
    dT = temp - t0
    u6 = 3.89e-7 * force - 1.5e-5
    k_d, k_l = A_D * E_D, A_L * E_L
    f0 = k_d * (ALPHA_D * dT + (u6 * k_l + (k_l * ALPHA_L - k_d * ALPHA_D) * dT * L_OL) / (k_l * L_OD + k_d * L_OL))
    f0 *= 1.0 - CREEP_FRACTION * (1.0 - np.exp(-t / CREEP_TAU_S))
    return MU * f0 * L_F / (L_F - sign * MU * L_FR) * R_D, temp


def main(seed: int = 2026) -> None:
    rng = np.random.default_rng(seed)
    t = np.arange(0, 3601, 120.0)
    out = sys.stdout
    out.write("test_id,direction,hand_force_N,time_s,drum_temp_C,torque_Nm\n")
    k = 0
    for direction, sign in (("downhill", 1.0), ("uphill", -1.0)):
        for force in (200.0, 250.0, 300.0, 350.0):
            k += 1
            t0 = 200.0 + rng.normal(0, 15)
            q, temp = torque_Nm(t, force, sign, t0)
            q = q + rng.normal(0, 6.0, t.size)
            temp = temp + rng.normal(0, 1.0, t.size)
            for ti, xi, qi in zip(t, temp, q):
                out.write(f"T{k},{direction},{force:g},{ti:g},{xi:.2f},{qi:.2f}\n")


if __name__ == "__main__":
    main()
