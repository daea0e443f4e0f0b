"""Output files: missing folders are created; a file in the way is a one-line error, exit 2."""
import pytest


def test_synth_and_diagnose_create_output_folders(run_cli, tmp_path):
    data = tmp_path / "a" / "bench.csv"
    code, _, err = run_cli("synth", "--seed", 3, "--out", data)
    assert code == 0, err
    code, _, err = run_cli("diagnose", data, "--json", tmp_path / "b" / "d.json", "--report", tmp_path / "c" / "d.html")
    assert code == 0, err
    assert (tmp_path / "b" / "d.json").is_file() and (tmp_path / "c" / "d.html").is_file()


@pytest.mark.parametrize("command", [
    ["synth", "--out", "{f}/x.csv"],
    ["paper", "--out", "{f}/figs"],
])
def test_file_in_the_way(run_cli, tmp_path, command):
    f = tmp_path / "file"
    f.write_text("")
    code, _, err = run_cli(*[c.format(f=f) for c in command])
    assert code == 2 and "Traceback" not in err and len(err.strip().splitlines()) == 1
