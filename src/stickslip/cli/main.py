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


#: Commands that run the compiled engine; the first of them after an install compiles it.
ENGINE_COMMANDS = frozenset({"simulate", "map", "boundary", "basin", "basin-map", "cycles",
                             "reproduce", "tune"})


def engine_cache_is_cold() -> bool:
    """True when numba has no compiled engine cached for the installed sources.

    numba keeps an index (``*.nbi``) per compiled function next to the source (in
    ``__pycache__``, or under ``NUMBA_CACHE_DIR``) and discards it when the source is newer;
    the run loop's index stands for the engine. Found without importing numba.
    """
    import os
    from importlib.util import find_spec
    from pathlib import Path

    spec = find_spec("stickslip.kernel.engine")
    if spec is None or spec.origin is None:
        return False
    source = Path(spec.origin)
    folders = [source.parent / "__pycache__"]
    if os.environ.get("NUMBA_CACHE_DIR"):
        folders.append(Path(os.environ["NUMBA_CACHE_DIR"]))
    stamp = source.stat().st_mtime
    return not any(index.stat().st_mtime >= stamp for folder in folders if folder.is_dir()
                   for index in folder.rglob("engine.run_prepared-*.nbi"))


def _announce_compilation(argv: list[str]) -> None:
    """On the first engine command after an install, say on stderr that numba compiles now.

    Never on stdout (``--json`` prints one object there), never for ``--help``.
    """
    command = next((a for a in argv if not a.startswith("-")), None)
    if command in ENGINE_COMMANDS and "--help" not in argv and engine_cache_is_cold():
        print("stickslip: first run: compiling the simulation engine with numba, about a minute "
              "(once; later runs load it from the cache)", file=sys.stderr, flush=True)


def run(argv: list[str] | None = None) -> None:
    """Console entry point: one line on stderr and exit code 2 for any bad input."""
    _announce_compilation(sys.argv[1:] if argv is None else list(argv))
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
