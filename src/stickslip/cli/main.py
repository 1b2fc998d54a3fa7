"""The ``stickslip`` command: a thin layer over the public Python API."""

from __future__ import annotations

import sys
import warnings
from typing import Annotated

import typer

from stickslip.cli.console import BadInput, fail

try:  # typer >= 0.25 ships its own copy of click
    from typer._click import exceptions as click_exceptions
except ImportError:  # pragma: no cover - older typer uses click itself
    from click import exceptions as click_exceptions  # type: ignore[no-redef]

#: Shown by ``stickslip --help``; every command's own ``--help`` has an example too.
HELP = """Predict and suppress stick-slip in sliding systems on elastic foundations.

Example: stickslip simulate --lam 3 --zeta 0.1 --json

Shell completion: stickslip --install-completion (or --show-completion to print the script).
"""

app = typer.Typer(
    name="stickslip",
    help=HELP,
    no_args_is_help=True,
    add_completion=True,  # Typer's --install-completion and --show-completion
    pretty_exceptions_enable=False,
)


def _version(value: bool) -> None:
    if value:
        from stickslip import __version__

        typer.echo(f"stickslip {__version__}")
        raise typer.Exit()


@app.callback()
def main(
    version: Annotated[
        bool, typer.Option("--version", callback=_version, is_eager=True, help="print the version")
    ] = False,
) -> None:
    """Predict and suppress stick-slip in sliding systems on elastic foundations."""


def _register() -> None:
    from stickslip.cli import (
        absorber_commands,
        app_command,
        basin_command,
        basin_map_command,
        cycles_command,
        design_command,
        map_commands,
        reproduce_command,
        simulate_command,
    )

    for module in (simulate_command, absorber_commands, map_commands, design_command,
                   basin_command, basin_map_command, cycles_command, reproduce_command, app_command):
        module.register(app)
    __import__("stickslip.cli.identify_command", fromlist=["register"]).register(app)


_register()


def _show_warning(message: Warning | str, category: type[Warning], filename: str, lineno: int,
                  file: object = None, line: str | None = None) -> None:
    """Warnings as one line on stderr, ``stickslip: warning: ...`` (no source line)."""
    text = " ".join(str(message).split())
    print(f"stickslip: warning: {text}", file=sys.stderr)


def run(argv: list[str] | None = None) -> None:
    """Console entry point: one line on stderr and exit code 2 for any bad input."""
    with warnings.catch_warnings():
        warnings.showwarning = _show_warning
        _run(argv)


def _run(argv: list[str] | None) -> None:
    try:
        # the program name is fixed, so completion uses _STICKSLIP_COMPLETE however it is started
        result = app(args=argv, prog_name="stickslip", standalone_mode=False)
    except click_exceptions.NoArgsIsHelpError:
        raise SystemExit(0) from None
    except click_exceptions.UsageError as exc:
        fail(exc.format_message())
    except typer.Abort:
        print("stickslip: aborted", file=sys.stderr)
        raise SystemExit(130) from None
    except (BadInput, ValueError) as exc:
        fail(str(exc))
    except OSError as exc:
        fail(f"{exc.filename or 'file'}: {exc.strerror or exc}")
    except typer.Exit as exc:
        raise SystemExit(exc.exit_code) from None
    if isinstance(result, int) and result != 0:
        raise SystemExit(result)


if __name__ == "__main__":
    run()
