"""A user's layer mesh for ``ehl-cylinder-layer``: read, placed in the case's frame, checked.

``mesh_file`` gives the layer as a 2D gmsh ``.msh`` with the facet groups
``lubricated`` (Γ_l, one open curve under the cylinder) and ``bottom`` (bonded:
u = 0), and optionally the cell groups ``layer`` (modulus E) and ``coating``
(E_c).  The case needs Γ_l's highest node at y = 0 and the middle of its x
extent at x = 0, below the cylinder axis, and Γ_l ending at its two x extremes
X = ±x_l (p = 0 at both ends, the JFO inlet at X = −x_l).  Units: mm.

Your own layer (``mesh_file``): a 2D gmsh ``.msh`` with the physical groups
``lubricated`` (Γ_l, the face under the cylinder) and ``bottom`` (bonded: u = 0),
read, placed and checked by :mod:`tribofx.cases.ehl_user`; any other
boundary is traction free.  A coated layer carries the cell groups ``layer``
(modulus E) and ``coating`` (E_c), every cell in one of them; a mesh without
these groups is one material (E, ν).  It replaces H, x_l (half the x extent of
Γ_l), mesh and t_c (the coating is the user's cells).  The mesh is moved
so that Γ_l's highest node is at y = 0 and the middle of its x extent at x = 0,
below the cylinder axis (the rigid film h_r(W/steps) of the start is measured
from y = 0).  Γ_l must be one open curve ending at its two x extremes (checked):
p = 0 at both ends, the JFO inlet at the left end X = −x_l.  Everything else
applies as for the built layer (R, the cylinder; W, μ, U, the scales; the
lubrication model); ``mesh`` only sets the built layer's element sizes (SUPG
takes the cell size of Γ_l), so no size is needed from a user's mesh.
"""

import numpy as np
from dolfinx import mesh as dmesh
from mpi4py import MPI

from ..meshes.user import read_user_mesh
from ..params import InputError
from .film_setup import film_boundary

__all__ = ["USER_CELLS", "USER_GROUPS", "check_user_ends", "place_user_layer",
           "read_user_layer"]

#: boundary names a user's layer must carry
USER_GROUPS = ("lubricated", "bottom")
#: cell groups of a user's coated layer: E and E_c (optional)
USER_CELLS = ("layer", "coating")


def read_user_layer(v, comm, material):
    """Read and place the layer of ``v["mesh_file"]``; its materials from ``material(E)``.

    Returns ``(msh, ct, ft, names, materials, x_l)``: ``ct`` the cell tags (None
    without cell groups), ``names`` {group: tag}, ``materials`` {cell tag: law}
    (one law without cell groups), ``x_l`` half the x extent of Γ_l (mm).
    """
    msh, ft, names, ct, cells = read_user_mesh(v["mesh_file"], comm, 2, USER_GROUPS,
                                               cells=USER_CELLS)
    x_l = place_user_layer(msh, ft, names["lubricated"])
    if "coating" in cells and "layer" not in cells:
        raise InputError(f"{v['mesh_file']!r} has the cell group 'coating' but no "
                         "'layer' (the layer's cells, modulus E)")
    moduli = {"layer": v["E"], "coating": v["E_c"]}
    materials = ({tag: material(moduli[name]) for name, tag in cells.items()} if cells
                 else material(v["E"]))
    return msh, ct, ft, names, materials, x_l


def place_user_layer(msh, ft, tag):
    """Move a user's layer: Γ_l (facets ``tag``) highest at y = 0, x extent centred at 0.

    Returns x_l, half the x extent of Γ_l (mm).
    """
    comm = msh.comm
    msh.topology.create_connectivity(1, 2)
    x = msh.geometry.x
    nodes = np.unique(dmesh.entities_to_geometry(msh, 1, ft.find(tag), False).ravel())
    lo = comm.allreduce(float(np.min(x[nodes, 0], initial=np.inf)), op=MPI.MIN)
    hi = comm.allreduce(float(np.max(x[nodes, 0], initial=-np.inf)), op=MPI.MAX)
    top = comm.allreduce(float(np.max(x[nodes, 1], initial=-np.inf)), op=MPI.MAX)
    x[:, 0] -= 0.5 * (lo + hi)
    x[:, 1] -= top
    return 0.5 * (hi - lo)


def check_user_ends(film, v):
    """Raise InputError unless the user's Γ_l is one open curve ending at X = ±x_l.

    The pressure conditions (p = 0 at both ends, the JFO inlet at X = −x_l)
    need it; a closed or split curve has 0 or more than 2 end points.
    """
    ends = film_boundary(film)
    x_l = v["x_l"]
    if len(ends) != 2 or not np.allclose(np.sort(ends[:, 0]), [-x_l, x_l], atol=1e-9 * x_l):
        raise InputError(f"the group 'lubricated' of {v['mesh_file']!r} must be one open "
                         f"curve ending at its two x extremes (has {len(ends)} end "
                         f"point(s) at x = {', '.join(f'{e:.4g}' for e in ends[:, 0])})")
