"""``rollaway paper``: regenerate the analogues of the paper's Figures 9–14."""
from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from rollaway.cli import options as opt

from rollaway.model.drum_model import load_model


def paper(
    out: Path = typer.Option(Path("renders/paper"), "--out", help="folder for the PNGs"),
    params: Optional[str] = opt.params_option(),
) -> None:
    """Draw the analogues of the paper's Figures 9–14 as PNGs: cooling, torque vs time, FMVSS check, μ_d, occupants."""
    from rollaway.errors import UserError
    from rollaway.figures.paper import paper_figures
    p = load_model(params)
    if out.exists() and not out.is_dir():
        raise UserError(f"--out '{out}' is a file; give a folder for the PNGs")
    for path in paper_figures(p, out):
        typer.echo(f"wrote {path}")


def register(app: typer.Typer) -> None:
    app.command("paper")(paper)
