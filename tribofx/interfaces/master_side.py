"""The master side of a two-body interface: the current master boundary on every rank.

A slave node of a two-body interface (:class:`tribofx.interfaces.TwoBodyContact`,
:class:`tribofx.interfaces.TwoBodyFilm`) may pair with a master facet owned by
another rank.  :class:`MasterSide` holds the master boundary's facets, oriented
with the master's outward normal ((τ_y, −τ_x)/l in 2D, t₁ × t₂/|t₁ × t₂| in 3D,
the convention of :mod:`tribofx.two_body`), gathers their current nodes on
every rank (one row per global node, sorted by global dof), keeps the C++ box
tree of the search (refitted while the facets stay the same), and maps the
gathered nodes to the rows and columns of a :class:`tribofx.problem.Problem`.
"""

from __future__ import annotations

import weakref
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from dolfinx import mesh as dmesh
from mpi4py import MPI

from ..pattern import facet_rings
from ..petsc_insert import add_matrix_blocks, add_vector_blocks
from ..protocols import ComponentBase
from ..two_body import MasterSurface, MasterSurface3
from . import facets
from .surface import node_to_dof

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    import numpy.typing as npt
    from petsc4py import PETSc

    from ..body import Body
    from ..problem import Problem
    from .facets import Pairing

    #: global (rows, cols) of dofs in a problem (−1: not in it, or not solved for)
    RowsCols = tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]
    #: a kernel evaluation's cache: (the state's arrays it was evaluated at, its data)
    KernelCache = tuple[Sequence[npt.NDArray[Any]], dict[str, Any]]

__all__ = ["KernelAssembly", "MasterSide", "cached_state"]


def _vertex_dofs(body: Body, fs: npt.NDArray[np.int32]) -> npt.NDArray[np.int64]:
    """Per facet the (P1 block) dofs of its vertices, local indices."""
    msh = body.mesh
    geo = dmesh.entities_to_geometry(msh, msh.topology.dim - 1, fs, False)
    return node_to_dof(body.V)[geo]


def cached_state(cache: KernelCache | None, key: Sequence[npt.NDArray[Any]],
                 comm: MPI.Comm) -> dict[str, Any] | None:
    """Return the data of ``cache`` = (key, data) if its key equals ``key`` on all ranks.

    A kernel evaluation is collective (the master is gathered), so the cache hit is
    decided on all ranks together; returns the data, or None (evaluate again).
    """
    same = cache is not None and len(cache[0]) == len(key) and all(
        a.shape == b.shape and np.array_equal(a, b) for a, b in zip(cache[0], key))
    # a hit on all ranks is a hit on this one: cache is not None
    return cast("KernelCache", cache)[1] if comm.allreduce(same, op=MPI.LAND) else None


