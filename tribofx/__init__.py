"""tribofx: finite wear and soft-EHL of soft solids at finite deformation on FEniCSx."""

import dolfinx_solver  # noqa: F401  (loads the MPI/PETSc libraries; before dolfinx/petsc4py)

from .jit import compiler_warnings, read_plugins_once

compiler_warnings(show=False)  # quiet JIT compiles; `tribofx run -v` shows them (tribofx.jit)
read_plugins_once()  # each JIT compile reads setuptools' plugins once per process (tribofx.jit)

__all__ = ["__version__"]
__version__ = "0.1.0"
