# %% [markdown]
# # A roll-away in MuJoCo
#
# A car parked hot, with a weak pull on the lever: 220 N, facing uphill on 20 %, the drums at
# 200 °C. As the drums cool they contract and the clamp force falls (eq. 16a); at some point the
# brake lets go. The analytic check says when; the MuJoCo simulation shows it happen, with the
# tyres, the load transfer and the car rolling back.

# %%
# %matplotlib inline
import base64
import tempfile
from pathlib import Path

from matplotlib.figure import Figure
from IPython.display import HTML

import rollaway

here = Path.cwd()
ROOT = next(p for p in [here, *here.parents] if (p / "pyproject.toml").exists())
scenario = ROOT / "scenarios" / "hot-parking-rollaway.toml"
print(scenario.read_text())

# %% [markdown]
# ## What the analytic check predicts

# %%
v = rollaway.hold("paper", grade_pct=20, hand_force_N=220, direction="uphill",
                  occupants=1, duration_s=1800)
print(f"holds: {v.holds}; the brake slips at t = {v.slip_time_s:.0f} s")
print(f"least hand force that holds 30 min: {v.least_hand_force_N:.0f} N")

# %% [markdown]
# ## Simulate it, and render the run
#
# `rollaway.simulate` takes a scenario file (or its keys as arguments). `render=` writes a GIF,
# MP4 or PNG; a hold plays as a time-lapse, real time from 2 s before the roll-away.

# %%
gif = Path(tempfile.mkdtemp()) / "hot-parking.gif"
r = rollaway.simulate(scenario, render=gif,
                      render_options={"size": (320, 180), "fps": 8})
print(f"outcome: {r.outcome}; roll-away at t = {r.rollaway_time_s:.0f} s")
print(f"analytic slip: {r.analytic_time_to_slip_s:.0f} s "
      "(the car passes the 5 cm gate a few seconds after the brake slips)")
HTML('<img alt="the car rolls back as the drum cools" src="data:image/gif;base64,'
     + base64.b64encode(gif.read_bytes()).decode() + '">')

# %% [markdown]
# ## The trace
#
# The result carries the recorded trace: displacement along the slope and the rear drums'
# capacity against the demand.

# %%
tr = r.trace
fig = Figure(figsize=(7, 5))
a1, a2 = fig.subplots(2, 1, sharex=True)
a1.plot(tr.time_s, abs(tr.displacement_m) * 100)
a1.axhline(5, color="r", lw=0.8, ls="--", label="roll-away gate, 5 cm")
a1.set(ylabel="|travel| [cm]", yscale="symlog", ylim=(0, None))
a1.legend()
a2.plot(tr.time_s, tr.capacity_Nm.sum(axis=1), label="rear drums")
a2.axhline(r.demand_Nm, color="k", lw=1, label="demand T_req (eq. 23)")
a2.set(xlabel="time [s]", ylabel="torque [N·m]")
a2.legend()
fig

# %% [markdown]
# ## The same car with a firmer pull
#
# Scenario keys given as arguments override the file's: 300 N holds for the whole half hour.

# %%
held = rollaway.simulate(scenario, hand_force_N=300)
print(held.outcome, f"least margin {held.min_margin:.2f}")
