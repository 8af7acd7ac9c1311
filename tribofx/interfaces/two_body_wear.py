"""Wear of both surfaces of a two-body contact (chapter §3, eqs. 17–18).

* :func:`dissipation_increment` — the slave's frictional dissipation since the
  last commit, per unit reference slave area (eq. 17);
* :func:`master_transfer` — per-slave-node volumes carried to the master nodes
  of their projections (eq. 18 in the lumped nodal scheme);
* :class:`WearSurface` — either side of a :class:`TwoBodyContact` as the home
  of a :class:`tribofx.interfaces.Wear` (``contact.wear_surface(side)``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from ..forms import wear as wf
from . import facets
from .surface import Surface

if TYPE_CHECKING:
    import numpy.typing as npt

    from .two_body_contact import TwoBodyContact

__all__ = ["WearSurface", "dissipation_increment", "master_transfer"]


def dissipation_increment(contact: TwoBodyContact) -> npt.NDArray[np.float64]:
    """Frictional dissipation per unit reference slave area since the last commit (N/mm).

    ΔD⁽¹⁾ = T_T·Δs_T per owned slave node (λ-dof order): T_T the nominal
    friction traction of the Alart–Curnier law, Δs_T the tangential part of
    the slip x̄ − z (the current projection minus the current position of the
    master material point of the last converged projection).  It is the
    increment of eq. (17), Ḋ⁽¹⁾ = T_T·ξ̄̇ over the step; ≥ 0 (T_T is parallel
    to the slip in sliding and the slip vanishes in stick).
    """
    if contact.lam_t is None:
        raise ValueError("wear by frictional dissipation needs friction > 0")
    k = contact.kernel_data()
    q, r = k["q"], k["r"]
    d, il = contact.gdim, contact.multiplier_slot
    x = q[:, 0:d]
    facet = q[:, d:d + d * d].reshape(-1, d, d)
    old = q[:, d + d * d:il].reshape(-1, d, d)
    n = facets.normals(facet)
    if contact.slip_kind == "eulerian":                      # s = c^a t_a
        c = np.asarray(k["xi_old"]).reshape(len(q), d - 1)
        s = np.einsum("na,nad->nd", c, facet[:, 1:] - facet[:, :1])
    else:
        xi, _, _ = facets.plane_coordinates(x, facet)
        xbar = np.einsum("nk,nkd->nd", facets.shape_values(xi), facet)
        z = np.einsum("nk,nkd->nd", facets.shape_values(k["xi_old"]), old)
        s = xbar - z
    s_t = s - np.sum(s * n, axis=1)[:, None] * n
    wc = np.where(contact.constraint_weights > 0, contact.constraint_weights, 1.0)
    T_t = r[:, il + 1:] * contact.rho_t / wc[:, None]
    return np.sum(T_t * s_t, axis=1)


def master_transfer(
        contact: TwoBodyContact, volume: npt.NDArray[np.float64]
) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.float64]]:
    """Distribute per-slave-node volumes onto the master nodes of their projections.

    ``volume`` (n_owned_slave,) is split between the d nodes of the current
    master facet of each slave node with the weights N_i(ξ) (2D: 1 − ξ, ξ) and
    summed over all ranks; returns (global master node keys, volumes) on every rank.
    This is eq. (18) in the lumped nodal scheme: Ẇ⁽²⁾ dS⁽²⁾ = (j⁽²⁾/j⁽¹⁾) K⁽²⁾
    Ḋ⁽¹⁾ dS⁽²⁾ = K⁽²⁾ Ḋ⁽¹⁾ dS⁽¹⁾ (ds = j dS on both sides), so a slave node
    passes its volume K⁽²⁾ ΔD⁽¹⁾ w_c to the master surface element it faces.
    """
    k = contact.kernel_data()
    out = np.zeros(len(k["keys"]))
    seg, f = k["seg"], k["facet"]
    N = facets.shape_values(k["xi"])
    for j in range(contact.gdim):
        np.add.at(out, seg[f, j], N[:, j] * volume)
    contact.slave.mesh.comm.Allreduce(MPI.IN_PLACE, out, op=MPI.SUM)
    return k["keys"], out


class WearSurface:
    """One side of a :class:`TwoBodyContact` as the home of a :class:`tribofx.interfaces.Wear`.

    It carries the :class:`tribofx.interfaces.surface.Surface` attributes of its
    boundary (on the slave: the contact's own) and answers
    :meth:`wear_increment`: the nominal wear increment per unit reference area
    of its own surface over the last fast sub-step, eq. (17) on the slave,
    eq. (18) on the master (see :meth:`TwoBodyContact.master_transfer`).
    """

    def __init__(self, contact: TwoBodyContact, side: str) -> None:
        self.contact, self.side = contact, side
        body = contact.slave if side == "slave" else contact.master
        sf = contact.surface if side == "slave" else Surface(body, contact.master_boundary)
        self.surface, self.body = sf, body
        self.sub, self.emap, self.Q, self.Vs, self.dsc = sf.sub, sf.emap, sf.Q, sf.Vs, sf.dsc
        self.sub_dofs, self.bulk_dofs, self.X_sub = sf.sub_dofs, sf.bulk_dofs, sf.X_sub
        self.lam_t, self.friction = contact.lam_t, contact.friction
        self.slip_kind = contact.slip_kind
        self._inc: fem.Function = fem.Function(self.Q)
        if side == "master":
            im = body.V.dofmap.index_map
            key = np.zeros(len(self._inc.x.array), dtype=np.int64)
            key[sf.sub_dofs] = im.local_to_global(sf.bulk_dofs.astype(np.int32))
            self._key = key
            self._weight = sf.nodal(ufl.TestFunction(self.Q) * self.dsc)

    def nodal(self, form: fem.Form | ufl.Form) -> npt.NDArray[np.float64]:
        """Assembled (ghost-updated) vector of a linear form on this surface's dofs."""
        return self.surface.nodal(form)

    def wear_increment(self, K: float) -> npt.NDArray[np.float64]:
        """ΔW per unit reference area of this surface, all local dofs (mm), coefficient K.

        Slave: K ΔD⁽¹⁾ (eq. 17).  Master: the volumes K ΔD⁽¹⁾ w_c of the slave
        nodes transferred to the master nodes (eq. 18) over the lumped master
        weights.
        """
        dD = self.contact.dissipation_increment()
        inc = self._inc.x.array
        if self.side == "slave":
            inc[:] = 0.0
            inc[self.contact.slave_dofs] = wf.archard_nominal(K, dD)      # eq. (17)
            self._inc.x.scatter_forward()
            return inc.copy()
        keys, vol = self.contact.master_transfer(
            wf.archard_nominal(K, dD) * self.contact.constraint_weights)
        pos = np.searchsorted(keys, self._key)
        if len(keys) and not np.array_equal(keys[np.minimum(pos, len(keys) - 1)], self._key):
            raise RuntimeError("master surface nodes missing from the gathered polyline")
        return np.divide(vol[pos], self._weight, out=np.zeros_like(self._weight),
                         where=self._weight > 0)

    def nodal_data(self) -> dict[str, npt.NDArray[np.float64]]:
        """Per owned node: reference X and current x = X + u (mm)."""
        n = self.surface.n_own
        u = self.body.u.x.array.reshape(-1, self.body.gdim)
        x = self.X_sub.copy()
        x[self.sub_dofs] += u[self.bulk_dofs]
        return {"X": self.X_sub[:n], "x": x[:n]}
