"""The ``stickslip`` command: a thin layer over the public Python API."""

from __future__ import annotations

import functools
import os
import signal
import sys
import threading
import time
import warnings
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from importlib import import_module
from pathlib import Path
from types import FrameType
from typing import Annotated, Any, NoReturn

from stickslip.model.user_file import recording_inputs

#: Exit code after Ctrl-C: 128 + SIGINT, as a shell reports a process that SIGINT ended.
EXIT_INTERRUPTED = 130

#: The one line a Ctrl-C prints on stderr, whatever the command was doing.
ABORTED = "stickslip: aborted (Ctrl-C)"


def _aborted() -> NoReturn:
    """Ctrl-C: one line on stderr, exit code 130; finished work stays on disk for resume."""
    print(ABORTED, file=sys.stderr, flush=True)
    raise SystemExit(EXIT_INTERRUPTED) from None


try:  # Ctrl-C while the command line starts (these imports are most of its 0.1 s): one line
    import typer

    # typer is held below 0.25 (pyproject.toml: start-up time), which parses with click itself
    from click import exceptions as click_exceptions
    from typer.core import TyperCommand

    from stickslip.cli.console import BadInput, fail
except KeyboardInterrupt:
    _aborted()

#: Shown by ``stickslip --help``; every command's own ``--help`` has an example too.
HELP = """Predict and suppress stick-slip in sliding systems on elastic foundations.

Example: stickslip simulate --lam 3 --zeta 0.1 --json

Shell completion: stickslip --install-completion (or --show-completion to print the script).
"""

#: Command -> module of :mod:`stickslip.cli` whose ``register`` adds it, in ``--help`` order.
COMMAND_MODULES: dict[str, str] = {
    "simulate": "simulate_command",
    "frf": "absorber_commands",
    "tune": "absorber_commands",
    "map": "map_commands",
    "boundary": "map_commands",
    "design": "design_command",
    "basin": "basin_command",
    "basin-map": "basin_map_command",
    "cycles": "cycles_command",
    "continue": "continue_command",
    "stability": "stability_command",
    "identify": "identify_command",
    "reproduce": "reproduce_command",
    "app": "app_command",
    "compile": "compile_command",
}


#: Commands that run no compiled kernel (so their start-up never imports numba).
NUMBA_FREE_COMMANDS = frozenset({"frf", "app", "compile", "stability"})  # compile: its children compile


def _version(value: bool) -> None:
    if value:
        from stickslip import __version__

        typer.echo(f"stickslip {__version__}")
        raise typer.Exit()


def main(
    version: Annotated[
        bool, typer.Option("--version", callback=_version, is_eager=True, help="print the version")
    ] = False,
) -> None:
    """Predict and suppress stick-slip in sliding systems on elastic foundations."""


