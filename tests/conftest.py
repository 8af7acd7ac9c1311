"""Shared pytest configuration: the ``--runslow`` flag and MPI-safe imports."""

import gc
import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: E402,F401  (must be imported before dolfinx/petsc4py)
import pytest  # noqa: E402


def pytest_addoption(parser):
    parser.addoption("--runslow", action="store_true", default=False,
                     help="also run tests marked slow (large meshes, long runs)")


def pytest_collection_modifyitems(config, items):
    if config.getoption("--runslow"):
        return
    skip = pytest.mark.skip(reason="slow: run with --runslow")
    for item in items:
        if "slow" in item.keywords:
            item.add_marker(skip)


@pytest.fixture(autouse=True)
def _collect_garbage():
    """Free each test's meshes and PETSc objects before the next test, on every rank.

    Reference cycles (forms ↔ functions, components ↔ problems) keep meshes and
    their duplicated MPI communicators until the cycle collector runs; collecting
    after each test frees them at the same point on all ranks and keeps the
    process far from MPICH's limit of 2048 communicators.
    """
    yield
    gc.collect()
