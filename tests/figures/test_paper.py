"""`rollaway paper`: the analogues of Figs. 9-14, and what they must show (paper's descriptions)."""
import numpy as np

from rollaway import drum_brake, paper
from rollaway.hold import required_torque


def test_paper_figures(run_cli, tmp_path):
    code, out, err = run_cli("paper", "--out", tmp_path / "fig")
    assert code == 0, err
    pngs = sorted(p.name for p in (tmp_path / "fig").glob("*.png"))
    assert len(pngs) == 6 and pngs[0] == "fig09_temperature.png"
    assert all((tmp_path / "fig" / n).stat().st_size > 10_000 for n in pngs)


def test_figure_claims_hold_in_the_model():
    p = paper()
    t = np.linspace(0, 3600, 361)
    temp = drum_brake(p, time_s=t, hand_force_N=300).drum_temp_C
    rate_early = (temp[0] - temp[50]) / 500.0                           # Fig. 9: fast drop before ~500 s,
    rate_late = (temp[50] - temp[-1]) / 3100.0                          # then more gradual
    assert rate_early > 3 * rate_late
    down = drum_brake(p, time_s=t, hand_force_N=400, direction="downhill").torque_Nm
    up = drum_brake(p, time_s=t, hand_force_N=400, direction="uphill").torque_Nm
    assert np.all(down > 1.8 * up)                                      # Figs. 10-11: downhill well above uphill
    t_req = required_torque(p, 20, 1)
    for mu, holds in ((0.1, False), (0.2, True)):                       # Fig. 13: holds above mu ~ 0.2
        s = drum_brake(p, time_s=t, hand_force_N=400, direction="uphill", mu_drum=mu)
        assert bool(np.all(2 * s.torque_Nm >= t_req)) is holds
