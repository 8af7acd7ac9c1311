"""Build a gmsh model on rank 0 and distribute it as a DOLFINx mesh (shared by the builders)."""

import gmsh
from dolfinx.io import gmsh as gmshio

__all__ = ["distributed_model"]


def distributed_model(name, build, comm, gdim):
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
