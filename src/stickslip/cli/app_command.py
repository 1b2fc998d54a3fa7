"""``stickslip app``: start the web app (Streamlit, the optional ``app`` extra)."""

from __future__ import annotations

import importlib.util
import signal
import subprocess
import sys
from pathlib import Path
from typing import Annotated

import typer

from stickslip.cli.console import BadInput

APP_SCRIPT = Path(__file__).resolve().parent.parent / "app" / "streamlit_app.py"
#: Seconds left to Streamlit to shut down after Ctrl-C before it is killed.
SHUTDOWN_TIMEOUT = 10.0


def streamlit_command(port: int | None, headless: bool) -> list[str]:
    """The ``python -m streamlit run`` command line that serves the app."""
    command = [sys.executable, "-m", "streamlit", "run", str(APP_SCRIPT),
               "--browser.gatherUsageStats", "false", "--client.toolbarMode", "viewer"]
    if port is not None:
        command += ["--server.port", str(port)]
    if headless:
        command += ["--server.headless", "true"]
    return command


def app(
    port: Annotated[
        int | None,
        typer.Option("--port", min=1, max=65535, help="port to serve on (Streamlit's default: 8501)"),
    ] = None,
    headless: Annotated[
        bool, typer.Option("--headless", help="do not open a browser (servers, containers)")
    ] = False,
) -> None:
    """Start the web app: design calculator, verdicts, maps and time histories in a browser.

    Example: stickslip app --port 8600 --headless
    """
    if importlib.util.find_spec("streamlit") is None:
        raise BadInput("streamlit is not installed; install the app extra: pip install stickslip[app]")
    process = subprocess.Popen(streamlit_command(port, headless))
    signal.signal(signal.SIGTERM, _interrupt)
    try:
        code = process.wait()
    except KeyboardInterrupt:
        # Stop the server too (Ctrl-C in a terminal already reached it; a signal sent to
        # this process alone did not); Streamlit shuts down cleanly on SIGTERM.
        process.terminate()
        try:
            code = process.wait(timeout=SHUTDOWN_TIMEOUT)
        except subprocess.TimeoutExpired:
            process.kill()
            code = process.wait()
    if code != 0:
        raise typer.Exit(code)


def _interrupt(signum: int, frame: object) -> None:
    """SIGTERM handler: stop like Ctrl-C, so that the server is not left running."""
    raise KeyboardInterrupt


def register(app_: typer.Typer) -> None:
    """Add the ``app`` command to ``app_``."""
    app_.command("app")(app)
