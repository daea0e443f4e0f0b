"""The Typer application object; commands register themselves in their own modules."""
import typer

app = typer.Typer(
    name="rollaway",
    help="Will this parked car roll away? Drum parking-brake model (Ishak et al. 2018) + MuJoCo simulator.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    rich_markup_mode=None,
)
