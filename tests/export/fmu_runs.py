"""Running exported FMUs in FMPy and holding their outputs to the Python chain (helpers of tests/export)."""
import shutil

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy", reason="the test extra (FMPy) is not installed: pip install -e '.[test]'")
if shutil.which("gcc") is None:
    pytest.skip("gcc is not installed: the FMU's binary cannot be built (scripts/install.sh installs it)",
                allow_module_level=True)

TIMES_S = np.arange(0.0, 3601.0, 60.0)


def simulate(fmu, *, hand_force_N=400.0, uphill=False, initial_drum_temp_C=None, ambient_temp_C=None,
             stop_time_s=3600.0, output_interval_s=60.0):
    """One FMPy co-simulation run of *fmu*; the structured result array."""
    start = {"hand_force_N": hand_force_N, "facing_uphill": uphill}
    if initial_drum_temp_C is not None:
        start["initial_drum_temp_C"] = initial_drum_temp_C
    if ambient_temp_C is not None:
        start["ambient_temp_C"] = ambient_temp_C
    return fmpy.simulate_fmu(str(fmu), stop_time=stop_time_s, output_interval=output_interval_s, start_values=start)


def assert_same(result, series, rtol=1e-6):
    """FMU outputs against a BrakeSeries, relative to each value (near-zero values to the series' scale)."""
    for name, ref in (("torque_Nm", series.torque_Nm), ("drum_temp_C", series.drum_temp_C),
                      ("clamp_force_N", series.normal_force_N), ("lining_temp_C", series.lining_temp_C)):
        got, ref = np.asarray(result[name], float), np.asarray(ref, float)
        scale = np.maximum(np.abs(ref), 1e-9 * np.max(np.abs(ref)))
        zero = scale == 0.0                  # all zero (contact lost the whole run): must be zero too
        assert np.all(got[zero] == 0.0), name
        err = np.max(np.abs(got - ref)[~zero] / scale[~zero], initial=0.0)
        assert err <= rtol, (name, err)
