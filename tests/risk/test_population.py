"""Population files: distributions as scipy.stats defines them, the copula, and one-line errors for bad files."""
import numpy as np
import pytest
from scipy import stats

from rollaway.errors import UserError
from rollaway.risk import load_population

GOOD = """[vary]
mu_drum = { uniform = [0.3, 0.6] }
hand_force_N = { normal = [400, 35], truncate = [300, 480] }
initial_drum_temp_C = { triangular = [27, 120, 300] }
occupants = { choice = [0, 1, 5], weights = [3, 1, 1] }
heat_transfer_W_m2K = { lognormal = [40, 0.15] }

[[correlation]]
between = ["mu_drum", "initial_drum_temp_C"]
rho = -0.6
"""


def test_population_file_reads_and_the_copula_correlates_the_normal_scores(write_population):
    pop = load_population(write_population(GOOD))
    assert pop.names == ("mu_drum", "hand_force_N", "initial_drum_temp_C", "occupants", "heat_transfer_W_m2K")
    assert pop.directions == ("uphill",)
    v = pop.values_from_normal(np.random.default_rng(2).standard_normal((100_000, pop.dim)))
    z_mu = stats.norm.ppf((v["mu_drum"] - 0.3) / 0.3)
    z_t = stats.norm.ppf(stats.triang((120 - 27) / 273, 27, 273).cdf(v["initial_drum_temp_C"]))
    assert abs(np.corrcoef(z_mu, z_t)[0, 1] + 0.6) < 0.01
    assert abs(np.corrcoef(z_mu, v["hand_force_N"])[0, 1]) < 0.01


def test_a_varied_scenario_number_needs_no_fixed_value(write_population):
    head = 'grade_pct = 20\ndirection = "both"\noccupants = 5\nduration_s = 300\n'
    pop = load_population(write_population("[vary]\nhand_force_N = { normal = [400, 35] }\n", head=head))
    assert pop.directions == ("uphill", "downhill") and pop.fixed("hand_force_N") == pytest.approx(400)


BAD = [
    ("[vary]\nmu_drm = { uniform = [0.3, 0.6] }\n", ["vary.mu_drm", "mu_drum"]),
    ("[vary]\nmu_drum = { uniform = [0.6, 0.3] }\n", ["vary.mu_drum.uniform", "impossible"]),
    ("[vary]\nmu_drum = { normal = [0.4, -0.1] }\n", ["vary.mu_drum.normal", "standard deviation"]),
    ("[vary]\nmu_drum = { normal = [0.4, 0.2] }\n", ["vary.mu_drum", "physical range", "truncate"]),
    ("[vary]\nmu_drum = { unifrom = [0.3, 0.6] }\n", ["vary.mu_drum.unifrom", "uniform"]),
    ("[vary]\nmu_drum = { uniform = [0.3] }\n", ["vary.mu_drum.uniform", "2 numbers"]),
    ("[vary]\nmu_drum = { uniform = [0.3, 0.6], normal = [0.4, 0.01] }\n", ["vary.mu_drum", "exactly one"]),
    ("[vary]\nmu_drum = 0.4\n", ["vary.mu_drum", "inline table"]),
    ("[vary]\nmu_drum = { uniform = ['a', 0.6] }\n", ["vary.mu_drum.uniform"]),
    ("[vary]\nmu_drum = { triangular = [0.3, 0.7, 0.6] }\n", ["vary.mu_drum.triangular", "mode"]),
    ("[vary]\nmu_drum = { lognormal = [0, 0.1] }\n", ["vary.mu_drum.lognormal", "median"]),
    ("[vary]\nmu_drum = { uniform = [0.3, 0.6], truncate = [0.7, 0.8] }\n", ["vary.mu_drum.truncate", "no probability"]),
    ("[vary]\nmu_drum = { uniform = [0.3, 0.6], truncate = [0.5, 0.4] }\n", ["vary.mu_drum.truncate", "lower < upper"]),
    ("[vary]\noccupants = { uniform = [0, 5] }\n", ["vary.occupants", "whole number", "choice"]),
    ("[vary]\noccupants = { choice = [0, 2.5] }\n", ["vary.occupants.choice", "whole numbers"]),
    ("[vary]\noccupants = { choice = [0, 6] }\n", ["vary.occupants", "physical range"]),
    ("[vary]\noccupants = { choice = [0, 1], weights = [1] }\n", ["vary.occupants.weights", "2 numbers"]),
    ("[vary]\noccupants = { choice = [0, 1], weights = [-1, 2] }\n", ["vary.occupants.weights", "≥ 0"]),
    ("[vary]\nmu_drum = { normal = [0.4, 0.01], weights = [1] }\n", ["vary.mu_drum.weights", "choice"]),
    ("[vary]\nmu_drum = { uniform = [0.3, 0.6] }\n[[correlation]]\nbetween = [\"mu_drum\", \"hand_force_N\"]\n"
     "rho = 0.5\n", ["correlation[0].between", "hand_force_N", "not in [vary]"]),
    ("[vary]\nmu_drum = { uniform = [0.3, 0.6] }\nhand_force_N = { normal = [400, 35] }\n[[correlation]]\n"
     "between = [\"mu_drum\", \"hand_force_N\"]\nrho = 1.5\n", ["correlation[0].rho", "between -1 and 1"]),
    ("[vary]\nmu_drum = { uniform = [0.3, 0.6] }\nhand_force_N = { normal = [400, 35] }\n[[correlation]]\n"
     "between = [\"mu_drum\", \"hand_force_N\"]\nrh = 0.5\n", ["correlation[0].rh", "rho"]),
    ("[vary]\na = 1\n", ["vary.a"]),
    ("vary = 3\n", ["'vary'", "[vary] table"]),
    ("directoin = \"uphill\"\n", ["directoin", "direction"]),
]


@pytest.mark.parametrize("text, words", BAD)
def test_bad_population_is_a_one_line_error_naming_file_and_key(write_population, text, words):
    path = write_population(text)
    with pytest.raises(UserError) as exc:
        load_population(path)
    msg = str(exc.value)
    assert "\n" not in msg and str(path) in msg, msg
    for w in words:
        assert w in msg, (w, msg)


@pytest.mark.parametrize("head, words", [
    ('grade_pct = 20\ndirection = "sideways"\noccupants = 5\nhand_force_N = 400\nduration_s = 300\n', ["direction"]),
    ('grade_pct = 20\ndirection = "uphill"\noccupants = 5\nduration_s = 300\n', ["hand_force_N", "missing"]),
    ('grade_pct = "steep"\ndirection = "uphill"\noccupants = 5\nhand_force_N = 400\nduration_s = 300\n', ["grade_pct"]),
    ('params = "papr"\ngrade_pct = 20\ndirection = "uphill"\noccupants = 5\nhand_force_N = 400\nduration_s = 300\n',
     ["params", "paper"]),
])
def test_bad_fixed_values_are_one_line_errors_like_a_scenario(write_population, head, words):
    path = write_population("", head=head)
    with pytest.raises(UserError) as exc:
        load_population(path)
    msg = str(exc.value)
    assert "\n" not in msg and str(path) in msg
    for w in words:
        assert w in msg, (w, msg)


def test_the_example_populations_load():
    from pathlib import Path
    files = sorted((Path(__file__).resolve().parents[2] / "scenarios" / "populations").glob("*.toml"))
    assert len(files) >= 2
    for f in files:
        pop = load_population(f)
        assert pop.dim >= 3 and pop.description
