import pytest


@pytest.fixture
def write_population(tmp_path):
    """Write a population TOML (fixed FMVSS 135 uphill case + the given text) and return its path."""
    def _write(text: str, head: str | None = None, name: str = "pop.toml"):
        base = head if head is not None else ('grade_pct = 20\ndirection = "uphill"\noccupants = 5\n'
                                              'hand_force_N = 400\nduration_s = 300\ninitial_drum_temp_C = 200\n')
        p = tmp_path / name
        p.write_text(base + text, encoding="utf-8")
        return p
    return _write
