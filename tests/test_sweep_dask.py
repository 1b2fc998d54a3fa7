"""The Dask backend on a real LocalCluster of separate worker processes (loopback only)."""

from __future__ import annotations

import pytest

from stickslip.sweep import occurrence_map
from stickslip.sweep.execution import ExecutionOptions
from tests.sweep_helpers import LAMS, ZETAS, assert_same_map

distributed = pytest.importorskip("distributed")


def test_dask_cluster_is_bit_identical_to_serial(cluster: object) -> None:
    serial = occurrence_map(LAMS, ZETAS, "optimal", execution=ExecutionOptions(backend="serial"))
    address = cluster.scheduler_address  # type: ignore[attr-defined]
    assert address.startswith("tcp://127.0.0.1:")
    done: list[int] = []
    remote = occurrence_map(LAMS, ZETAS, "optimal",
                            execution=ExecutionOptions(backend="dask", scheduler=address, chunk_size=4,
                                                       progress=lambda d, n: done.append(d)))
    assert_same_map(serial.dataset, remote.dataset)
    assert remote.chunks_computed == 8 and remote.backend == "dask"
    assert done[0] == 0 and done[-1] == 30 and sorted(done) == done
    workers = cluster.scheduler_info["workers"]  # type: ignore[attr-defined]
    assert len(workers) == 2


def test_unreachable_scheduler_is_a_one_line_error() -> None:
    with pytest.raises(ValueError, match="cannot reach the dask scheduler"):
        occurrence_map([1.0], [0.1], "none",
                       execution=ExecutionOptions(backend="dask", scheduler="tcp://127.0.0.1:9"))
