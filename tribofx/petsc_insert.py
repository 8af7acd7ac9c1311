"""Dense element blocks into PETSc objects from C++ (the two-body contact's assembly).

:func:`add_matrix_blocks` and :func:`add_vector_blocks` hand n dense blocks to
the C++ loop of ``cpp_kernels/src/petsc_insert.hpp``, which calls PETSc's
``MatSetValues``/``VecSetValues`` (ADD_VALUES) once per block, without a
Python loop.  Shapes and packing:

* ``rows`` (n, nr) and ``cols`` (n, nc): global PETSc indices of block k
  (``PETSc.IntType``; −1 marks an unused slot, which PETSc skips);
* matrix ``values`` (n, nr, nc) float64, row-major per block; vector
  ``values`` (n, nr).

The wheel's PETSc has no headers: the C entry points are found in the
already loaded ``libpetsc`` (the one petsc4py uses) and passed by address
with the object handles (``Mat.handle``, ``Vec.handle``).  That lookup is
the only platform-dependent part and lives here.  :func:`add_matrix_blocks_ref`
and :func:`add_vector_blocks_ref` are the plain petsc4py twins, for the tests.
"""

import ctypes
import ctypes.util
import functools
import os

import numpy as np
from petsc4py import PETSc

from . import _cpp

__all__ = ["add_matrix_blocks", "add_matrix_blocks_ref", "add_vector_blocks",
           "add_vector_blocks_ref"]


@functools.cache
def _entry_points():
    """Addresses of MatSetValues and VecSetValues in the loaded libpetsc."""
    path = None
    try:
        with open("/proc/self/maps") as maps:    # Linux: the library petsc4py loaded
            for line in maps:
                if "libpetsc.so" in line:
                    path = line.split()[-1]
                    break
    except OSError:
        pass
    path = path or ctypes.util.find_library("petsc")
    if path is None:
        raise RuntimeError("libpetsc not found among the loaded libraries")
    lib = ctypes.CDLL(path, mode=getattr(os, "RTLD_NOLOAD", 0) | ctypes.RTLD_LOCAL)
    return tuple(ctypes.cast(getattr(lib, f), ctypes.c_void_p).value
                 for f in ("MatSetValues", "VecSetValues"))


def _indices(a):
    return np.ascontiguousarray(a, dtype=PETSc.IntType)


def add_matrix_blocks(A, rows, cols, values):
    """Add ``values[k]`` at ``rows[k] × cols[k]`` of the PETSc Mat ``A`` (see module)."""
    rows, cols = _indices(rows), _indices(cols)
    _cpp.add_matrix_blocks(_entry_points()[0], A.handle, rows, cols,
                           np.ascontiguousarray(values, dtype=np.float64))


def add_vector_blocks(b, rows, values):
    """Add ``values[k]`` at ``rows[k]`` of the PETSc Vec ``b`` (see module)."""
    _cpp.add_vector_blocks(_entry_points()[1], b.handle, _indices(rows),
                           np.ascontiguousarray(values, dtype=np.float64))


def add_matrix_blocks_ref(A, rows, cols, values):
    """Twin of :func:`add_matrix_blocks`: one petsc4py ``setValues`` per block."""
    for r, c, v in zip(rows, cols, values):
        keep_r, keep_c = r >= 0, c >= 0
        A.setValues(_indices(r[keep_r]), _indices(c[keep_c]), v[np.ix_(keep_r, keep_c)],
                    addv=True)


def add_vector_blocks_ref(b, rows, values):
    """Twin of :func:`add_vector_blocks`: one petsc4py ``setValues``."""
    rows, values = np.asarray(rows).ravel(), np.asarray(values).ravel()
    keep = rows >= 0
    b.setValues(_indices(rows[keep]), values[keep], addv=True)
