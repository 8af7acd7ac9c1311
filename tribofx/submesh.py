"""Facet submeshes: the home of fields that live only on a boundary (multipliers, pressure)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from dolfinx import mesh as dmesh
from mpi4py import MPI

if TYPE_CHECKING:
    import numpy.typing as npt

__all__ = ["facet_submesh"]


def facet_submesh(msh: dmesh.Mesh, facet_tags: dmesh.MeshTags, tag: int | tuple[int, ...],
                  what: str) -> tuple[dmesh.Mesh, dmesh.EntityMap, npt.NDArray[np.int32]]:
    """Submesh of the facets tagged ``tag``; returns ``(submesh, entity_map, geometry_map)``.

    ``tag``: a tag value or a tuple of values (the union of those boundaries).

    ``what`` names the surface in the error raised when no facet carries the tag.
    The facet-to-cell connectivity needed by mixed-dimensional assembly is created.
    """
    tdim = msh.topology.dim
    msh.topology.create_connectivity(tdim - 1, tdim)
    tags = tag if isinstance(tag, tuple) else (tag,)
    facets = np.unique(np.concatenate([facet_tags.find(t) for t in tags])).astype(np.int32)
    if msh.comm.allreduce(len(facets), op=MPI.SUM) == 0:
        raise ValueError(f"mesh has no facets tagged {tag} ({what})")
    sub, emap, _, gmap = dmesh.create_submesh(msh, tdim - 1, facets)
    return sub, emap, gmap
