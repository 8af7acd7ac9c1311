"""A user's gmsh mesh for a case: read, check the named groups, check the cells.

A case that builds its body by gmsh also accepts ``mesh_file=PATH``: a gmsh
``.msh`` whose *physical groups* carry the names the case documents (``tribofx
list``), one group of dimension d − 1 per named boundary (d the case's
dimension) and cells of dimension d.  Every problem is reported as a one-line
:class:`tribofx.params.InputError` (exit status 2 in the CLI), on every rank:

* the file cannot be read or is not a gmsh mesh;
* its mesh has the wrong dimension;
* a required group is missing, has the wrong dimension or holds no facet;
* a cell is inverted or degenerate (its Jacobian determinant at the midpoint has
  the sign opposite to the other cells', or is below 1e-12 of their mean size).
"""

import os

import gmsh
import numpy as np
import ufl
from dolfinx import fem
from dolfinx.io import gmsh as gmshio
from mpi4py import MPI

__all__ = ["read_user_mesh"]


def _error(msg):
    from tribofx.params import InputError

    return InputError(msg)


def _open_on_root(path, comm, gdim):
    """Open ``path`` in gmsh on rank 0: (message or None, {name: (dim, tag)}, mesh dim)."""
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


def read_user_mesh(path, comm, gdim, required):
    """Read a gmsh mesh for a case of dimension ``gdim`` with named boundaries ``required``.

    Args:
        path: the ``.msh`` file.
        comm: communicator of the distributed mesh.
        gdim: the case's dimension (2 or 3).
        required: boundary names every one of which must be a non-empty physical
            group of dimension gdim − 1.

    Returns:
        ``(mesh, facet_tags, names)`` with ``names`` {group name: facet tag value},
        the form a :class:`tribofx.body.Body` takes.
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
        data = gmshio.model_to_mesh(gmsh.model, comm, 0, gdim=gdim)
    finally:
        if comm.rank == 0 and gmsh.isInitialized():
            gmsh.clear()
        if not initialized:
            gmsh.finalize()
    msh, ft = data.mesh, data.facet_tags
    names = {name: groups[name][1] for name in required}
    for name, tag in names.items():
        n = comm.allreduce(int(np.sum(ft.values == tag)), op=MPI.SUM)
        if n == 0:
            raise _error(f"physical group {name!r} in {path!r} holds no boundary facet")
    _check_cells(msh, path)
    return msh, ft, names


def _check_cells(msh, path):
    """Raise InputError if a cell is inverted or degenerate (see the module docstring)."""
    comm = msh.comm
    V0 = fem.functionspace(msh, ("DG", 0))
    detj = fem.Function(V0)
    detj.interpolate(fem.Expression(ufl.JacobianDeterminant(msh),
                                    V0.element.interpolation_points))
    n = msh.topology.index_map(msh.topology.dim).size_local
    d = detj.x.array[:n]
    pos = comm.allreduce(int(np.sum(d > 0)), op=MPI.SUM)
    neg = comm.allreduce(int(np.sum(d < 0)), op=MPI.SUM)
    total = comm.allreduce(n, op=MPI.SUM)
    sign = 1.0 if pos >= neg else -1.0
    mean = comm.allreduce(float(np.sum(np.abs(d))), op=MPI.SUM) / max(total, 1)
    bad = comm.allreduce(int(np.sum(sign * d <= 1e-12 * mean)), op=MPI.SUM)
    if bad:
        raise _error(f"mesh file {path!r} has {bad} inverted or degenerate cell(s) "
                     f"of {total}")
