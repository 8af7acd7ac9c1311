"""Build a gmsh model on rank 0 and distribute it as a DOLFINx mesh (shared by the builders)."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import gmsh
from dolfinx.io import gmsh as gmshio

if TYPE_CHECKING:
    from mpi4py import MPI

__all__ = ["distributed_model"]


def distributed_model(
    name: str, build: Callable[[], None], comm: MPI.Comm, gdim: int
) -> gmshio.MeshData:
    """Run ``build()`` on rank 0 into a new gmsh model ``name``; return the model's mesh data.

    gmsh is initialised (and finalised again) here unless the caller already
    has it running; the returned ``dolfinx.io.gmsh.MeshData`` has ``mesh``,
    ``cell_tags`` and ``facet_tags``.
    """
    initialized = gmsh.isInitialized()
    if not initialized:
        gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add(name)
    if comm.rank == 0:
        build()
    data = gmshio.model_to_mesh(gmsh.model, comm, 0, gdim=gdim)
    gmsh.model.remove()
    if not initialized:
        gmsh.finalize()
    return data
