"""SNES's preconditioner lag, read and set through the PETSc library (one version gap).

petsc4py 3.25 binds neither ``SNESSetLagPreconditioner`` nor
``SNESGetLagPreconditioner``; both are called here, by ctypes, from the PETSc
library that petsc4py loaded (:mod:`tribofx.petsc_lib`).
"""

from __future__ import annotations

import ctypes

import numpy as np
from petsc4py import PETSc

from .petsc_lib import function

__all__ = ["lag_preconditioner"]


def lag_preconditioner(snes: PETSc.SNES, lag: int | None = None) -> int:
    """Set (``lag`` given) and return SNES's preconditioner lag.

    −1: keep the preconditioner; −2: rebuild it at the next Jacobian, then −1;
    k ≥ 1: rebuild it every k Jacobians.  PetscInt is ``PETSc.IntType``.
    """
    cint = ctypes.c_int64 if np.dtype(PETSc.IntType).itemsize == 8 else ctypes.c_int32
    handle = ctypes.c_void_p(snes.handle)
    if lag is not None and function("SNESSetLagPreconditioner")(handle, cint(lag)) != 0:
        raise RuntimeError("SNESSetLagPreconditioner failed")
    out = cint()
    if function("SNESGetLagPreconditioner")(handle, ctypes.byref(out)) != 0:
        raise RuntimeError("SNESGetLagPreconditioner failed")
    return out.value
