"""ExecutionOptions: one validated object for how a sweep runs (issue 17, point 3).

The loose keywords of before still work for one release with a DeprecationWarning, and give
the same answers as ``execution=`` (the backends are bit-identical: DESIGN.md section 6).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from stickslip import Slider, rigid_base
from stickslip.sweep import ExecutionOptions, basin_map, basin_stability, occurrence_map, sample_box
from stickslip.sweep.boundary import stick_slip_boundary
from stickslip.sweep.execution import EXECUTION_KEYWORDS, execution_from_keywords


@pytest.mark.parametrize("kwargs, fragment", [
    ({"backend": "gpu"}, "not one of"),
    ({"workers": 0}, "at least 1"),
    ({"workers": 1.5}, "whole number"),
    ({"chunk_size": 0}, "at least 1"),
    ({"scheduler": "tcp://127.0.0.1:1"}, "needs the dask backend"),
    ({"backend": "dask", "scheduler": "tcp://127.0.0.1:1", "workers": 2}, "not both"),
    ({"backend": "serial", "workers": 2}, "one thread"),
    ({"overwrite": "yes"}, "True or False"),
    ({"progress": 3}, "callable"),
])
def test_execution_options_are_validated_at_construction(kwargs, fragment):  # type: ignore[no-untyped-def]
    with pytest.raises(ValueError, match=fragment):
        ExecutionOptions(**kwargs)


def test_execution_options_are_frozen_and_replace_validates():  # type: ignore[no-untyped-def]
    run = ExecutionOptions(workers=2)
    with pytest.raises(AttributeError):
        run.workers = 3  # type: ignore[misc]
    assert run.replace(chunk_size=8).chunk_size == 8
    with pytest.raises(ValueError):
        run.replace(chunk_size=-1)


def test_old_keywords_warn_and_unknown_ones_are_refused():  # type: ignore[no-untyped-def]
    with pytest.warns(DeprecationWarning, match=r"execution=ExecutionOptions\(workers=...\)"):
        run = execution_from_keywords(None, {"workers": 1}, "occurrence_map")
    assert run == ExecutionOptions(workers=1)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert execution_from_keywords(ExecutionOptions(chunk_size=5), {}, "f").chunk_size == 5
    with pytest.raises(TypeError, match="unexpected keyword argument 'worker'"):
        execution_from_keywords(None, {"worker": 1}, "occurrence_map")
    assert set(EXECUTION_KEYWORDS) == {f for f in ExecutionOptions.__dataclass_fields__}


def test_occurrence_map_old_keywords_give_the_same_map():  # type: ignore[no-untyped-def]
    seen: list[tuple[int, int]] = []
    new = occurrence_map("log:0.5:5:4", [0.05, 0.3], execution=ExecutionOptions(
        backend="serial", chunk_size=3, progress=lambda d, t: seen.append((d, t))))
    with pytest.warns(DeprecationWarning, match="occurrence_map"):
        old = occurrence_map("log:0.5:5:4", [0.05, 0.3], backend="serial", chunk_size=3)
    np.testing.assert_array_equal(new.verdict, old.verdict)
    np.testing.assert_array_equal(new.dataset["period"].values, old.dataset["period"].values)
    assert seen[0] == (0, 8) and seen[-1] == (8, 8) and len(seen) == 1 + 3  # ceil(8 / 3) chunks
    assert new.second_axis_name == "zeta"
    with pytest.warns(DeprecationWarning, match="second_axis_name"):
        assert new.second == "zeta"


def test_basin_stability_takes_execution():  # type: ignore[no-untyped-def]
    structure, slider = rigid_base(0.1), Slider(2.5)
    states = sample_box(structure, slider, 64, {"xi": (-2.0, 2.0), "v": (-2.0, 1.0)}, 1)
    new = basin_stability(structure, slider, states, execution=ExecutionOptions(chunk_size=16))
    with pytest.warns(DeprecationWarning, match="basin_stability"):
        old = basin_stability(structure, slider, states, chunk_size=16, workers=1)
    np.testing.assert_array_equal(new.verdict, old.verdict)
    assert new.chunks_total == 4


def test_in_process_sweeps_refuse_what_they_cannot_honour():  # type: ignore[no-untyped-def]
    with pytest.raises(ValueError, match=r"numba threads in this process only.*backend='dask'"):
        stick_slip_boundary([0.1], execution=ExecutionOptions(backend="dask"))
    with pytest.raises(ValueError, match="progress"):
        stick_slip_boundary([0.1], execution=ExecutionOptions(progress=lambda d, t: None))
    with pytest.raises(ValueError, match="store"):
        basin_map("log:0.5:5:2", [0.1], samples=4, execution=ExecutionOptions(store="x"))


def test_moved_and_renamed_names_still_work_with_a_warning():  # type: ignore[no-untyped-def]
    import stickslip.sweep.basin as basin_module
    from stickslip.sweep.basin_maps import DEFAULT_MAP_BOX, BasinMap

    for name, new in (("basin_map", basin_map), ("BasinMap", BasinMap), ("DEFAULT_MAP_BOX", DEFAULT_MAP_BOX)):
        with pytest.warns(DeprecationWarning, match=f"stickslip.sweep.basin_maps.{name}"):
            assert getattr(basin_module, name) is new
    with pytest.raises(AttributeError):
        basin_module.no_such_name  # noqa: B018


def test_sweep_face_gives_functions_not_modules():  # type: ignore[no-untyped-def]
    """A submodule named like a function would shadow it on the lazy face once imported."""
    import importlib

    import stickslip.sweep as face

    for name in face.__all__:
        importlib.import_module(face._EXPORTS[name])
        assert not isinstance(getattr(face, name), type(face)), name