class MasterSide:
    """The boundary ``boundary`` of ``master`` as the master of a two-body interface."""

    _tree: Any          # the C++ box tree (MasterSurface or MasterSurface3), no stub
    _segments: npt.NDArray[np.int32] | None
    _ring: npt.NDArray[np.int64] | None
    _ring_seg: npt.NDArray[np.int32] | None
    _ref_keys: npt.NDArray[np.int64] | None
    _ref: npt.NDArray[np.float64] | None
    _seg: npt.NDArray[np.int32] | None
    _rows: dict[int, tuple[weakref.ref[Problem], RowsCols]]

    def __init__(self, master: Body, boundary: str) -> None:
        self.body = master
        self.gdim = d = master.gdim
        mfacets = master.facets(boundary)
        seg = _vertex_dofs(master, mfacets)
        if len(mfacets):
            mm = master.mesh
            tdim = mm.topology.dim
            mm.topology.create_connectivity(tdim - 1, tdim)
            f2c = mm.topology.connectivity(tdim - 1, tdim)
            cells = np.array([f2c.links(f)[0] for f in mfacets])
            xc = mm.geometry.x[dmesh.entities_to_geometry(mm, tdim, cells, False)].mean(axis=1)
            Xd = master.V.tabulate_dof_coordinates()[:, :d]
            a, b = Xd[seg[:, 0]], Xd[seg[:, 1]]
            if d == 2:
                t = b - a
                out = np.c_[t[:, 1], -t[:, 0]]
            else:
                out = np.cross(b - a, Xd[seg[:, 2]] - a)
            flip = np.sum(out * (Xd[seg].mean(axis=1) - xc[:, :d]), axis=1) < 0
            seg[flip] = seg[flip][:, ::-1] if d == 2 else seg[flip][:, [0, 2, 1]]
        self.seg_local = seg
        self._tree = self._segments = None
        self._ring = self._ring_seg = None
        self._ref_keys = self._ref = None
        self._seg, self._rows = None, {}

    def dofs(self) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]:
        """Local (P1 block) dofs of the master boundary and their global block indices."""
        dofs = np.unique(self.seg_local)
        im = self.body.V.dofmap.index_map
        return dofs, im.local_to_global(dofs.astype(np.int32))

    def gather(self, local: Callable[[npt.NDArray[np.int64]], npt.NDArray[Any]]
               ) -> tuple[npt.NDArray[np.int64], npt.NDArray[Any]]:
        """Concatenate per-node arrays ``local(dofs)`` of every rank, one row per global node."""
        dofs, keys = self.dofs()
        parts = self.body.mesh.comm.allgather((keys, local(dofs)))
        allk = np.concatenate([p[0] for p in parts])
        uniq, first = np.unique(allk, return_index=True)
        return uniq, np.concatenate([p[1] for p in parts])[first]

    def current(
            self
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64], npt.NDArray[np.int32]]:
        """Return current master positions (n_m, d), global node keys, facets (all ranks)."""
        m, d = self.body, self.gdim
        X = m.V.tabulate_dof_coordinates()[:, :d]
        u = m.u.x.array.reshape(-1, d)
        keys, x = self.gather(lambda nd: X[nd] + u[nd])
        if self._seg is None:                  # the facets' topology: gathered once
            dofs, local_keys = self.dofs()
            seg_keys = local_keys[np.searchsorted(dofs, self.seg_local)]
            allseg = np.concatenate(m.mesh.comm.allgather(seg_keys.reshape(-1, d)))
            seg = np.unique(np.searchsorted(keys, allseg), axis=0)   # on two ranks: once
            self._seg = seg.astype(np.int32)
        return x, keys, self._seg

    def reference(self, keys: npt.NDArray[np.int64]) -> npt.NDArray[np.float64]:
        """Return the reference positions of the gathered nodes ``keys`` (cached)."""
        if self._ref_keys is None or not np.array_equal(self._ref_keys, keys):
            X = self.body.V.tabulate_dof_coordinates()[:, :self.gdim]
            self._ref_keys, self._ref = self.gather(lambda nd: X[nd])
        assert self._ref is not None        # set with _ref_keys
        return self._ref

    def project(self, xs: npt.NDArray[np.float64], reference: Pairing | None, sticky: float
                ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64],
                           npt.NDArray[np.int32], dict[str, npt.NDArray[Any]]]:
        """Project the slave positions ``xs`` (n, d) onto the current master boundary.

        The box tree is refitted (rebuilt when the gathered facets change); a node
        keeps its ``reference`` facet (segments, facet per node) under the
        hysteresis ``sticky`` (:func:`facets.keep_reference_facets`).  Returns
        ``(xm, keys, seg, proj)`` with ``proj`` the kernel's ``facet``, ``xi``,
        ``distance``.
        """
        xm, keys, seg = self.current()
        # _segments (the tree's facets) is None only before the first search, with _tree
        if self._tree is None or cast("npt.NDArray[np.int32]", self._segments).shape != seg.shape \
                or not np.array_equal(cast("npt.NDArray[np.int32]", self._segments), seg):
            surface = MasterSurface if self.gdim == 2 else MasterSurface3
            self._tree, self._segments = surface(np.ascontiguousarray(xm), seg), seg
        else:
            self._tree.refit(np.ascontiguousarray(xm))
        proj = self._tree.project(np.ascontiguousarray(xs))
        proj = facets.keep_reference_facets(xs, xm, seg, proj, reference, sticky)
        return xm, keys, seg, proj

    def rows(self, problem: Problem) -> RowsCols:
        """Return global (rows, cols) (n_m, d) of the gathered master nodes in ``problem``."""
        ref, rows = self._rows.get(id(problem), (None, None))
        if ref is None or ref() is not problem:     # a problem's layout is fixed: once
            d = self.gdim
            mrow, mcol = problem.global_rows(self.body.u)
            _, rc = self.gather(lambda nd: np.c_[
                np.stack([mrow[d * nd + c] for c in range(d)], 1),
                np.stack([mcol[d * nd + c] for c in range(d)], 1)])
            rows = (rc[:, :d], rc[:, d:])
            self._rows[id(problem)] = (weakref.ref(problem), rows)
        assert rows is not None             # stored with its problem, or just computed
        return rows

    def ring_rows(self, rm: npt.NDArray[np.int64], cm: npt.NDArray[np.int64],
                  seg: npt.NDArray[np.int32], facet: npt.NDArray[np.int32]) -> RowsCols:
        """Rows and columns (n, d·width) of the master nodes of every facet near ``facet``.

        A node paired with facet f may slide onto any facet sharing a node with f
        during the iterations (:func:`tribofx.pattern.facet_rings`), so those
        couplings are preallocated.
        """
        # the rings depend on the segments only: rebuilt when they change
        if self._ring_seg is None or not np.array_equal(self._ring_seg, seg):
            self._ring, self._ring_seg = facet_rings(seg), seg.copy()
        assert self._ring is not None       # set with _ring_seg
        ring = self._ring[facet]
        valid = ring >= 0
        width = self.gdim * ring.shape[1]
        safe = np.maximum(ring, 0)
        rr = np.where(valid[..., None], rm[safe], -1).reshape(len(facet), width)
        cc = np.where(valid[..., None], cm[safe], -1).reshape(len(facet), width)
        return rr, cc


