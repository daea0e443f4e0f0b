"""Lab-style exports of canonical bench data (for the reader tests): renamed columns with units in the
header, °F, milliseconds, lbf, one file per test with a manifest, Parquet."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

COLUMNS_TOML = """[columns]
time_s = "Time [ms]"
torque_Nm = "Torque [lbf·ft]"
drum_temp_C = { column = "T_drum", unit = "degF" }
hand_force_N = { column = "Lever force", unit = "lbf" }
direction = "Facing"
"""
LBF_FT = 1.3558179483314004
LBF = 4.4482216152605


def lab_frame(frame: pd.DataFrame) -> pd.DataFrame:
    """The canonical columns renamed and converted as a lab exports them."""
    return pd.DataFrame({
        "Time [ms]": np.round(frame["time_s"].to_numpy() * 1000.0, 3),
        "Torque [lbf·ft]": frame["torque_Nm"].to_numpy() / LBF_FT,
        "T_drum": frame["drum_temp_C"].to_numpy() * 9.0 / 5.0 + 32.0,
        "Lever force": frame["hand_force_N"].to_numpy() / LBF,
        "Facing": frame["direction"].to_numpy(),
        "Comment": "",
    })


def export_folder(data, folder: Path, kind: str = "csv", manifest: bool = True) -> Path:
    """One file per test (named after it), lab columns; direction and force in a manifest.csv if *manifest*."""
    folder.mkdir(parents=True, exist_ok=True)
    frame = data.to_frame()
    rows = []
    for tid, part in frame.groupby("test_id", sort=False):
        lab = lab_frame(part)
        if manifest:
            lab = lab.drop(columns=["Lever force", "Facing"])
            rows.append({"test_id": tid, "direction": part["direction"].iloc[0],
                         "hand_force_N": part["hand_force_N"].iloc[0]})
        if kind == "parquet":
            lab.to_parquet(folder / f"{tid}.parquet", index=False)
        else:
            lab.to_csv(folder / f"{tid}.csv", index=False)
    if manifest:
        pd.DataFrame(rows).to_csv(folder / "manifest.csv", index=False)
    (folder / "columns.toml").write_text(COLUMNS_TOML, encoding="utf-8")
    return folder


def export_file(data, path: Path) -> Path:
    """All tests in one lab-style file (CSV or Parquet by suffix) with a 'Test' column."""
    frame = data.to_frame()
    lab = lab_frame(frame)
    lab.insert(0, "Test", frame["test_id"].to_numpy())
    if path.suffix == ".parquet":
        lab.to_parquet(path, index=False)
    else:
        lab.to_csv(path, index=False)
    (path.parent / "columns.toml").write_text(COLUMNS_TOML + 'test_id = "Test"\n', encoding="utf-8")
    return path
