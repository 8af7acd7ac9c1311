"""SNES's preconditioner lag, read and set through the PETSc library (one version gap).

petsc4py 3.25 binds neither ``SNESSetLagPreconditioner`` nor
``SNESGetLagPreconditioner``; both are called here, by ctypes, from the PETSc
library that petsc4py loaded.  This is the one place that works around it.
"""

import ctypes

import numpy as np
from petsc4py import PETSc

__all__ = ["lag_preconditioner"]

_libpetsc = None


def lag_preconditioner(snes, lag=None):
    """Set (``lag`` given) and return SNES's preconditioner lag.

    −1: keep the preconditioner; −2: rebuild it at the next Jacobian, then −1;
    k ≥ 1: rebuild it every k Jacobians.  PetscInt is ``PETSc.IntType``.
    """
    global _libpetsc
    if _libpetsc is None:
        with open("/proc/self/maps") as f:
            path = next(ln.split()[-1] for ln in f if "/libpetsc.so" in ln)
        _libpetsc = ctypes.CDLL(path)
    cint = ctypes.c_int64 if np.dtype(PETSc.IntType).itemsize == 8 else ctypes.c_int32
    handle = ctypes.c_void_p(snes.handle)
    if lag is not None and _libpetsc.SNESSetLagPreconditioner(handle, cint(lag)) != 0:
        raise RuntimeError("SNESSetLagPreconditioner failed")
    out = cint()
    if _libpetsc.SNESGetLagPreconditioner(handle, ctypes.byref(out)) != 0:
        raise RuntimeError("SNESGetLagPreconditioner failed")
    return out.value
