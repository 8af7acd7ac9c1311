"""A user's gmsh mesh for a case: read, check the named groups, check the cells.

A case that builds its body by gmsh also accepts ``mesh_file=PATH``: a gmsh
``.msh`` whose *physical groups* carry the names the case documents (``tribofx
list``), one group of dimension d − 1 per named boundary (d the case's
dimension) and cells of dimension d.  Every problem is reported as a one-line
:class:`InputError` (:mod:`meshes.errors`, exit status 2 in the CLI), on every rank:

* the file cannot be read or is not a gmsh mesh;
* its mesh has the wrong dimension;
* a required group is missing, has the wrong dimension or holds no facet;
* the mesh has no cells of dimension d in a physical group;
* a cell is inverted or degenerate (its Jacobian determinant at the midpoint has
  the sign opposite to the other cells' of its group, or is below 1e-12 of
  their mean size);
* a cell group the case names (e.g. ``coating``, a material of its own) is
  empty, or a cell lies outside the named cell groups the file has.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import basix
import gmsh
import numpy as np
import ufl
from dolfinx import fem
from dolfinx import mesh as dmesh
from dolfinx.io import gmsh as gmshio
from mpi4py import MPI

from .errors import InputError

if TYPE_CHECKING:
    import numpy.typing as npt

    # {physical name: (dimension, tag)} of a gmsh file's physical groups
    Groups = dict[str, tuple[int, int]]

__all__ = ["boundary_facet_size", "num_cell_vertices", "read_user_mesh"]


def num_cell_vertices(cell_type: dmesh.CellType) -> int:
    """Return the number of vertices of a DOLFINx cell type (basix's reference topology)."""
    return len(basix.topology(basix.CellType[cell_type.name])[0])


def _error(msg: str) -> InputError:
    return InputError(msg)


def _open_on_root(path: str, comm: MPI.Comm, gdim: int) -> tuple[str | None, Groups, int]:
    """Open ``path`` in gmsh on rank 0: (message or None, {name: (dim, tag)}, mesh dim)."""
    msg: str | None
    groups: Groups
    msg, groups, dim = None, {}, -1
    if comm.rank == 0:
        if not os.path.isfile(path):
            msg = f"mesh file {path!r} does not exist"
        else:
            try:
                gmsh.open(path)
                dim = gmsh.model.getDimension()
                for d, tag in gmsh.model.getPhysicalGroups():
                    groups[gmsh.model.getPhysicalName(d, tag)] = (d, tag)
                if not len(gmsh.model.mesh.getNodes()[0]):
                    msg = f"mesh file {path!r} holds no mesh (run gmsh -{gdim} on it)"
            except Exception as err:  # gmsh raises a plain Exception on bad files
                msg = f"cannot read mesh file {path!r}: {str(err).splitlines()[0]}"
    return comm.bcast((msg, groups, dim), root=0)


def read_user_mesh(
    path: str | os.PathLike[str], comm: MPI.Comm, gdim: int, required: Sequence[str],
    cells: Sequence[str] | None = None,
) -> (tuple[dmesh.Mesh, dmesh.MeshTags, dict[str, int]]
      | tuple[dmesh.Mesh, dmesh.MeshTags, dict[str, int], dmesh.MeshTags | None,
              dict[str, int]]):
    """Read a gmsh mesh for a case of dimension ``gdim`` with named boundaries ``required``.

    Args:
        path: the ``.msh`` file.
        comm: communicator of the distributed mesh.
        gdim: the case's dimension (2 or 3).
        required: boundary names every one of which must be a non-empty physical
            group of dimension gdim − 1.
        cells: names of the cell groups (dimension gdim) the case gives materials
            of their own, e.g. ``("layer", "coating")``.  Those of them the file
            has must each hold cells, and then every cell must lie in one of them
            (a cell of another group would get no material); a file with none of
            them is one material.

    Returns:
        ``(mesh, facet_tags, names)`` with ``names`` {group name: facet tag value},
        the form a :class:`tribofx.body.Body` takes; with ``cells``,
        ``(mesh, facet_tags, names, cell_tags, cell_names)``, ``cell_names``
        {name: cell tag value} of the named cell groups in the file (may be empty).
    """
    path = os.fspath(path)
    initialized = gmsh.isInitialized()
    if not initialized:
        gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    try:
        msg, groups, dim = _open_on_root(path, comm, gdim)
        if msg is None and dim != gdim:
            msg = f"mesh file {path!r} is {dim}D, the case needs a {gdim}D mesh"
        if msg is None and not any(d == gdim for d, _ in groups.values()):
            msg = (f"mesh file {path!r} has no physical group of dimension {gdim} "
                   "(the body's cells)")
        if msg is None:
            for name in required:
                if name not in groups:
                    msg = (f"mesh file {path!r} has no physical group {name!r} (needs "
                           f"{', '.join(required)}; has {', '.join(groups) or 'none'})")
                    break
                if groups[name][0] != gdim - 1:
                    msg = (f"physical group {name!r} in {path!r} has dimension "
                           f"{groups[name][0]}, a boundary needs {gdim - 1}")
                    break
        if msg is not None:
            raise _error(msg)
        try:
            data = gmshio.model_to_mesh(gmsh.model, comm, 0, gdim=gdim)
        except RuntimeError as err:   # e.g. cells outside every physical group
            raise _error(f"mesh file {path!r}: {str(err).splitlines()[0]}") from None
    finally:
        if comm.rank == 0 and gmsh.isInitialized():
            gmsh.clear()
        if not initialized:
            gmsh.finalize()
    msh, ft = data.mesh, data.facet_tags
    if msh.topology.dim != gdim or ft is None:
        raise _error(f"mesh file {path!r} does not give {gdim}D cells with tagged boundaries")
    names = {name: groups[name][1] for name in required}
    for name, tag in names.items():
        n = comm.allreduce(int(np.sum(ft.values == tag)), op=MPI.SUM)
        if n == 0:
            raise _error(f"physical group {name!r} in {path!r} holds no boundary facet")
    _check_cells(msh, data.cell_tags, path)
    if cells is None:
        return msh, ft, names
    return (msh, ft, names, data.cell_tags,
            _cell_groups(msh, data.cell_tags, groups, cells, gdim, path))


def _cell_groups(
    msh: dmesh.Mesh, ct: dmesh.MeshTags | None, groups: Mapping[str, tuple[int, int]],
    cells: Sequence[str], gdim: int, path: str,
) -> dict[str, int]:
    """Return {name: tag} of the cell groups ``cells`` in the file.

    InputError if one of them is empty, or (when any is present) a cell lies
    outside all of them.
    """
    comm = msh.comm
    present = {n: groups[n][1] for n in cells if n in groups and groups[n][0] == gdim}
    if not present:
        return present
    assert ct is not None       # cells in named groups: the file tags cells
    n_local = msh.topology.index_map(gdim).size_local
    owned = ct.indices < n_local
    for name, tag in present.items():
        if comm.allreduce(int(np.sum(ct.values[owned] == tag)), op=MPI.SUM) == 0:
            raise _error(f"cell group {name!r} in {path!r} holds no cell")
    tagged = np.zeros(n_local, dtype=bool)
    tagged[ct.indices[owned][np.isin(ct.values[owned], list(present.values()))]] = True
    outside = comm.allreduce(int(np.sum(~tagged)), op=MPI.SUM)
    if outside:
        raise _error(f"{outside} cell(s) of {path!r} lie outside the cell groups "
                     f"{', '.join(present)} (every cell needs a material)")
    return present


def _check_cells(msh: dmesh.Mesh, cell_tags: dmesh.MeshTags | None, path: str) -> None:
    """Raise InputError if a cell is inverted or degenerate (see the module docstring).

    gmsh orients the elements of one entity consistently, so the sign of det J is
    compared within each cell group (two surfaces of opposite orientation are
    valid); a cell of the minority sign in its group, or with |det J| below 1e-12
    of the mean, is reported.
    """
    comm = msh.comm
    V0 = fem.functionspace(msh, ("DG", 0))
    detj = fem.Function(V0)
    detj.interpolate(fem.Expression(ufl.JacobianDeterminant(msh),
                                    V0.element.interpolation_points))
    n = msh.topology.index_map(msh.topology.dim).size_local
    d = detj.x.array[:n]
    group = np.zeros(n, dtype=np.int64)
    if cell_tags is not None:
        owned = cell_tags.indices < n
        group[cell_tags.indices[owned]] = cell_tags.values[owned]
    tags = sorted(set().union(*comm.allgather(set(np.unique(group).tolist()))))
    total = comm.allreduce(n, op=MPI.SUM)
    mean = comm.allreduce(float(np.sum(np.abs(d))), op=MPI.SUM) / max(total, 1)
    bad = 0
    for tag in tags:
        g = d[group == tag]
        pos = comm.allreduce(int(np.sum(g > 0)), op=MPI.SUM)
        neg = comm.allreduce(int(np.sum(g < 0)), op=MPI.SUM)
        sign = 1.0 if pos >= neg else -1.0
        bad += comm.allreduce(int(np.sum(sign * g <= 1e-12 * mean)), op=MPI.SUM)
    if bad:
        raise _error(f"mesh file {path!r} has {bad} inverted or degenerate cell(s) "
                     f"of {total}")


def boundary_facet_size(
    msh: dmesh.Mesh, ft: dmesh.MeshTags, tag: int,
    near: tuple[Sequence[float] | npt.NDArray[np.float64], float] | None = None,
) -> float:
    """Mean longest edge of the facets tagged ``tag`` (2D: their mean length).

    The element size a case takes from a user's mesh where its own mesh has a
    known size (e.g. the augmentation ρ_N = E/h of a contact boundary); the same
    value on every rank.  ``near=(point, radius)``: only the facets whose
    midpoint is within ``radius`` of ``point`` (e.g. the zone of first contact of
    a graded mesh), or the nearest ones if none is that close.
    """
    comm = msh.comm
    fdim = msh.topology.dim - 1
    im = msh.topology.index_map(fdim)
    facets = ft.find(tag)
    facets = facets[facets < im.size_local]
    nv = num_cell_vertices(msh.topology.entity_types[fdim][0])
    geo: npt.NDArray[np.int32] | npt.NDArray[np.int64]    # then as int64, nv columns
    geo = dmesh.entities_to_geometry(msh, fdim, facets, False)
    geo = np.asarray(geo, dtype=np.int64).reshape(len(facets), -1)[:, :nv] if len(facets) \
        else np.zeros((0, nv), dtype=np.int64)     # a rank without such facets: no rows
    x = msh.geometry.x[geo].reshape(len(facets), nv, 3)
    # edges: segment 0-1; triangle 0-1, 1-2, 2-0; quadrilateral (vertex order 0 1 3 2)
    pairs = {2: [(0, 1)], 3: [(0, 1), (1, 2), (2, 0)],
             4: [(0, 1), (1, 3), (3, 2), (2, 0)]}[nv]
    size = np.max([np.linalg.norm(x[:, i] - x[:, j], axis=1) for i, j in pairs], axis=0)
    if near is not None:
        point, radius = near
        p = np.zeros(3)
        p[:len(point)] = point
        d = np.linalg.norm(x.mean(axis=1) - p, axis=1)
        dmin = comm.allreduce(float(np.min(d, initial=np.inf)), op=MPI.MIN)
        size = size[d <= max(radius, dmin)]
    n = comm.allreduce(len(size), op=MPI.SUM)
    if n == 0:
        raise _error("no facet with the boundary tag " + str(tag))
    return comm.allreduce(float(np.sum(size)), op=MPI.SUM) / n