class KernelAssembly(ComponentBase):
    """The nodal kernel of a two-body interface in a :class:`tribofx.problem.Problem`.

    Base of :class:`~tribofx.interfaces.TwoBodyContact` and
    :class:`~tribofx.interfaces.TwoBodyFilm`, which give ``side`` (a
    :class:`MasterSide`), ``sub`` (the slave's submesh), ``_kernel()`` (a dict
    with ``r``, ``J``, ``seg``, ``facet`` of the current state), ``_rows(problem,
    k)`` (global rows and columns of the kernel's slots) and the pairing
    references ``_facet_ref``, ``_facet_committed``.
    """

    assembles = True
    iterates = True

    side: MasterSide
    sub: dmesh.Mesh
    _facet_ref: Pairing | None
    _facet_committed: Pairing | None

    if TYPE_CHECKING:   # given by the subclass
        def _kernel(self) -> dict[str, Any]: ...

        def _rows(self, problem: Problem, k: dict[str, Any]) -> RowsCols: ...

    def _kernel_ready(self) -> bool:
        """Whether the kernel has a committed state to evaluate (always, by default)."""
        return True

    def couplings(self, problem: Problem) -> RowsCols:
        """Dense blocks (rows, cols) of the entries the kernel may add in the next solve.

        Per owned slave node its slots and the nodes of every master facet sharing
        a node with its current one (a node sliding onto a neighbour facet during
        the iterations stays inside the pattern), all against all (:mod:`tribofx.pattern`).
        """
        k = self._kernel()
        rows, cols = self._rows(problem, k)
        rr, cc = self.side.ring_rows(*self.side.rows(problem), k["seg"], k["facet"])
        return np.c_[rows, rr], np.c_[cols, cc]

    def evaluate(self, problem: Problem) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64],
                                                  npt.NDArray[np.int64], npt.NDArray[np.int64]]:
        """Kernel residuals and tangents of the owned slave nodes, with their rows/columns."""
        k = self._kernel()
        rows, cols = self._rows(problem, k)
        return k["r"], k["J"], rows, cols

    def add_residual(self, b: PETSc.Vec, problem: Problem) -> None:
        """Add the kernel residual of every owned slave node to ``b`` (global rows, C++)."""
        r, _, rows, _ = self.evaluate(problem)
        add_vector_blocks(b, rows, r)

    def add_jacobian(self, A: PETSc.Mat, problem: Problem) -> None:
        """Add the kernel's dense tangent block of every owned slave node to ``A`` (C++).

        Inserted by :func:`tribofx.petsc_insert.add_matrix_blocks` (unused slots −1).
        """
        _, J, rows, cols = self.evaluate(problem)
        add_matrix_blocks(A, rows, cols, J)

    def reset_iterate(self) -> None:
        """Start a Newton solve (or a restore): the pairing's reference is the committed one."""
        self._facet_ref = self._facet_committed

    def accept_iterate(self) -> bool:
        """Move the pairing's reference to the current (accepted) Newton iterate.

        Returns whether any slave node changed facet (on any rank): the residual at
        the iterate is then evaluated again, so that it and the Jacobian share the
        reference.
        """
        if not self._kernel_ready():
            return False
        k = self._kernel()
        same = facets.same_pairing(self._facet_ref, (k["seg"], k["facet"]))
        self._facet_ref = (k["seg"].copy(), k["facet"].copy())
        return not self.sub.comm.allreduce(same, op=MPI.LAND)
