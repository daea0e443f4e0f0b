# %% [markdown]
# # Check a design against the regulations
#
# Does the bundled car hold on 20 % with 400 N on the lever, as FMVSS 135 and UN R13-H ask?
# Where does it stop holding, and why? This tutorial answers with the paper's analytic check
# (seconds), then with the MuJoCo gate that CI runs.
#
# Everything here uses only `import rollaway`.

# %%
# %matplotlib inline
import numpy as np
from matplotlib.figure import Figure

import rollaway

model = rollaway.DrumModel("paper")   # Ishak et al. 2018, Table 1 + what it does not give
model

# %% [markdown]
# ## One case: FMVSS 135, laden, facing downhill
#
# `rollaway.hold` checks one parked case over a duration. The brake holds while its margin
# `2·T_gen(t)/T_req` stays ≥ 1 (the torque falls as the drum cools from 200 °C); the rear tyres
# hold while their adhesion margin stays ≥ 1.

# %%
v = rollaway.hold(model, grade_pct=20, hand_force_N=400, direction="downhill",
                  occupants=5, duration_s=300)
print(f"holds: {v.holds}")
print(f"least brake margin {v.brake_margin_min:.2f}, tyre margin {v.tyre_margin:.2f}")
print(f"least hand force that holds: {v.least_hand_force_N:.0f} N")

# %% [markdown]
# ## Every preset at once
#
# `rollaway.check(..., analytic=True)` runs the same check on each regulation preset, in both
# facings. `paper30` is the paper's own 30 % case: facing downhill the brake holds, but the
# unloaded rear tyres slide, which the paper's brake-only check does not see.

# %%
result = rollaway.check(["all"], analytic=True)
print("every case holds" if result.passed else f"{len(result.failed)} case(s) fail")
result.table()[["preset", "direction", "grade_pct", "hand_force_N",
                "min_brake_margin", "tyre_margin", "verdict", "reason"]]

# %% [markdown]
# ## How the margin falls as the drum cools
#
# Facing uphill is the critical direction for the brake (the trailing-shoe geometry, eqs. 18–21).
# The hold margin over an hour, for three hand forces:

# %%
t = np.linspace(0, 3600, 361)
fig = Figure(figsize=(7, 3.5))
ax = fig.subplots()
for force in (200, 250, 400):
    margin = rollaway.hold.hold_margin(model, t, force, 20, "uphill", 5)
    ax.plot(t / 60, margin, label=f"{force} N")
ax.axhline(1, color="k", lw=1)
ax.set(xlabel="time parked [min]", ylabel="brake hold margin [–]",
       title="20 %, facing uphill, laden, from 200 °C")
ax.legend()
fig

# %% [markdown]
# The least hand force that holds for the whole hour, solved in closed form:

# %%
v = rollaway.hold(model, grade_pct=20, hand_force_N=250, direction="uphill",
                  occupants=5, duration_s=3600)
print("250 N:", "holds" if v.holds else f"slips at {v.slip_time_s:.0f} s")
print(f"least hand force for the hour: {v.least_hand_force_N:.0f} N")

# %% [markdown]
# ## The gate CI runs: the same presets simulated in MuJoCo
#
# Without `analytic=True`, every case is simulated: the car stands on the tilted road, held by
# the rear drums, and fails if it slips or skids. This is what `rollaway check` runs in CI
# (see [the gate in a CI pipeline](../how-to/ci-gate.html)).

# %%
gate = rollaway.check(["fmvss135", "unr13h"])
print("PASS" if gate.passed else "FAIL")
gate.table()[["target", "direction", "brake_margin_min", "tyre_margin",
              "sim_outcome", "verdict"]]
