"""The agreement tests' shared fixture: ``L``, the benchmarks' ``libraries`` module, after the module's own ``A``
fixture has checked that the extras it needs import."""
from __future__ import annotations

import pytest
from _bench import bench_module


@pytest.fixture(scope="module")
def L(A):
    return bench_module("libraries")
