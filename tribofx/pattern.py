"""The Jacobian's sparsity pattern grown by couplings assembled outside UFL.

DOLFINx builds the matrix pattern from the UFL forms; the two-body contact
adds slave–master couplings whose pairs change as the bodies slide.  Adding an
entry outside a PETSc AIJ pattern costs a reallocation of the matrix storage
(measured: 2086 reallocations, 1.45 s, for the first insertion of a 12k-unknown
3D problem against 2.5 ms once the entries exist).  Before each solve the
components say which entries they may fill (:meth:`couplings`, their current
pairs and a margin of neighbouring facets); :func:`grow` returns a new matrix
whose preallocated pattern is the union of the old one and those entries (or
None when nothing is missing), with the old matrix's layout and local-to-global
maps, so that DOLFINx assembles into it unchanged.  Entries still missing
during the iterations fall back to PETSc's own allocation (the option
NEW_NONZERO_ALLOCATION_ERR is off).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from mpi4py import MPI
from petsc4py import PETSc

if TYPE_CHECKING:
    import numpy.typing as npt

__all__ = ["facet_rings", "grow"]


def grow(A: PETSc.Mat, rows: npt.ArrayLike, cols: npt.ArrayLike) -> PETSc.Mat | None:
    """Matrix with the pattern of ``A`` plus the entries rows[k, i] × cols[k, j], or None.

    Args:
        A: assembled PETSc AIJ matrix (its pattern is read, not changed).
        rows: (n, m) global row indices of n dense blocks (−1: unused slot).
        cols: (n, m') global column indices of the same blocks (−1: unused slot).
    """
    comm = A.getComm().tompi4py()
    rstart, rend = A.getOwnershipRange()
    N = A.getSize()[1]
    nloc = rend - rstart
    ai, aj, _ = A.getValuesCSR()
    old = np.repeat(np.arange(nloc, dtype=np.int64), np.diff(ai)) * N + aj
    r = np.repeat(np.asarray(rows, np.int64), np.shape(cols)[1], axis=1).ravel()
    c = np.tile(np.asarray(cols, np.int64), (1, np.shape(rows)[1])).ravel()
    keep = (r >= rstart) & (r < rend) & (c >= 0)
    new = np.unique((r[keep] - rstart) * N + c[keep])
    missing = np.setdiff1d(new, old, assume_unique=True)
    if comm.allreduce(len(missing), op=MPI.SUM) == 0:
        return None
    keys = np.union1d(old, missing)
    row_of = keys // N
    indptr = np.searchsorted(row_of, np.arange(nloc + 1)).astype(PETSc.IntType)
    M = PETSc.Mat().create(comm=A.getComm())
    # petsc4py's stubs: getSizes' pairs and NumPy index arrays are what these calls take
    M.setSizes(A.getSizes())  # type: ignore[arg-type]
    M.setType(A.getType())
    M.setOptionsPrefix(A.getOptionsPrefix())
    M.setPreallocationCSR((indptr, (keys % N).astype(PETSc.IntType)))  # type: ignore[arg-type]
    M.setLGMap(*A.getLGMap())
    M.setOption(PETSc.Mat.Option.NEW_NONZERO_ALLOCATION_ERR, False)  # type: ignore[arg-type]
    return M


def facet_rings(facets: npt.NDArray[np.integer]) -> npt.NDArray[np.int64]:
    """Per facet, the nodes of every facet sharing a node with it, padded with −1.

    ``facets`` (m, k) node indices; returns (m, width) int.  A contact node paired
    with facet f may slide onto any facet of its ring during Newton's iterations, so
    the ring's nodes belong to its preallocated couplings.
    """
    node_facets: list[list[int]] = [[] for _ in range(int(facets.max(initial=-1)) + 1)]
    for i, f in enumerate(facets):
        for v in f:
            node_facets[v].append(i)
    ring = [np.unique(facets[np.concatenate([node_facets[v] for v in f])]) for f in facets]
    width = max((len(r) for r in ring), default=0)
    return np.array([np.pad(r, (0, width - len(r)), constant_values=-1) for r in ring],
                    dtype=np.int64).reshape(len(facets), width)
