"""``rollaway chart``: least hand force against grade for one or more drum models, side by side."""
from __future__ import annotations

from pathlib import Path
from typing import List

import typer


def chart(
    params: List[str] = typer.Option(["paper"], "--params", metavar="MODEL",
                                     help="a set name, parameter file or model file (repeat to compare models)"),
    out: Path = typer.Option(Path("renders/design-chart.png"), "--out", metavar="FILE", help="PNG to write"),
    occupants: int = typer.Option(5, "--occupants", metavar="N", help="number of 70 kg occupants, 0–5"),
    duration_s: float = typer.Option(3600.0, "--duration-s", metavar="SECONDS", help="how long the car must hold"),
    t0_C: float = typer.Option(200.0, "--t0-C", metavar="CELSIUS", help="drum temperature when parked [°C]"),
    uncertainty: int = typer.Option(0, "--uncertainty", min=0, max=10000, metavar="N",
                                    help="shade each calibrated model's 5-95 % band of the least hand force from N "
                                         "predictive draws (parameters, competing effects, model error)"),
) -> None:
    """Design chart: least hand force that holds, against grade, both facings, for each --params model."""
    from rollaway.errors import UserError
    from rollaway.figures.design import design_chart
    from rollaway.hold import validate_occupants
    from rollaway.model.drum_model import load_model

    validate_occupants(occupants)
    if not (0 < duration_s <= 7 * 86400):
        raise UserError(f"--duration-s {duration_s:g} must be in (0, 604800] seconds, e.g. 3600")
    models = {Path(p).stem if p.endswith(".toml") else p: load_model(p) for p in params}
    if uncertainty and not any(m.covariance is not None or m.predictive for m in models.values()):
        raise UserError(f"--uncertainty {uncertainty} shades the band of calibrated models, and none of --params "
                        f"{', '.join(params)} is one (no [covariance]); give a model file saved by 'rollaway diagnose "
                        f"--save-model', or leave --uncertainty out")
    path = design_chart(models, out, occupants=occupants, duration_s=duration_s, initial_temp_C=t0_C,
                        uncertainty=uncertainty)
    typer.echo(f"wrote {path}")


def register(app: typer.Typer) -> None:
    app.command("chart")(chart)
