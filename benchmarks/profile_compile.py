"""Where a cold first run spends its compile time: seconds per compiled numba function.

The profile behind issue 21.5's compile-time work. numba reports each compile as a
``numba:compile`` event (:mod:`numba.core.event`); nested compiles are the callees of a
kernel and numba's own overloads. This prints, for one ``stickslip`` command run in this
process against an empty numba cache (a fresh ``NUMBA_CACHE_DIR``, the package's own cache is
left alone), every compile with its exclusive seconds (its own, callees' excluded), its
inclusive seconds, the function, the caller that triggered it and the argument types, the
longest first; then the total. A function listed twice was compiled for two signatures
(literal constants and array layouts count).

    python benchmarks/profile_compile.py [--top 40] [simulate --lam 3 --zeta 0.1 --json]
"""

from __future__ import annotations

import argparse
import contextlib
import io
import os
import tempfile
import time
from typing import Any


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--top", type=int, default=40, help="compiles listed (the longest)")
    parser.add_argument("command", nargs=argparse.REMAINDER,
                        help="stickslip arguments (default: simulate --lam 3 --zeta 0.1 --json)")
    args = parser.parse_args()
    if args.top < 1:
        parser.error(f"--top {args.top} must be at least 1")
    argv = args.command or ["simulate", "--lam", "3", "--zeta", "0.1", "--json"]
    with tempfile.TemporaryDirectory(prefix="stickslip-profile-cache-") as cache:
        os.environ["NUMBA_CACHE_DIR"] = cache  # before numba is imported: read at its import
        from numba.core import event

        stack: list[list[Any]] = []
        rows: list[tuple[float, float, str, str, str]] = []

        class Listener(event.Listener):
            def on_start(self, ev: Any) -> None:
                stack.append([time.perf_counter(), 0.0, ev.data])

            def on_end(self, ev: Any) -> None:
                started, children, data = stack.pop()
                seconds = time.perf_counter() - started
                if stack:
                    stack[-1][1] += seconds
                function = data["dispatcher"].py_func
                caller = stack[-1][2]["dispatcher"].py_func.__name__ if stack else "-"
                rows.append((seconds - children, seconds,
                             f"{function.__module__.rsplit('.', 1)[-1]}.{function.__name__}", caller,
                             str(data["args"])))

        event.register("numba:compile", Listener())
        from stickslip.cli.main import run

        started = time.perf_counter()
        with contextlib.redirect_stdout(io.StringIO()), contextlib.suppress(SystemExit):
            run(argv)
        total = time.perf_counter() - started
    rows.sort(reverse=True)
    print(f"stickslip {' '.join(argv)} with an empty numba cache: {total:.1f} s, {len(rows)} compiles, "
          f"{sum(r[0] for r in rows):.1f} s of them compiling")
    print(f"{'own s':>7} {'incl s':>7}  {'function':<36} {'called from':<24} argument types")
    for own, inclusive, name, caller, types in rows[: args.top]:
        print(f"{own:7.2f} {inclusive:7.2f}  {name:<36} {caller:<24} {types[:120]}")


if __name__ == "__main__":
    main()
