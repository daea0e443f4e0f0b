import pytest


@pytest.fixture(scope="session")
def export_dir(tmp_path_factory):
    """One folder for the FMUs a test session exports."""
    return tmp_path_factory.mktemp("fmus")
