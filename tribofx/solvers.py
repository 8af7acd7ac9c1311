"""Linear-solver strategies of a :class:`tribofx.problem.Problem`.

A strategy gives the PETSc options of the Newton system's KSP/PC (set under the
problem's prefix unless the command line sets them) and may configure the KSP
after SNES is set up (fieldsplit index sets, near-nullspaces).
"""

__all__ = ["DirectSolver"]


class DirectSolver:
    """Sparse LU by MUMPS (``preonly`` + ``lu``), the default for small problems.

    Args:
        package: factorisation package (``mumps``).
    """

    def __init__(self, package="mumps"):
        self.package = package

    def options(self):
        """PETSc options of the KSP and PC (without the problem's prefix)."""
        return {"ksp_type": "preonly", "pc_type": "lu",
                "pc_factor_mat_solver_type": self.package}

    def configure(self, problem):
        """Nothing beyond the options for a direct solve."""
