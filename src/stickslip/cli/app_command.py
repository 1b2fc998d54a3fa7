"""``stickslip app``: start the web app (Streamlit, the optional ``app`` extra)."""

from __future__ import annotations

import errno
import importlib.util
import ipaddress
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
#: The address served by default: this computer only.
DEFAULT_ADDRESS = "127.0.0.1"


def is_loopback(address: str) -> bool:
    """True when ``address`` reaches this computer only (127.0.0.0/8, ::1, ``localhost``).

    Written forms that resolve to a loopback address count too (``127.1``, the IPv4-mapped
    ``::ffff:127.0.0.1``): every address the name resolves to must be one. A name that does
    not resolve is not loopback (the warning errs on the safe side).
    """
    import socket

    host = served_address(address)
    if host.lower() == "localhost":
        return True
    try:
        infos = socket.getaddrinfo(host, 0, type=socket.SOCK_STREAM)
    except (socket.gaierror, UnicodeError):
        return False
    for info in infos:
        ip = ipaddress.ip_address(str(info[4][0]).split("%", 1)[0])
        mapped = getattr(ip, "ipv4_mapped", None)
        if not (ip.is_loopback or (mapped is not None and mapped.is_loopback)):
            return False
    return bool(infos)


def served_address(address: str) -> str:
    """The address as the server takes it: without spaces and an IPv6 literal's brackets
    (``[::1]``: Streamlit's own resolution failed with a traceback on the brackets)."""
    return address.strip().strip("[]")


def streamlit_command(port: int | None, headless: bool, address: str = DEFAULT_ADDRESS) -> list[str]:
    """The ``python -m streamlit run`` command line that serves the app on ``address``.

    Tracebacks are not sent to the browser (they name the server's files); uploads are
    limited to :data:`~stickslip.io.machine_file.UPLOAD_MAX_MB`. Streamlit's full garbage
    collection after every run of the page is off: with the engine's compiled kernels loaded
    it took about 0.2 s, during which the end of the page waited to be sent (Python's own
    collector still runs as usual).
    """
    from stickslip.io.machine_file import UPLOAD_MAX_MB

    command = [sys.executable, "-m", "streamlit", "run", str(APP_SCRIPT),
               "--browser.gatherUsageStats", "false", "--client.toolbarMode", "viewer",
               "--server.address", address, "--client.showErrorDetails", "none",
               "--server.maxUploadSize", str(UPLOAD_MAX_MB), "--runner.postScriptGC", "false"]
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
    address: Annotated[
        str,
        typer.Option("--address", help="address to serve on (default 127.0.0.1: this computer "
                     "only; 0.0.0.0 opens the app to the network, with a warning)"),
    ] = DEFAULT_ADDRESS,
) -> None:
    """Start the web app: design calculator, verdicts, maps and time histories in a browser.

    It serves this computer only unless --address opens it to others: the app has no login,
    and anyone who reaches it can run computations on this computer.

    Example: stickslip app --port 8600 --headless
    """
    if not address.strip():
        raise BadInput("--address '' is empty: give an address such as 127.0.0.1 (this computer "
                       "only) or 0.0.0.0 (every interface)")
    if importlib.util.find_spec("streamlit") is None:
        raise BadInput("streamlit is not installed; install the app extra: pip install stickslip[app]")
    check_can_serve(address.strip(), port)
    if not is_loopback(address):
        print(f"stickslip: warning: --address {address} opens the app to other computers; it has "
              "no login, and anyone who reaches it can run computations here", file=sys.stderr)
    process = subprocess.Popen(streamlit_command(port, headless, served_address(address)))
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


def check_can_serve(address: str, port: int | None) -> None:
    """Refuse, in one line, an address this computer cannot serve on or a port in use.

    Binds a socket for a moment (to ``port``, or to any free port when Streamlit picks it):
    without this check, Streamlit's own traceback (``socket.gaierror``, ``OSError``) or a
    timestamped log line was all a mistyped address or a busy port got.
    """
    import socket

    host = served_address(address)
    try:
        infos = socket.getaddrinfo(host, port or 0, type=socket.SOCK_STREAM)
    except socket.gaierror as exc:
        raise BadInput(f"--address {address!r} cannot be resolved ({exc.strerror}): give an address "
                       "of this computer, such as 127.0.0.1 or 0.0.0.0") from None
    family, kind, proto, _, where = infos[0]
    with socket.socket(family, kind, proto) as probe:
        try:
            probe.bind(where)
        except OSError as exc:
            if port is not None and exc.errno == errno.EADDRINUSE:
                raise BadInput(f"--port {port} is in use on {address}: choose another port") from None
            raise BadInput(f"--address {address!r} cannot be served on by this computer "
                           f"({exc.strerror}): give one of its addresses, such as 127.0.0.1 or "
                           "0.0.0.0") from None


def _interrupt(signum: int, frame: object) -> None:
    """SIGTERM handler: stop like Ctrl-C, so that the server is not left running."""
    raise KeyboardInterrupt


def register(app_: typer.Typer) -> None:
    """Add the ``app`` command to ``app_``."""
    app_.command("app")(app)
