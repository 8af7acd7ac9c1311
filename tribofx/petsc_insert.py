"""Dense element blocks into PETSc objects from C++ (the two-body contact's assembly).

:func:`add_matrix_blocks` and :func:`add_vector_blocks` hand n dense blocks to
the C++ loop of ``cpp_kernels/src/petsc_insert.hpp``, which calls PETSc's
``MatSetValues``/``VecSetValues`` (ADD_VALUES) once per block, without a
Python loop.  Shapes and packing:

* ``rows`` (n, nr) and ``cols`` (n, nc): global PETSc indices of block k
  (``PETSc.IntType``; −1 marks an unused slot, which PETSc skips);
* matrix ``values`` (n, nr, nc) float64, row-major per block; vector
  ``values`` (n, nr).

The wheel's PETSc has no headers: the C entry points are those of the PETSc
petsc4py loaded (:mod:`tribofx.petsc_lib`), passed by address with the object
handles (``Mat.handle``, ``Vec.handle``).  :func:`add_matrix_blocks_ref`
and :func:`add_vector_blocks_ref` are the plain petsc4py twins, for the tests.
"""

from __future__ import annotations

import functools

import numpy as np
import numpy.typing as npt
from petsc4py import PETSc

from . import _cpp
from .petsc_lib import address

__all__ = ["add_matrix_blocks", "add_matrix_blocks_ref", "add_vector_blocks",
           "add_vector_blocks_ref"]


@functools.cache
def _entry_points() -> tuple[int | None, int | None]:
    return address("MatSetValues"), address("VecSetValues")


def _indices(a: npt.ArrayLike) -> npt.NDArray[np.integer]:
    return np.ascontiguousarray(a, dtype=PETSc.IntType)


def add_matrix_blocks(A: PETSc.Mat, rows: npt.ArrayLike, cols: npt.ArrayLike,
                      values: npt.ArrayLike) -> None:
    """Add ``values[k]`` at ``rows[k] × cols[k]`` of the PETSc Mat ``A`` (see module)."""
    rows, cols = _indices(rows), _indices(cols)
    _cpp.add_matrix_blocks(_entry_points()[0], A.handle, rows, cols,
                           np.ascontiguousarray(values, dtype=np.float64))


def add_vector_blocks(b: PETSc.Vec, rows: npt.ArrayLike, values: npt.ArrayLike) -> None:
    """Add ``values[k]`` at ``rows[k]`` of the PETSc Vec ``b`` (see module)."""
    _cpp.add_vector_blocks(_entry_points()[1], b.handle, _indices(rows),
                           np.ascontiguousarray(values, dtype=np.float64))


def add_matrix_blocks_ref(A: PETSc.Mat, rows: npt.NDArray[np.integer],
                          cols: npt.NDArray[np.integer], values: npt.NDArray[np.float64]) -> None:
    """Twin of :func:`add_matrix_blocks`: one petsc4py ``setValues`` per block."""
    for r, c, v in zip(rows, cols, values):
        keep_r, keep_c = r >= 0, c >= 0
        # petsc4py's stub types indices and values as Sequence; it takes arrays
        A.setValues(_indices(r[keep_r]), _indices(c[keep_c]), v[np.ix_(keep_r, keep_c)],  # type: ignore[arg-type]
                    addv=True)


def add_vector_blocks_ref(b: PETSc.Vec, rows: npt.ArrayLike, values: npt.ArrayLike) -> None:
    """Twin of :func:`add_vector_blocks`: one petsc4py ``setValues``."""
    rows, values = np.asarray(rows).ravel(), np.asarray(values).ravel()
    keep = rows >= 0
    b.setValues(_indices(rows[keep]), values[keep], addv=True)  # type: ignore[arg-type]  # petsc4py stub: Sequence, not ndarray
