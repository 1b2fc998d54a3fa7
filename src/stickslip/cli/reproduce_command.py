"""``stickslip reproduce``: the paper end to end, figures and a report."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer

from stickslip.cli.console import BadInput, print_json, show_progress

#: a file in every folder ``reproduce`` wrote: a later run may refresh that folder
MARKER = ".stickslip-reproduce"
#: a file in the folder while a run writes it, left there when the run is interrupted
INCOMPLETE = "INCOMPLETE.txt"
INCOMPLETE_TEXT = ("stickslip reproduce was interrupted while writing this folder: its figures, "
                   "data and report may come from different runs. Run `stickslip reproduce --out "
                   "{out}` again to complete it.\n")


def reproduce(
    out: Annotated[Path, typer.Option("--out", help="folder for figures, data and the report")] = Path(
        "results"),
    quality: Annotated[
        str, typer.Option("--quality", help="tiny (coarse maps: about a minute with the "
                          "compiled cache, several on a loaded machine), default (a few "
                          "minutes) or high (dense maps)")
    ] = "default",
    json: Annotated[bool, typer.Option("--json", help="print one JSON object and nothing else")] = False,
    overwrite: Annotated[bool, typer.Option(
        "--overwrite", help="write into a non-empty folder that no earlier reproduce wrote")] = False,
) -> None:
    """Recompute every figure and claim of the paper; write report.md and report.html.

    A folder an earlier reproduce wrote is refreshed (it holds the marker file
    .stickslip-reproduce); any other non-empty folder is refused unless --overwrite.

    Example: stickslip reproduce --out results --quality tiny
    """
    from rich.console import Console
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    from stickslip.reproduction.quality import quality as get_quality
    from stickslip.reproduction.run import reproduce as run_reproduction

    get_quality(quality)
    if out.exists() and not out.is_dir():
        raise BadInput(f"--out {str(out)!r} exists and is not a folder")
    if (out.is_dir() and not overwrite and not (out / MARKER).exists()
            and any(out.iterdir())):
        raise BadInput(f"--out {str(out)!r} is a non-empty folder that stickslip reproduce did not "
                       "write; its files could be replaced: pass --overwrite, or name a new folder")
    try:
        out.mkdir(parents=True, exist_ok=True)
        (out / MARKER).write_text("written by stickslip reproduce; it may refresh this folder\n",
                                  encoding="utf-8")
    except OSError as exc:
        raise BadInput(f"--out {str(out)!r} cannot be created: {exc.strerror}") from None

    columns = (TextColumn("{task.description}"), BarColumn(), TextColumn("{task.percentage:>3.0f}%"),
               TimeElapsedColumn())
    # on stderr, as every command's bar, and on a terminal only: stdout holds the summary (or
    # the JSON) alone
    incomplete = out / INCOMPLETE
    incomplete.write_text(INCOMPLETE_TEXT.format(out=out), encoding="utf-8")
    try:
        with Progress(*columns, transient=False, disable=not show_progress(),
                      console=Console(stderr=True)) as bar:
            task = bar.add_task("starting (the first run compiles the kernels, a few minutes)", total=1)

            def progress(step: str, done: int, total: int) -> None:
                bar.update(task, description=step, completed=done, total=max(total, 1))

            report = run_reproduction(out, quality, progress)
    except KeyboardInterrupt:
        # the folder holds this run's first figures beside an earlier run's report: said here
        # and in the folder (INCOMPLETE stays until a run completes)
        from stickslip.cli.main import ABORTED, EXIT_INTERRUPTED

        print(f"{ABORTED}: {str(out)!r} is incomplete; run the same command again to complete it",
              file=sys.stderr, flush=True)
        raise SystemExit(EXIT_INTERRUPTED) from None
    incomplete.unlink(missing_ok=True)
    if json:
        print_json(report.to_dict())
        return
    counts = ", ".join(f"{v} {k}" for k, v in sorted(report.counts().items()))
    typer.echo(f"{len(report.figures)} figures and {len(report.claims)} claims ({counts}) "
               f"in {report.seconds:.0f} s")
    typer.echo(f"report: {report.html_path} (also {report.markdown_path.name}, report.json)")
    typer.echo(f"figures: {out / 'figures'}   data: {out / 'data'}")


def register(app: typer.Typer) -> None:
    """Add the ``reproduce`` command to ``app``."""
    app.command("reproduce")(reproduce)
