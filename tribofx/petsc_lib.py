"""The PETSc C library that petsc4py loaded, for the few entry points petsc4py does not bind.

The wheel's PETSc ships no headers, and petsc4py 3.25 binds neither
``SNESSetLagPreconditioner``/``SNESGetLagPreconditioner`` (:mod:`tribofx.snes_lag`)
nor a raw ``MatSetValues``/``VecSetValues`` for C++ loops
(:mod:`tribofx.petsc_insert`).  Both are looked up here, in one place, through
petsc4py's own extension module: ``dlsym`` on its handle searches the module and
the libraries it was linked against, so the symbol is the one of the PETSc that
petsc4py itself calls (no path search, no second copy of the library).
"""

from __future__ import annotations

import ctypes
import functools

from petsc4py import PETSc

__all__ = ["address", "function"]


@functools.cache
def _library() -> ctypes.CDLL:
    return ctypes.CDLL(PETSc.__file__)


def function(name: str) -> ctypes._NamedFuncPointer:
    """Return the C function ``name`` of petsc4py's PETSc (a ctypes function pointer)."""
    try:
        return getattr(_library(), name)
    except AttributeError:
        raise RuntimeError(f"{name} not found in the PETSc library petsc4py loaded") from None


def address(name: str) -> int | None:
    """Return the address of the C function ``name`` of petsc4py's PETSc (an int)."""
    return ctypes.cast(function(name), ctypes.c_void_p).value
