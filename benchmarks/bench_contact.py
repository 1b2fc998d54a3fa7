"""Benchmark: the contact engine against an event-driven solve_ivp, on the brake pad, in one run.

    .venv/bin/python benchmarks/bench_contact.py [--repeats 3]

The case is ``examples/brake_pad/slow_belt.toml`` (Hoffmann et al. 2002's minimal model at
2 cm/s, mu_s = 0.5, mu_k = 0.4): stick-slip with lift-off and re-contact, about 1,100 events
before the engine sees its breakaway state repeat. The engine (exact flows of each linear
mode, every event found by a search that cannot skip a root; ``stickslip simulate --config``)
is timed against the oracle of ``tests/test_contact_engine.py`` (``scipy.integrate.solve_ivp``,
DOP853 at rtol 1e-11, terminal events, mode by mode) over the same time span; the best of
``--repeats`` runs of each is printed with their ratio, and the two periods and event lists
are compared.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the oracle lives in tests/

from tests.test_contact_engine import brake_pad, oracle

from stickslip.analysis.contact.engine import simulate_contact


def best_of(fn, repeats: int) -> tuple[float, object]:  # type: ignore[no-untyped-def]
    """Fastest wall time of ``repeats`` calls (s) and the last result."""
    best, out = math.inf, None
    for _ in range(repeats):
        start = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - start)
    return best, out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3, help="runs of each (1 to 20)")
    args = parser.parse_args(argv)
    if not 1 <= args.repeats <= 20:
        parser.error(f"--repeats {args.repeats} must be from 1 to 20")
    system = brake_pad(0.02, 0.5, 0.4)
    simulate_contact(system)  # warm
    t_engine, run = best_of(lambda: simulate_contact(system), args.repeats)
    t_end = run.t_end * (1.0 + 1e-9)  # type: ignore[attr-defined]
    t_oracle, ref = best_of(lambda: oracle(system, t_end), args.repeats)
    breaks = [t for kind, t, _ in ref if kind == "break+"]  # type: ignore[union-attr]
    names = {"break+": "breakaway forward", "break-": "breakaway backward",
             "re-stick": "belt speed"}
    same = ([names.get(kind, kind) for kind, _, _ in ref]  # type: ignore[union-attr]
            == [e.kind for e in run.events])  # type: ignore[attr-defined]
    print("bench_contact: brake pad at 2 cm/s (examples/brake_pad/slow_belt.toml), "
          f"best of {args.repeats}")
    print(f"  engine     {t_engine:8.3f} s  {len(run.events)} events, verdict "  # type: ignore[attr-defined]
          f"{run.verdict.value}, period {run.period_s!r} s")  # type: ignore[attr-defined]
    print(f"  solve_ivp  {t_oracle:8.3f} s  {len(ref)} events, period "  # type: ignore[arg-type]
          f"{breaks[-1] - breaks[-2]!r} s (DOP853, rtol 1e-11, event-driven)")
    print(f"  ratio      {t_oracle / t_engine:8.2f}x; same event sequence: {same}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
