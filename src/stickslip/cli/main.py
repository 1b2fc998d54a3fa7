"""The ``stickslip`` command: a thin layer over the public Python API."""

from __future__ import annotations

import sys

import click
import typer

from stickslip.cli.common import EXIT_BAD_INPUT, BadInput, fail

app = typer.Typer(
    name="stickslip",
    help="Predict and suppress stick-slip in sliding systems on elastic foundations.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)


def _register() -> None:
    from stickslip.cli import simulate_command

    simulate_command.register(app)
    try:
        from stickslip.cli import absorber_commands
    except ImportError:  # the absorber commands are added by their own module
        return
    absorber_commands.register(app)


_register()


def run(argv: list[str] | None = None) -> None:
    """Console entry point: one line on stderr and exit code 2 for any bad input."""
    try:
        result = app(args=argv, standalone_mode=False)
    except click.exceptions.NoArgsIsHelpError:
        raise SystemExit(0) from None
    except click.exceptions.UsageError as exc:
        fail(exc.format_message())
    except click.exceptions.Abort:
        print("stickslip: aborted", file=sys.stderr)
        raise SystemExit(130) from None
    except (BadInput, ValueError) as exc:
        fail(str(exc))
    except click.exceptions.Exit as exc:
        raise SystemExit(exc.exit_code) from None
    if isinstance(result, int) and result not in (0,):
        raise SystemExit(result)
    _ = EXIT_BAD_INPUT


if __name__ == "__main__":
    run()
