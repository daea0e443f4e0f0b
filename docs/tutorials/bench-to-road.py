# %% [markdown]
# # From bench data to a roll-away probability
#
# The paper's model is a starting point, not the truth. Here bench measurements with a hidden
# physical effect (nobody told the tool which) go through the whole path:
#
# 1. load the measurements;
# 2. `diagnose`: which effect is the paper's model missing?
# 3. the calibrated model, with the covariance of its fitted values, saved as a file;
# 4. checked on tests it was not fitted on;
# 5. the roll-away probability of a parked car under that uncertainty.

# %%
# %matplotlib inline
import tempfile
from pathlib import Path

from matplotlib.figure import Figure
import numpy as np

import rollaway

here = Path.cwd()
ROOT = next(p for p in [here, *here.parents] if (p / "pyproject.toml").exists())
data = rollaway.load_measurements(ROOT / "examples/identify/bench-hidden-effect.csv")
data.to_frame().head()

# %% [markdown]
# Eight tests: hand forces 200–350 N, both directions, an hour each from about 200 °C. Keep the
# last two tests aside to judge the model on data it has not seen.

# %%
fit_tests, held_out_tests = data.tests[:6], data.tests[6:]
train = data.subset(np.isin(data.test_id, fit_tests))
held_out = data.subset(np.isin(data.test_id, held_out_tests))
print(f"fit on {train.n_tests} tests ({len(train)} samples)")
print("held out:", held_out_tests)

# %% [markdown]
# ## Which effect is missing?

# %%
d = rollaway.diagnose(train)
print("verdict:", d.verdict)
for line in d.evidence:
    print(" -", line)

# %% [markdown]
# ## The calibrated model, as a file any command reads
#
# `save_model` writes a TOML file a person can read: the base set, the fitted values, the
# effect, the covariance and where the values came from. `rollaway.DrumModel(path)` (or
# `--params path` on the command line) reads it back.

# %%
out = Path(tempfile.mkdtemp())
path = d.save_model(out / "calibrated.toml")
print(path.read_text())
calibrated = rollaway.DrumModel(path)
paper = rollaway.DrumModel("paper")

# %% [markdown]
# ## On the held-out tests
#
# Each model predicts the torque of the tests it was not fitted on (each test's own start
# temperature and hand force).

# %%
fig = Figure(figsize=(7, 3.8))
ax = fig.subplots()
for test in held_out.tests:
    one = held_out.subset(held_out.test_id == test)
    ax.plot(one.time_s / 60, one.torque_Nm, "k.", ms=4)
    for m, style in ((paper, "--"), (calibrated, "-")):
        s = m.evaluate(one.time_s, one.hand_force_N, one.sign,
                       initial_temp_C=one.initial_temp_C)
        name = "paper" if m is paper else "calibrated"
        ax.plot(one.time_s / 60, s.torque_Nm, style, label=f"{test}: {name}")
ax.set(xlabel="time [min]", ylabel="torque per drum [N·m]",
       title="held-out tests: measured (dots) and predicted")
ax.legend(fontsize=8)
fig

# %%
def rmse(m):
    s = m.evaluate(held_out.time_s, held_out.hand_force_N, held_out.sign,
                   initial_temp_C=held_out.initial_temp_C)
    return float(np.sqrt(np.mean((s.torque_Nm - held_out.torque_Nm) ** 2)))


print("torque RMSE on the held-out tests:")
print(f"  paper {rmse(paper):.1f} N·m, calibrated {rmse(calibrated):.1f} N·m")

# %% [markdown]
# ## On the road: 30 %, facing downhill, five occupants, 250 N, parked an hour from 200 °C
#
# The paper model says it holds. The calibrated model, with 1 000 draws from the covariance of
# its fitted values:

# %%
case = dict(grade_pct=30, hand_force_N=250, direction="downhill", occupants=5,
            duration_s=3600)
for name, m in (("paper", paper), ("calibrated", calibrated)):
    v = rollaway.hold(m, **case)
    verdict = "holds" if v.holds else f"rolls away at {v.slip_time_s:.0f} s"
    print(f"{name:>10}: least margin {v.brake_margin_min:.3f}, {verdict}; "
          f"least hand force {v.least_hand_force_N:.0f} N")
risky = rollaway.hold(calibrated, **case, uncertainty=1000)
print(f"roll-away probability: {risky.rollaway_probability:.3f}")

# %%
fig = Figure(figsize=(7, 3))
ax = fig.subplots()
ax.hist(risky.risk.least_margin, bins=40)
ax.axvline(1, color="r")
ax.set(xlabel="least margin over the hour [–]", ylabel="draws",
       title="calibrated model, 1 000 draws")
fig

# %% [markdown]
# The report `d.report("diagnose.html")` holds the evidence in full (candidates, fit
# statistics, residuals, interactive figures); `rollaway diagnose DATA.csv --report` writes the
# same page from the command line.
