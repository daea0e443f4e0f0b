"""Import paths of the previous release still work, warn once and give the very same objects."""
import importlib
import sys
import warnings

import pytest

from rollaway._moved import MOVED


@pytest.mark.parametrize("old", sorted(MOVED))
def test_an_old_module_path_is_the_new_module_with_a_warning(old):
    sys.modules.pop(old, None)
    with pytest.warns(DeprecationWarning, match=MOVED[old].replace(".", r"\.")):
        module = importlib.import_module(old)
    assert module is importlib.import_module(MOVED[old])


def test_old_names_of_the_identify_and_uncertainty_packages():
    import rollaway.identify
    import rollaway.uncertainty
    from rollaway.bench.measurements import load_measurements
    from rollaway.uncertainty.draws import rollaway_risk
    with pytest.warns(DeprecationWarning, match=r"rollaway\.bench\.measurements\.load_measurements"):
        assert rollaway.identify.load_measurements is load_measurements
    with pytest.warns(DeprecationWarning, match=r"rollaway\.uncertainty\.draws\.rollaway_risk"):
        assert rollaway.uncertainty.rollaway_risk is rollaway_risk
    with pytest.raises(AttributeError):
        rollaway.identify.no_such_name


def test_the_new_paths_do_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        from rollaway.bench import load_measurements  # noqa: F401
        from rollaway.identify import BenchModel  # noqa: F401
        from rollaway.model import DrumModel, load_model  # noqa: F401