def build_app(command: str | None = None, *, announced: bool = False) -> typer.Typer:
    """The ``stickslip`` Typer application, with every command or with ``command`` alone.

    A run of one command needs only that command's module: ``stickslip simulate`` then
    imports neither the map, basin nor design commands (nor what they import), which keeps
    its start-up short (issue 21, point 4). ``command=None``, or a name that is no command
    (typing errors, ``--help``, shell completion), registers them all. Every command that may
    compile numba kernels runs :func:`watching_compiles`; ``announced`` says that the
    first-run notice is printed already.
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
    app.callback()(main)
    if command in COMMAND_MODULES:
        modules = [COMMAND_MODULES[command]]
    else:
        modules = list(dict.fromkeys(COMMAND_MODULES.values()))
    for module in modules:
        import_module(f"stickslip.cli.{module}").register(app)
    for info in app.registered_commands:
        if info.cls is None or info.cls is TyperCommand:
            info.cls = _command_class()
        if info.name not in NUMBA_FREE_COMMANDS and info.callback is not None:
            info.callback = watching_compiles(info.callback, announced)
    return app


def first_sentence(text: str) -> str:
    """The first sentence of ``text``'s first paragraph, whitespace collapsed.

    click ends it at any period followed by a word that does not start in lowercase, which cut
    "(paper Figs. 8 and 11)" to "(paper Figs."; here a period ends a sentence only before an
    upper-case letter or at the end of the paragraph.
    """
    import re

    paragraph = " ".join(text.strip().split("\n\n")[0].split())
    match = re.search(r"\.(?=\s+[A-Z])", paragraph)
    return paragraph[: match.end()] if match else paragraph


@functools.cache
def _command_class() -> type[Any]:
    """typer's command, listed in ``stickslip --help`` by :func:`first_sentence`.

    The sentence is shortened to the width click gives it (the terminal's), at a word.
    """
    import textwrap

    class Command(TyperCommand):
        def __init__(self, *args: Any, **kwargs: Any) -> None:
            super().__init__(*args, **kwargs)
            _restore_argument_help(self)

        def format_arguments(self, ctx: Any, formatter: Any) -> None:
            """Nothing: typer lists the arguments in its own section with the options (click
            8.5 added a "Positional arguments" section, so ``RECORD`` was listed twice)."""

        def get_short_help_str(self, limit: int = 45) -> str:
            if self.short_help or not self.help:
                return str(super().get_short_help_str(limit))
            sentence = first_sentence(self.help)
            if len(sentence) <= limit:
                return sentence
            return textwrap.shorten(sentence, max(limit, 4), placeholder="...",
                                    break_on_hyphens=False)

    return Command


def _restore_argument_help(command: TyperCommand) -> None:
    """Give each argument of ``command`` the ``help`` of its ``typer.Argument`` again.

    click 8.5's ``Parameter.__init__`` sets ``help`` itself (to None for an argument), after
    typer 0.24's ``TyperArgument`` has set it: ``identify --help`` listed ``RECORD`` with no
    description. The help is read back from the command's signature.
    """
    from typer.core import TyperArgument
    from typer.utils import get_params_from_function

    if command.callback is None:
        return
    lost = [p for p in command.params if isinstance(p, TyperArgument) and not p.help]
    if lost:
        declared = get_params_from_function(command.callback)
        for param in lost:
            meta = declared.get(param.name or "")
            param.help = getattr(meta.default, "help", None) if meta is not None else None


def __getattr__(name: str) -> typer.Typer:
    """``app``, the application with every command (docs, tests), built on first use (PEP 562)."""
    if name == "app":
        app = globals()["app"] = build_app()
        return app
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def invoked_command(argv: list[str]) -> str | None:
    """The command ``argv`` runs (its first word that is no option), or None."""
    if os.environ.get("_STICKSLIP_COMPLETE"):  # shell completion needs every command
        return None
    return next((a for a in argv if not a.startswith("-")), None)


def _show_warning(message: Warning | str, category: type[Warning], filename: str, lineno: int,
                  file: object = None, line: str | None = None) -> None:
    """Warnings as one line on stderr, ``stickslip: warning: ...`` (no source line)."""
    text = " ".join(str(message).split())
    print(f"stickslip: warning: {text}", file=sys.stderr)


#: Commands that run the compiled engine; the first of them after an install compiles it.
ENGINE_COMMANDS = frozenset({"simulate", "map", "boundary", "basin", "basin-map", "cycles",
                             "reproduce", "tune"})


def engine_cache_is_cold() -> bool:
    """True when numba has no compiled engine cached for the installed kernel sources.

    numba keeps an index (``*.nbi``) per compiled function next to the source (in
    ``__pycache__``), or under ``NUMBA_CACHE_DIR`` when that is set (then only there), and
    uses it only when the stamp written in it is the kernel folder's
    (:func:`stickslip.kernel._stamp.kernel_source_stamp`: the sources' names and contents,
    not their times); the run loop's index stands for the engine. So the cache is warm when
    an index of the run loop holds the current stamp (numba pickles it as its text): a
    checkout that rewrites identical files keeps it warm, any kernel edit makes it cold.
    Found without importing numba. A kernel compiled although this says warm (another
    command's kernels, a new signature) is still announced, by :class:`CompileWatch`.
    """
    from stickslip.kernel._stamp import KERNEL_DIR, kernel_source_stamp

    user_dir = os.environ.get("NUMBA_CACHE_DIR")
    folders = [Path(user_dir)] if user_dir else [KERNEL_DIR / "__pycache__"]
    stamp = kernel_source_stamp().encode()
    return not any(_holds(index, stamp) for folder in folders if folder.is_dir()
                   for index in folder.rglob("engine.run_prepared-*.nbi"))


def _holds(index: Path, stamp: bytes) -> bool:
    """Whether the cache index file ``index`` holds ``stamp`` (False when it cannot be read)."""
    try:
        return stamp in index.read_bytes()
    except OSError:
        return False


#: How long a command's first run compiles, roughly, on a 2-core machine with an empty cache
#: (``benchmarks/bench_startup.py --cold simulate,map,basin``: 42 s, 78 s, 115 s on 2026-11-24;
#: 50 s, 94 s, 133 s on a slower 2026-11-25); commands not listed compile the engine's family,
#: about a minute.
FIRST_RUN_DURATION = {"basin": "about two minutes", "basin-map": "about two minutes",
                      "reproduce": "a few minutes"}


def first_run_notice(command: str | None = None) -> str:
    """The first-run notice of ``command`` on stderr (never on stdout: ``--json`` prints one
    object there), with its rough compile time (:data:`FIRST_RUN_DURATION`)."""
    return (f"stickslip: first run: compiling the simulation engine with numba, "
            f"{FIRST_RUN_DURATION.get(command or '', 'about a minute')} "
            "(once; later runs load it from the cache)")


#: The notice of a command with the engine's compile time (``simulate``, ``map``, ...).
FIRST_RUN_NOTICE = first_run_notice()


def _announce_compilation(argv: list[str]) -> bool:
    """On the first engine command after an install, say on stderr that numba compiles now.

    Never on stdout (``--json`` prints one object there), never for ``--help``. Returns
    whether it printed the notice.
    """
    command = invoked_command(argv)
    if command in ENGINE_COMMANDS and "--help" not in argv and engine_cache_is_cold():
        print(first_run_notice(command), file=sys.stderr, flush=True)
        return True
    return False


class CompileWatch:
    """What numba compiles during one command, told on stderr as it happens.

    numba reports every compile its cache could not serve as a ``numba:compile`` event
    (:mod:`numba.core.event`; loads from the cache report none). The first compile of a
    stickslip kernel prints :data:`FIRST_RUN_NOTICE` (unless the cache check of
    :func:`_announce_compilation` has printed it), :meth:`close` then prints how many kernels
    (compiled functions of this package) and signatures took how long. A run served by the
    cache prints nothing.
    """

    def __init__(self, announced: bool) -> None:
        from numba.core import event

        self.announced = announced
        self.kernels = 0
        self.functions: set[str] = set()
        self.seconds = 0.0
        self._depth = 0
        self._started = 0.0
        self._event = event
        watch = self

        class Listener(event.Listener):
            def on_start(self, ev: Any) -> None:
                function = ev.data["dispatcher"].py_func
                watch.started(function.__module__, function.__qualname__)

            def on_end(self, ev: Any) -> None:
                watch.ended()

        self._listener = Listener()
        event.register("numba:compile", self._listener)

    def started(self, module: str, name: str) -> None:
        """A compile begins (nested ones: the callees of a kernel, numba's own overloads)."""
        if self._depth == 0:
            self._started = time.perf_counter()
        self._depth += 1
        if module.startswith("stickslip."):
            self.kernels += 1
            self.functions.add(f"{module}.{name}")
            if not self.announced:
                print(FIRST_RUN_NOTICE, file=sys.stderr, flush=True)
                self.announced = True

    def ended(self) -> None:
        """A compile ends; the outermost one adds its wall time."""
        self._depth -= 1
        if self._depth == 0:
            self.seconds += time.perf_counter() - self._started

    def close(self) -> None:
        """Stop listening; say on stderr how many kernels were compiled, if any."""
        self._event.unregister("numba:compile", self._listener)
        if self.kernels:
            print(f"stickslip: compiled {len(self.functions)} numba kernels ({self.kernels} "
                  f"signatures) in {self.seconds:.0f} s; they are cached for later runs",
                  file=sys.stderr, flush=True)


def watching_compiles(command: Callable[..., Any], announced: bool) -> Callable[..., Any]:
    """``command`` run under a :class:`CompileWatch` (started once its options are parsed).

    After parsing, so that ``--help`` and refused input never import numba. The signature
    and docstring stay those of ``command`` (typer reads them through ``__wrapped__``).
    """

    @functools.wraps(command)
    def watched(*args: Any, **kwargs: Any) -> Any:
        watch = CompileWatch(announced)
        try:
            return command(*args, **kwargs)
        finally:
            watch.close()

    return watched


#: Times a Ctrl-C lost in a finalizer is sent again (each loss is a rare coincidence).
MAX_REDELIVERIES = 5
#: Seconds before a lost Ctrl-C is sent again: the finalizer that lost it has returned by then.
REDELIVERY_DELAY = 0.05


class SigintNote:
    """Whether SIGINT arrived during a command (set by :func:`noting_sigint`'s handler).

    Python runs the handler wherever the main thread is, a finalizer included (a weakref
    callback, ``__del__``), and an exception raised there is only printed ("Exception
    ignored in ...") while the command goes on. :meth:`unraisable` is ``sys.unraisablehook``
    during the command: such a lost ``KeyboardInterrupt`` is not printed but sent again, a
    moment later, from another thread, so that it lands in the command's own code.
    """

    def __init__(self) -> None:
        self.caught = False
        self.active = False  # the handler is installed (a late resend is dropped after it)
        self.redelivered = 0
        self.previous_hook: Callable[[Any], object] = sys.unraisablehook

    def __call__(self, signum: int, frame: FrameType | None) -> None:
        self.caught = True
        raise KeyboardInterrupt

    def unraisable(self, info: Any) -> None:
        """``sys.unraisablehook``: send a Ctrl-C lost in a finalizer again; pass on the rest."""
        if (not issubclass(info.exc_type, KeyboardInterrupt)
                or self.redelivered >= MAX_REDELIVERIES):
            self.previous_hook(info)
            return
        self.redelivered += 1
        timer = threading.Timer(REDELIVERY_DELAY, self._resend)
        timer.daemon = True
        timer.start()

    def _resend(self) -> None:
        if self.active:
            os.kill(os.getpid(), signal.SIGINT)


@contextmanager
def noting_sigint() -> Iterator[SigintNote]:
    """Python's SIGINT handler, which also notes that the signal came; restored on exit.

    Library code may turn the ``KeyboardInterrupt`` into another exception (numba's
    dispatcher raises ``SystemError``, a worker pool its own error, a cleanup handler a
    ``ValueError``): once the note is set, whatever ends the command is reported as Ctrl-C.
    A ``KeyboardInterrupt`` lost in a finalizer is sent again (:meth:`SigintNote.unraisable`).
    Only where Python handles SIGINT itself, in the main thread (a background job that
    inherits SIGINT ignored keeps it ignored); elsewhere nothing changes.
    """
    note = SigintNote()
    main = threading.current_thread() is threading.main_thread()
    if not main or signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        yield note
        return
    signal.signal(signal.SIGINT, note)
    sys.unraisablehook = note.unraisable
    note.active = True
    try:
        yield note
    finally:
        note.active = False
        signal.signal(signal.SIGINT, signal.default_int_handler)
        sys.unraisablehook = note.previous_hook


#: How far :func:`interrupted` follows an exception's causes (chains are a few links long).
_CHAIN_LIMIT = 32


def interrupted(exc: BaseException, note: SigintNote | None = None) -> bool:
    """True when ``exc`` comes from Ctrl-C: SIGINT was noted, or a ``KeyboardInterrupt`` is
    ``exc`` or one of its causes or contexts (numba's ``SystemError``, click's ``Abort``)."""
    if note is not None and note.caught:
        return True
    seen: set[int] = set()
    pending: list[BaseException] = [exc]
    while pending and len(seen) < _CHAIN_LIMIT:
        current = pending.pop()
        if id(current) in seen:
            continue
        seen.add(id(current))
        if isinstance(current, KeyboardInterrupt):
            return True
        pending += [e for e in (current.__cause__, current.__context__) if e is not None]
    return False


def run(argv: list[str] | None = None) -> None:
    """Console entry point: one line on stderr and exit code 2 for any bad input.

    Ctrl-C at any moment (while the command starts, parses, compiles or runs a kernel, a
    solver or a worker pool) prints one line on stderr and exits with code 130.
    """
    note: SigintNote | None = None
    try:
        with noting_sigint() as note, recording_inputs():  # no output over an input of it
            args = sys.argv[1:] if argv is None else list(argv)
            announced = _announce_compilation(args)
            with warnings.catch_warnings():
                warnings.showwarning = _show_warning
                _run(argv, build_app(invoked_command(args), announced=announced), note)
    except SystemExit as exc:
        if note is not None and note.caught and exc.code not in (0, None, EXIT_INTERRUPTED):
            _aborted()  # a command that turned Ctrl-C into an error exit of its own
        raise
    except BaseException as exc:
        if interrupted(exc, note):
            _aborted()
        raise


def _run(argv: list[str] | None, app: typer.Typer, note: SigintNote | None = None) -> None:
    try:
        try:
            # the program name is fixed, so completion uses _STICKSLIP_COMPLETE however it is
            # started
            result = app(args=argv, prog_name="stickslip", standalone_mode=False)
        except SystemExit:
            raise
        except BaseException as exc:
            if interrupted(exc, note):
                _aborted()
            raise
    except click_exceptions.NoArgsIsHelpError as exc:  # bare `stickslip`: its help, as --help
        typer.echo(exc.ctx.get_help() if exc.ctx is not None else exc.format_message())
        raise SystemExit(0) from None
    except click_exceptions.UsageError as exc:
        fail(exc.format_message())
    except typer.Abort:  # click's answer to Ctrl-C or end of input at a prompt
        _aborted()
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
