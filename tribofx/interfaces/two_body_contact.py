"""Contact of two deformable bodies, master–slave closest point (chapter §2, eqs. 1–9), 2D and 3D.

The slave boundary Γ_c of one :class:`tribofx.body.Body` carries the nominal
multipliers λ_N (and λ_T with friction), P1 on its facet submesh, as for
:class:`tribofx.interfaces.Contact`; each slave node is paired with its
closest point on the *current* master boundary of another body (or of another
part of the same body: one mesh with two cell tags works too).  Every residual
evaluation

1. gathers the current master polyline on every rank (a rank's slave nodes may
   project onto master facets of another rank) and refits the C++ box tree;
2. projects the owned slave nodes (:class:`tribofx.two_body.MasterSurface`);
3. evaluates per slave node the Alart–Curnier residual and its exact tangent
   with respect to the slave, the master and the multiplier dofs
   (:func:`tribofx.two_body.node_residuals`, eqs. 2, 4–5, 8), and adds them to
   the rows and columns of the block system (:meth:`Problem.global_rows`);
   the matrix pattern grows by the new slave–master pairs.

The linear part −∫ (1/ρ)λ·δλ dS of the constraint rows is UFL.  Vertex
quadrature (the nodal scheme of the rigid case).  Eulerian slip (steady
sliding, eq. 27): the master's material moves along its own surface, the slip
is −Δτ F⁽²⁾V (:meth:`TwoBodyContact._eulerian_constants`).  Lagrangian slip: the master
material point of the last converged projection is kept (segment and ξ̄), and
the slip is the current projection minus that point's current position, so a
slave node may change master segment between iterations and steps.  A master
held fixed gives exactly the rigid countersurface of the same shape.
Plane strain (master segments) and 3D (master triangles), P1 displacements,
affine meshes.  Units: mm, N, MPa.  Forces are those on the modelled parts: N/mm
per unit thickness in plane strain, N on a 3D model (a quarter model carries a
quarter of the full bodies' force).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import ufl
from dolfinx import fem

from ..forms import contact as cf
from ..problem import BlockTolerance
from ..two_body import node_residuals, num_local
from . import facets, two_body_wear
from .master_side import KernelAssembly, MasterSide, cached_state
from .surface import Surface
from .two_body_outputs import TwoBodyOutputs

if TYPE_CHECKING:
    import numpy.typing as npt
    from dolfinx import mesh as dmesh

    from ..body import Body
    from ..problem import Problem
    from .master_side import KernelCache, RowsCols

__all__ = ["TwoBodyContact"]


class TwoBodyContact(KernelAssembly, TwoBodyOutputs):
    """Frictional contact of ``slave`` on ``slave_boundary`` with ``master`` on ``master_boundary``.

    Args:
        slave, master: :class:`tribofx.body.Body` (plane strain, P1; may be the same).
        slave_boundary, master_boundary: boundary names.
        rho_n: normal augmentation (MPa/mm); rho_t: tangential (default rho_n).
        friction: Coulomb coefficient μ.
        name, rtol: as for :class:`tribofx.interfaces.Contact`.
        slip: "lagrangian" (the slip is the projection's increment since the last
            commit) or "eulerian" (steady sliding, eq. 27: the master's material
            moves with ``V_master`` (mm/s) along its own surface, the slave at
            rest; slip = relative velocity × ``dtau`` (s), see
            :meth:`_eulerian_constants`).
    """

    #: relative hysteresis of the master-segment choice (see :meth:`_pairs`)
    STICKY = 0.05

    #: the master material points of the last commit: global master node keys (n, d)
    #: of each slave node's facet and its coordinates ξ (n,) in 2D, (n, 2) in 3D
    _old: tuple[npt.NDArray[np.int64], npt.NDArray[np.float64]] | None
    _cache: KernelCache | None

    def __init__(self, slave: Body, slave_boundary: str, master: Body, master_boundary: str,
                 rho_n: float, friction: float = 0.0, rho_t: float | None = None,
                 name: str = "contact", rtol: float = 1e-10, slip: str = "lagrangian",
                 V_master: npt.ArrayLike | None = None, dtau: float = 1.0) -> None:
        for b in (slave, master):
            if (b.gdim, b.kind) not in ((2, "plane_strain"), (3, "3d")):
                raise ValueError("TwoBodyContact is implemented for plane strain and 3D")
            if b.gdim != slave.gdim:
                raise ValueError("slave and master must have the same dimension")
            if b.V.ufl_element().embedded_superdegree != 1:
                raise ValueError("TwoBodyContact needs P1 displacements")
        if friction < 0:
            raise ValueError("friction coefficient must be >= 0")
        if slip not in ("lagrangian", "eulerian"):
            raise ValueError(f"unknown slip {slip!r}")
        if slip == "eulerian" and V_master is None:
            raise ValueError("eulerian slip needs V_master, the master's material velocity")
        self.slip_kind, self.dtau = slip, float(dtau)
        self.V_master = None if V_master is None else np.asarray(V_master, float)
        self.slave, self.master, self.name, self.rtol = slave, master, name, rtol
        self.rho_n, self.friction = float(rho_n), float(friction)
        self.rho_t = float(rho_n if rho_t is None else rho_t)
        self.gdim = d = slave.gdim
        # local unknowns: x (d), current facet (d nodes), old facet (d nodes), λ_N, λ_T (d)
        self._lam = d + 2 * d * d
        self.surface = sf = Surface(slave, slave_boundary)
        self.sub, self.emap, self.Q, self.Vs, self.dsc = sf.sub, sf.emap, sf.Q, sf.Vs, sf.dsc
        self.master_boundary = master_boundary
        self.lam_n = fem.Function(self.Q, name=f"{name}_pressure_nominal")
        self.lam_t = (fem.Function(self.Vs, name=f"{name}_friction_traction_nominal")
                      if self.friction > 0 else None)
        # owned slave nodes in λ-dof order: λ dof q ↔ bulk block dof of the same vertex
        own = sf.sub_dofs < sf.n_own
        order = np.argsort(sf.sub_dofs[own])
        self._q = sf.sub_dofs[own][order]
        self._bulk = sf.bulk_dofs[own][order]
        self._X = sf.X_sub[self._q]
        q = ufl.TestFunction(self.Q)
        self._w_c = self._lumped(q * self.dsc)[self._q]
        self._w = self._lumped(q * slave.weight * self.dsc)[self._q]
        # the current master boundary on every rank (oriented facets, search, rows)
        self.side = MasterSide(master, master_boundary)
        self._old = None
        # hysteresis reference of the pairing (segments, facet per slave node): the
        # committed state's, moved on at each accepted Newton iterate (accept_iterate)
        self._facet_committed = None
        self._facet_ref = None
        self._cache = None
        self._post = None

    def _lumped(self, form: fem.Form | ufl.Form) -> npt.NDArray[np.float64]:
        """Assembled (ghost-updated) vector of a linear form on the slave submesh."""
        return self.surface.nodal(form)

    def _pairs(self) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64],
                              npt.NDArray[np.int32], npt.NDArray[np.float64],
                              dict[str, npt.NDArray[Any]]]:
        """Return master data, slave positions and projections (box tree refitted).

        The reference is the pairing of the last accepted Newton iterate (the
        committed one at the start of a solve and after restore()), never that of
        the last evaluation: line-search trials, Taylor perturbations and output
        evaluations do not move it, so the residual is a function of the state and
        of this reference, which the cache key carries.
        """
        xs = self._X + self.slave.u.x.array.reshape(-1, self.gdim)[self._bulk]
        xm, keys, seg, proj = self.side.project(xs, self._facet_ref, self.STICKY)
        return xm, keys, seg, xs, proj

    # -- kernel evaluation -------------------------------------------------------------
    def _state_key(self) -> list[npt.NDArray[Any]]:
        return [self.slave.u.x.array, self.master.u.x.array, self.lam_n.x.array] + \
            ([self.lam_t.x.array] if self.lam_t is not None else []) + \
            (list(self._old) if self._old is not None else []) + \
            (list(self._facet_ref) if self._facet_ref is not None else [])

    def _kernel(self) -> dict[str, Any]:
        """Kernel data of the owned slave nodes at the current state, computed once per state.

        SNES asks for the residual and then the Jacobian at the same iterate, and
        the outputs ask again after the solve: the unknowns and the slip history
        are the key.  The evaluation is collective (the master is gathered), so
        the cache hit is decided on all ranks.  Returns a dict: ``q`` (n, L),
        ``xi_old``, ``r``, ``J``, the pairing (``xm``, ``keys``, ``seg``,
        ``facet``, ``xi``) and ``old_seg`` (master nodes of the committed points).
        """
        if self._old is None:
            self.commit()
        key = self._state_key()
        hit = cached_state(self._cache, key, self.slave.mesh.comm)
        if hit is not None:
            return hit
        xm, keys, seg, xs, proj = self._pairs()
        f, d, il = proj["facet"], self.gdim, self._lam
        if self.slip_kind == "eulerian":     # no history: the old-facet slots repeat the facet
            old_seg, xi_old = seg[f], self._eulerian_constants(keys, seg, f)
        else:
            assert self._old is not None    # made by commit() above
            old_seg, xi_old = np.searchsorted(keys, self._old[0]), self._old[1]
        n = len(self._q)
        qv = np.zeros((n, num_local(d)))
        qv[:, 0:d] = xs
        for k in range(d):
            qv[:, d * (1 + k):d * (2 + k)] = xm[seg[f, k]]
            qv[:, d * (1 + d + k):d * (2 + d + k)] = xm[old_seg[:, k]]
        qv[:, il] = self.lam_n.x.array[self._q]
        if self.lam_t is not None:
            qv[:, il + 1:] = self.lam_t.x.array.reshape(-1, d)[self._q]
        r, J = node_residuals(qv, xi_old, self._w, self._w_c, self.rho_n, self.rho_t,
                              self.friction, eulerian=self.slip_kind == "eulerian")
        data = {"q": qv, "xi_old": xi_old, "r": r, "J": J, "xm": xm, "keys": keys,
                "seg": seg, "facet": f, "xi": proj["xi"], "old_seg": old_seg, "rows": {}}
        self._cache = ([a.copy() for a in key], data)
        return data

    def _eulerian_constants(self, keys: npt.NDArray[np.int64], seg: npt.NDArray[np.int32],
                            f: npt.NDArray[np.int32]) -> npt.NDArray[np.float64]:
        """Per slave node the constants c of the Eulerian slip (eq. 27) on its master facet.

        The master's material moves with ``V_master`` along its own reference surface
        (a disc or a belt in an Eulerian frame, the slave at rest):
        :func:`tribofx.interfaces.facets.eulerian_slip_constants` of the reference facets.
        """
        Xref = self.side.reference(keys)
        assert self.V_master is not None    # eulerian slip needs it (__init__)
        return facets.eulerian_slip_constants(Xref[seg[f]], self.V_master, self.dtau)

    def _rows(self, problem: Problem, k: dict[str, Any]) -> RowsCols:
        """Global rows and columns (n, L) of the local unknowns of ``k`` in ``problem``."""
        if id(problem) in k["rows"]:
            return k["rows"][id(problem)]
        d, il = self.gdim, self._lam
        rm, cm = self.side.rows(problem)
        seg, f, old_seg = k["seg"], k["facet"], k["old_seg"]
        n, L = len(self._q), num_local(d)
        srow, scol = problem.global_rows(self.slave.u)
        nrow, ncol = problem.global_rows(self.lam_n)
        rows = np.full((n, L), -1, dtype=np.int64)
        cols = np.full((n, L), -1, dtype=np.int64)
        bd = d * self._bulk[:, None] + np.arange(d)
        rows[:, 0:d], cols[:, 0:d] = srow[bd], scol[bd]
        for k_ in range(d):
            for j, nodes in ((d * (1 + k_), seg[f, k_]), (d * (1 + d + k_), old_seg[:, k_])):
                rows[:, j:j + d], cols[:, j:j + d] = rm[nodes], cm[nodes]
        rows[:, il], cols[:, il] = nrow[self._q], ncol[self._q]
        if self.lam_t is not None:
            trow, tcol = problem.global_rows(self.lam_t)
            td = d * self._q[:, None] + np.arange(d)
            rows[:, il + 1:], cols[:, il + 1:] = trow[td], tcol[td]
        k["rows"][id(problem)] = (rows, cols)
        return rows, cols

    # -- component protocol --------------------------------------------------------------
    def unknowns(self) -> list[fem.Function]:
        """λ_N (and λ_T)."""
        return [self.lam_n] + ([self.lam_t] if self.lam_t is not None else [])

    def contributions(self) -> list[tuple[fem.Function, ufl.Form]]:
        """Return the linear part −∫(1/ρ) λ·δλ dS of the constraint rows (rest: kernel)."""
        # ρ as Constants: a run at another ρ reuses the compiled kernels
        rho_n, rho_t = (fem.Constant(self.slave.mesh, r) for r in (self.rho_n, self.rho_t))
        out = [(self.lam_n, cf.multiplier_regularisation(
            self.lam_n, ufl.TestFunction(self.Q), rho_n, self.dsc))]
        if self.lam_t is not None:
            out.append((self.lam_t, cf.multiplier_regularisation(
                self.lam_t, ufl.TestFunction(self.Vs), rho_t, self.dsc)))
        return out

    def bcs(self) -> list[fem.DirichletBC]:
        """Return no conditions."""
        return []

    def bcs_by_unknown(self) -> dict[fem.Function, list[fem.DirichletBC]]:
        """Return no conditions."""
        return {}

    def entity_maps(self) -> list[dmesh.EntityMap]:
        """Return the submesh ↔ slave entity map."""
        return [self.emap]

    def refresh(self) -> None:
        """Nothing to refresh: the kernel runs inside the assembly (it needs the layout)."""

    def tolerances(self) -> dict[fem.Function, BlockTolerance]:
        """Constraint rows over their lumped measure: a gap ≤ rtol·G/ρ_N mm (as Contact)."""
        G = min(self.slave.stiffness, self.master.stiffness)
        atol = max(self.rtol * G / self.rho_n,
                   100 * np.finfo(float).eps * self.slave.length)
        out = {self.lam_n: BlockTolerance(atol, "mm", ufl.TestFunction(self.Q) * self.dsc)}
        if self.lam_t is not None:
            ones = ufl.as_vector([1.0] * self.gdim)
            out[self.lam_t] = BlockTolerance(
                atol, "mm", ufl.dot(ufl.TestFunction(self.Vs), ones) * self.dsc)
        return out

    def state_fields(self) -> list[fem.Function]:
        """Return the multipliers (the slip history is committed data)."""
        return self.unknowns()

    def commit(self) -> None:
        """Accept the converged step: the master material points of the projections.

        The pairing is that of the converged state's kernel evaluation (not a new
        search), so the committed state carries the tractions it was solved with.
        """
        if self._old is None:
            _, keys, seg, _, p = self._pairs()
            self._old = (keys[seg[p["facet"]]], p["xi"].copy())
            self._facet_committed = self._facet_ref = (seg.copy(), p["facet"].copy())
            return
        k = self._kernel()
        self._facet_committed = self._facet_ref = (k["seg"].copy(), k["facet"].copy())
        d = self.gdim
        # the kernel's own (unclamped) coordinates: the material point is x̄ itself, so
        # the slip restarts from zero also for a node slightly off its facet
        xi, _, _ = facets.plane_coordinates(k["q"][:, :d], k["q"][:, d:d + d * d].reshape(-1, d, d))
        self._old = (k["keys"][k["seg"][k["facet"]]], xi[:, 0] if d == 2 else xi)

    def _kernel_ready(self) -> bool:
        """Whether the slip history exists (the kernel needs the committed points)."""
        return self._old is not None

    # -- wear of both surfaces (eqs. 17-18) --------------------------------------------
    def dissipation_increment(self) -> npt.NDArray[np.float64]:
        """Frictional dissipation per unit reference slave area since the last commit (N/mm).

        See :func:`tribofx.interfaces.two_body_wear.dissipation_increment`.
        """
        return two_body_wear.dissipation_increment(self)

    def master_transfer(
            self, volume: npt.NDArray[np.float64]
    ) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.float64]]:
        """Per-slave-node volumes onto the master nodes (eq. 18); see :mod:`.two_body_wear`."""
        return two_body_wear.master_transfer(self, volume)

    def wear_surface(self, side: str) -> two_body_wear.WearSurface:
        """Return the ``"slave"`` or ``"master"`` side for a :class:`~tribofx.interfaces.Wear`."""
        if side not in ("slave", "master"):
            raise ValueError(f"side {side!r}: 'slave' or 'master'")
        if self.lam_t is None:
            raise ValueError("wear of a two-body contact is driven by the frictional "
                             "dissipation (eqs. 17-18): friction > 0 needed")
        return two_body_wear.WearSurface(self, side)
