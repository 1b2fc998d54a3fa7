"""The ``stickslip`` command: a thin layer over the public Python API."""

from __future__ import annotations

import sys
import warnings
from typing import Annotated, NoReturn

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
    # help texts are plain text: units and TOML tables are written in brackets ("[kg]",
    # "[system]"), which Rich markup would swallow as style tags
    rich_markup_mode=None,
    context_settings={"max_content_width": 120},  # up to 120 columns when the terminal has them
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
        continue_command,
        cycles_command,
        design_command,
        identify_command,
        map_commands,
        reproduce_command,
        simulate_command,
    )

    for module in (simulate_command, absorber_commands, map_commands, design_command,
                   basin_command, basin_map_command, cycles_command, continue_command, identify_command,
                   reproduce_command, app_command):
        module.register(app)


_register()


def _show_warning(message: Warning | str, category: type[Warning], filename: str, lineno: int,
                  file: object = None, line: str | None = None) -> None:
    """Warnings as one line on stderr, ``stickslip: warning: ...`` (no source line)."""
    text = " ".join(str(message).split())
    print(f"stickslip: warning: {text}", file=sys.stderr)


#: Exit code after Ctrl-C: 128 + SIGINT, as a shell reports a process that SIGINT ended.
EXIT_INTERRUPTED = 130


def _aborted() -> NoReturn:
    """Ctrl-C: one line on stderr, exit code 130; finished work stays on disk for resume."""
    print("stickslip: aborted (Ctrl-C)", file=sys.stderr)
    raise SystemExit(EXIT_INTERRUPTED) from None


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
        _aborted()
    except SystemError as exc:
        # Ctrl-C inside a compiled kernel outside the chunk loops: numba's dispatcher reports
        # the KeyboardInterrupt as "returned a result with an exception set"
        if isinstance(exc.__cause__ or exc.__context__, KeyboardInterrupt):
            _aborted()
        raise
    except (BadInput, ValueError) as exc:
        fail(str(exc))
    except OSError as exc:
        fail(f"{exc.filename or 'file'}: {exc.strerror or exc}")
    except typer.Exit as exc:
        raise SystemExit(exc.exit_code) from None
    if result == EXIT_INTERRUPTED:  # typer turns a KeyboardInterrupt into this exit code
        _aborted()
    if isinstance(result, int) and result != 0:
        raise SystemExit(result)


if __name__ == "__main__":
    run()
