# %% [markdown]
# # A sweep and its design chart
#
# One case says whether a design holds; a sweep says *where* it holds. Here: grade × load ×
# hand force on the FMVSS 135 car, the analytic margin of every point, and the design chart an
# engineer reads off: the least hand force that holds for the whole duration against grade.
#
# The analytic pass takes milliseconds for thousands of points. MuJoCo then simulates only the
# points near the hold/roll boundary (`simulate="band"`); to keep this page quick to build the
# sweep below is analytic only (`simulate="none"`) — the [sweeps page](../sweeps.html) explains the
# band and [Dask](../how-to/dask.html) how to spread the simulations over a cluster.

# %%
import tempfile
from pathlib import Path

from IPython.display import Image

import rollaway
from rollaway.api import build_scenario
from rollaway.sweep import grid_spec

base = build_scenario(name="fmvss135", grade_pct=20, direction="uphill", occupants=5,
                      hand_force_N=400, duration_s=300, initial_drum_temp_C=200)
grid = {"grade_pct": [g / 2 for g in range(0, 101, 5)],      # 0, 2.5, ..., 50 %
        "occupants": [0, 1, 3, 5],
        "hand_force_N": [150, 200, 300, 400, 500],
        "direction": ["uphill", "downhill"]}
spec = grid_spec(base, grid, simulate="none")
print(len(spec.points), "points")

# %%
out = Path(tempfile.mkdtemp()) / "grade-load"
res = rollaway.sweep(spec, out)
print(f"{res.n_points} points in {res.wall_time_s:.2f} s")
print("wrote", ", ".join(f.name for f in res.files))
res.table[["grade_pct", "occupants", "hand_force_N", "direction",
           "brake_margin_min", "tyre_margin", "verdict"]].head(8)

# %% [markdown]
# ## The design chart
#
# Least hand force that holds for the whole 5 minutes against grade, per facing and load, with
# the 400 N regulation line; × marks the grade beyond which the rear tyres slide whatever the
# hand force. Facing uphill is the critical direction for the brake; facing downhill, the tyres.

# %%
Image(filename=str(out / "plots" / "design-chart.png"))

# %% [markdown]
# ## The hold / roll-away map
#
# Margin contours over grade and load (margin = 1 bold), hold green, roll-away red; the paper's
# brake-only boundary dashed.

# %%
maps = sorted((out / "plots").glob("map-grade-*.png"))
print([m.name for m in maps])
Image(filename=str(maps[0]))

# %% [markdown]
# ## The table is a pandas DataFrame
#
# For instance: the steepest grade that holds laden at 400 N, per facing.

# %%
t = res.table
laden = t[(t.occupants == 5) & (t.hand_force_N == 400) & (t.verdict == "hold")]
laden.groupby("direction")["grade_pct"].max()
