# %% [markdown]
# # Fleet risk: a roll-away rate in ppm, what drives it, and the design that meets a target
#
# One hold check answers for one car. A production fleet scatters: the lining's μ_d (the paper's
# Table 1 gives 0.3–0.6), the drivers' pull on the lever, the drum's temperature when parked, the
# load. Here: a population file → the fraction of cars that roll away with its 95 % interval →
# which tolerance drives it → the least hand force that keeps it under a target.
# The method, its assumptions and its measured accuracy are on the [fleet-risk page](../fleet-risk.html).

# %%
from pathlib import Path

from IPython.display import Image

import rollaway

here = Path.cwd()
ROOT = next(p for p in [here, *here.parents] if (p / "pyproject.toml").exists())
population = ROOT / "scenarios" / "populations" / "fmvss135-production.toml"
print(population.read_text())

# %% [markdown]
# ## The rate
#
# `method="auto"` runs a pilot Monte Carlo sample first; too few of its cars roll away for a useful
# interval here, so it switches to importance sampling around the most probable failing cars
# (FORM design points), one stratum per number of occupants.

# %%
r = rollaway.risk(population, seed=1)
print(r.summary())

# %% [markdown]
# The same with plain Monte Carlo, for comparison: a million cars see almost no roll-away, so its
# interval spans from 0 to a few ppm — the rare-event estimate above is narrower with far fewer cars.

# %%
mc = rollaway.risk(population, method="mc", samples=1_000_000, seed=1)
print(f"Monte Carlo {mc.ppm:.3g} ppm, 95 % interval {mc.ci95[0] * 1e6:.3g}–{mc.ci95[1] * 1e6:.3g} ppm "
      f"({mc.estimate.samples} cars)")

# %% [markdown]
# ## What drives it
#
# Sobol indices of the least brake margin over the hold (SALib): the first-order index is the share
# of the margin's variance an input explains alone, the total index includes its interactions.

# %%
import tempfile

out = Path(tempfile.mkdtemp())
r = rollaway.risk(population, method="mc", samples=100_000, sensitivity=True, chart=out / "drivers.png")
print(r.summary())
Image(filename=str(out / "drivers.png"))

# %% [markdown]
# ## The design that meets a target
#
# The hand force is varied in this population (drivers differ), so the design question here is the
# lining's: the least lower spec limit of μ_d (`mu_drum.lower`: parts below it are rejected) that
# keeps the rate at or below 0.1 ppm.

# %%
r = rollaway.risk(population, method="mc", samples=100_000, design="mu_drum.lower", target=1e-7,
                  chart=out / "design.png")
d = r.design
print(f"{d.side} {d.name} = {d.value:.4f}: rate {d.probability * 1e6:.3g} ppm ≤ target {d.target * 1e6:g} ppm "
      f"({d.method})")
Image(filename=str(out / "design.png"))

# %% [markdown]
# The same from the command line:
#
# ```bash
# rollaway risk scenarios/populations/fmvss135-production.toml --sensitivity --chart drivers.png
# rollaway risk scenarios/populations/fmvss135-production.toml --design mu_drum.lower --target 1e-7 --json
# ```
