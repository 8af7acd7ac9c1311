"""Outputs of a :class:`tribofx.interfaces.TwoBodyContact` and its kernel data for wear.

:class:`TwoBodyOutputs` is the part of the two-body contact that reads the C++
kernel's per-node results after a solve: nodal tractions and pressures, the
forces on both bodies, the rank-0 profile, and the public view of the kernel
data that :mod:`tribofx.interfaces.two_body_wear` uses (eqs. 17–18).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from ..forms import kinematics as kin
from .contact import gather_nodal

if TYPE_CHECKING:
    import numpy.typing as npt
    from dolfinx import mesh as dmesh

    from ..body import Body
    from ..problem import Problem

__all__ = ["TwoBodyOutputs"]


class TwoBodyOutputs:
    """Post-processing of :class:`TwoBodyContact` (its base; reads ``_kernel()`` and the layout)."""

    # given by TwoBodyContact
    slave: Body
    gdim: int
    rho_n: float
    rho_t: float
    Q: fem.FunctionSpace
    emap: dmesh.EntityMap
    dsc: ufl.Measure
    _q: npt.NDArray[np.int64]
    _X: npt.NDArray[np.float64]
    _w_c: npt.NDArray[np.float64]
    _lam: int
    _post: fem.Form | None

    if TYPE_CHECKING:
        def _kernel(self) -> dict[str, Any]: ...

        def _lumped(self, form: fem.Form | ufl.Form) -> npt.NDArray[np.float64]: ...

    # -- kernel data for the wear of both surfaces --------------------------------------
    def kernel_data(self) -> dict[str, Any]:
        """Kernel data of the owned slave nodes at the current state (see :meth:`_kernel`)."""
        return self._kernel()

    @property
    def slave_dofs(self) -> npt.NDArray[np.int64]:
        """Submesh dofs of the owned slave nodes, in the kernel's (λ-dof) order."""
        return self._q

    @property
    def constraint_weights(self) -> npt.NDArray[np.float64]:
        """Lumped reference measure ∫ φ dS of the owned slave nodes (kernel order), mm."""
        return self._w_c

    @property
    def multiplier_slot(self) -> int:
        """Column of λ_N in the kernel's per-node packing (λ_T follows it)."""
        return self._lam


    # -- outputs ---------------------------------------------------------------------
    def nodal_data(self, problem: Problem | None = None) -> dict[str, npt.NDArray[Any]]:
        """Per owned slave node: X, x, nominal T_N, T_T, pressure −T_N/j, weights (current, ref).

        (``problem`` is not needed; accepted for the interface of the other contacts.)
        """
        k = self._kernel()
        r = k["r"]
        wc = np.where(self._w_c > 0, self._w_c, 1.0)
        il = self._lam
        T_n = r[:, il] * self.rho_n / wc
        T_t = r[:, il + 1:] * self.rho_t / wc[:, None]
        if self._post is None:
            s = self.slave
            j = kin.area_ratio(kin.deformation_gradient(s.u, s.kind), ufl.FacetNormal(s.mesh),
                               s.kind)
            self._post = fem.form(j * ufl.TestFunction(self.Q) * self.dsc,
                                  entity_maps=[self.emap])
        wj = self._lumped(self._post)[self._q]
        j = np.divide(wj, self._w_c, out=np.ones_like(wj), where=self._w_c > 0)
        return {"X": self._X, "x": k["q"][:, 0:self.gdim], "T_n": T_n, "T_t": T_t, "p": -T_n / j,
                "weight": wj, "weight_ref": self._w_c.copy(), "active": T_n < 0}

    def forces(self, problem: Problem | None = None
               ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """Total contact force on the slave and on the master, all ranks.

        N/mm per unit thickness in plane strain; N in 3D, on the modelled parts
        (a quarter model: a quarter of the full bodies' force).
        """
        r = self._kernel()["r"]
        comm = self.slave.mesh.comm
        d = self.gdim
        on_slave = -comm.allreduce(r[:, 0:d].sum(axis=0), op=MPI.SUM)
        on_master = -comm.allreduce(r[:, d:d + d * d].reshape(-1, d, d).sum(axis=(0, 1)),
                                    op=MPI.SUM)
        return on_slave, on_master

    def gather_profile(self, problem: Problem | None = None
                       ) -> dict[str, npt.NDArray[Any]] | None:
        """All nodal data on rank 0 (None elsewhere), sorted by reference X[0]."""
        return gather_nodal(self.slave.mesh.comm, self.nodal_data())
