"""Where a new point of the web app's slider page spends its time, inside the page's script.

    .venv/bin/python benchmarks/profile_app_rerun.py [--machine]

Runs the page with Streamlit's ``AppTest`` (no browser), changes the belt speed twice (the
second change is timed: caches warm, the point new), and prints the time spent in each of the
page's cached computations (``stickslip.app.computations``) and figure functions
(``stickslip.app.figures``), nested calls counted in both. ``benchmarks/bench_app.py`` times
the whole rerun in a real browser. ``--machine`` times reruns of the machine page instead (typed
modes: a new machine, then one designed before).
"""

from __future__ import annotations

import collections
import functools
import time
from pathlib import Path
from typing import Any

import stickslip.app.computations as computations
import stickslip.app.figures as figures

APP = Path(__file__).resolve().parents[1] / "src" / "stickslip" / "app" / "streamlit_app.py"
SPENT: collections.defaultdict[str, float] = collections.defaultdict(float)


def _timed(module: Any, name: str) -> None:
    function = getattr(module, name)

    @functools.wraps(function)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        start = time.perf_counter()
        try:
            return function(*args, **kwargs)
        finally:
            SPENT[f"{module.__name__.rsplit('.', 1)[-1]}.{name}"] += time.perf_counter() - start

    setattr(module, name, wrapper)


def main() -> None:
    for name in ("design_report", "operating_point_runs", "basin_runs", "occurrence_maps",
                 "bifurcation_diagrams"):
        _timed(computations, name)
    for name in dir(figures):
        value = getattr(figures, name)
        if callable(value) and getattr(value, "__module__", "") == figures.__name__ \
                and not name.startswith("_"):
            _timed(figures, name)
    from streamlit.testing.v1 import AppTest

    page = AppTest.from_file(str(APP), default_timeout=600)
    page.run()
    page.text_input(key="speed").set_value("6 cm/s").run()
    SPENT.clear()
    start = time.perf_counter()
    page.text_input(key="speed").set_value("7.5 cm/s").run()
    print(f"new point (7.5 cm/s) in the page's script: {time.perf_counter() - start:.2f} s")
    for key, seconds in sorted(SPENT.items(), key=lambda item: -item[1]):
        print(f"  {seconds:6.3f} s  {key}")


def machine_page() -> None:
    """The machine page (typed modes): a new mode shape, then back to the one before."""
    from streamlit.testing.v1 import AppTest

    page = AppTest.from_file(str(APP), default_timeout=600)
    page.run()
    page.sidebar.radio(key="page").set_value("your machine (matrices or modes)").run()
    for label, shapes in (("new machine", "0.06, 0.03"), ("machine designed before", "0.07, 0.03"),
                          ("new machine", "0.065, 0.03"), ("machine designed before", "0.07, 0.03")):
        start = time.perf_counter()
        page.text_input(key="machine_shapes").set_value(shapes).run()
        print(f"machine page, {label} (mode shapes {shapes}): "
              f"{time.perf_counter() - start:.2f} s in the page's script")


if __name__ == "__main__":
    import sys

    if "--machine" in sys.argv[1:]:
        machine_page()
    else:
        main()
