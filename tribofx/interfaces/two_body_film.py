"""A lubricating film between two deformable bodies (plane strain, axisymmetric, 3D): §6–7.

The chapter restricts soft-EHL to one rigid body and calls two deformable bodies
"a challenging task for future work".  :class:`TwoBodyFilm` is the
:class:`tribofx.interfaces.Film` on the slave's lubricated boundary Γ_l with
the other body (the master) in place of a rigid countersurface:

* the lubrication surface is the slave's current boundary, S = γ_l
  (:func:`tribofx.forms.two_body_film.layer_surface_kinematics`; the derivation
  and why this surface are in ``docs/films.md``, "A film between two
  deformable bodies");
* each node of Γ_l is projected onto the master's *current* boundary
  (:class:`tribofx.interfaces.master_side.MasterSide`: gathered on every rank, the
  C++ box tree refitted every evaluation); the gap h and the master's surface
  velocity w at the projection are nodal unknowns of the film, equal to their
  kernel values node by node;
* the fluid traction (46) is collocated at the nodes (unknown t) and carried by
  the kernel to the slave (−w_k t_k) and to the master at the projection
  (w_k N_m(ξ̄_k) t_k): action equals reaction exactly;
* the Reynolds rows (49)/(57) with SUPG, penalty or JFO cavitation, and the
  stopping test, are the film's own.

The exact Jacobian: UFL differentiates the Reynolds, trace, gradient and
collocation rows with respect to u_s, p, g, λ, h, w, t and the bulk u; the
C++ kernel (:func:`tribofx.two_body.film_node_residuals`, exact dual-number
tangent) supplies the slave and master columns of the gap, velocity and
traction rows, inserted like the two-body contact's (:mod:`tribofx.pattern`).

The bodies' materials move through their meshes (Eulerian rolling or sliding):
``motion1``/``motion2`` (:mod:`tribofx.motions`) with speeds ``U1``/``U2`` (mm/s,
Constants a continuation may drive).  Plane strain, axisymmetric or 3D, P1
displacements, affine meshes; in 3D the master's facets are triangles (the
kernel's ``film_node_residual_3d``).  Axisymmetric: both bodies are meridian sections
(r, z), the search and the kernel the plane ones in that plane; the Reynolds
rows carry the film's 2πr (as :class:`Film`'s), and the nodal unknown t is the
ring traction: W_k t_k, with W_k = ∫ φ_k 2πR dS the exact lumped area, is the
lumped ring force ∫ φ_k 2πr T dS on the current radius
(:meth:`TwoBodyFilm._collocation`), which the kernel puts on the slave and, at
the projections, on the master.
Units: mm, N, s, MPa; forces per unit thickness (N/mm), of the revolved bodies
(N) when axisymmetric.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Self, cast

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from ..forms import two_body_film as tbf
from ..problem import BlockTolerance, Problem
from ..scheme import BDF2
from ..two_body import film_node_residuals, num_data_film, num_local_film
from .film import Film
from .film_options import FilmScales
from .master_side import KernelAssembly, MasterSide, cached_state
from .prescribed_pressure import BoundaryPressure

if TYPE_CHECKING:
    from collections.abc import Callable

    import numpy.typing as npt
    import ufl.core.expr

    from ..body import Body
    from ..forms.ehl import LubricationKinematics
    from ..motions import Rolling, Sliding
    from ..protocols import Counterpart
    from ..reports import NewtonReport
    from ..scheme import Scheme
    from .film import Shape
    from .film_options import Fluid
    from .master_side import KernelCache, RowsCols

__all__ = ["TwoBodyFilm"]


class _NoCounterpart:
    """The film's counterpart slot: the master enters through the kernel, not a geometry."""

    def update(self, x_nodes: npt.NDArray[np.float64]) -> None:
        """Nothing to project here: the kernel runs inside the assembly."""

    def unknowns(self) -> list[fem.Function]:
        """Return no unknowns."""
        return []

    def state_fields(self) -> list[fem.Function | fem.Constant]:
        """Return no state."""
        return []

    def commit(self) -> None:
        """Nothing to accept."""


class TwoBodyFilm(KernelAssembly, Film):
    """Soft-EHL film on ``boundary`` of ``slave`` against ``master_boundary`` of ``master``.

    Args:
        slave, master: plane-strain, axisymmetric or 3D P1 :class:`tribofx.body.Body`
            (affine meshes, both of one kind).
        boundary, master_boundary: boundary names; the master's must extend beyond
            the projections of Γ_l.
        fluid: the lubricant, a :class:`~tribofx.interfaces.film_options.Fluid` (as for
            :class:`Film`).
        motion1, motion2: None (at rest) or the shape of the reference velocity of
            the slave's and the master's material (:class:`tribofx.motions.Rolling`,
            :class:`~tribofx.motions.Sliding`).
        U1, U2: their speeds (mm/s); ``self.U1``/``self.U2`` are the Constants.
        **kwargs: the :class:`Film` options (scales, cavitation, quadrature,
            shear, supg, row_scaling, name, rtol, require_open); model is
            "finite", S = γ_l.
    """

    #: relative hysteresis of the master-segment choice (as for TwoBodyContact)
    STICKY = 0.05

    master: Body
    gap: fem.Function          # the nodal gap h (None only until Film.__init__ builds the rows)
    v_master: fem.Function     # the master's surface velocity w at the projection
    t_nodal: fem.Function      # the nodal fluid traction t
    _master_hist: list[fem.Function]   # a transient film's master displacements at t_n, t_{n−1}
    _cache: KernelCache | None

    def __init__(self, slave: Body, boundary: str, master: Body, master_boundary: str,
                 fluid: Fluid, motion1: Rolling | Sliding | None = None, U1: float = 0.0,
                 motion2: Rolling | Sliding | None = None, U2: float = 0.0,
                 **kwargs: Any) -> None:
        for b in (slave, master):
            if (b.kind not in ("plane_strain", "axisymmetric", "3d")
                    or b.V.ufl_element().embedded_superdegree != 1):
                raise ValueError("TwoBodyFilm is implemented for plane-strain, axisymmetric "
                                 "and 3D P1 bodies")
        if slave.kind != master.kind:
            raise ValueError(f"TwoBodyFilm: a {slave.kind} slave needs a {slave.kind} master, "
                             f"not a {master.kind} one")
        for key in ("V_counter", "model", "alpha", "motion"):
            if key in kwargs:
                raise ValueError(f"TwoBodyFilm has no option {key!r} (S = γ_l, finite model)")
        self.master, self._motion1, self._motion2 = master, motion1, motion2
        self.U1 = fem.Constant(slave.mesh, float(U1))
        self.U2 = fem.Constant(slave.mesh, float(U2))
        self.gap = cast("fem.Function", None)     # built by _kinematics, in Film.__init__
        # the master enters through the kernel (_kinematics asks no counterpart's geometry)
        super().__init__(slave, boundary, lambda V1: cast("Counterpart", _NoCounterpart()), fluid,
                         motion=None if motion1 is None else (motion1, self.U1), **kwargs)
        self.side = MasterSide(master, master_boundary)
        self._master_boundary = master_boundary
        self._master_dry: tuple[BoundaryPressure, Problem] | None = None
        sf, sub = self._surface, self.sub
        self._c_w = fem.Constant(sub, self.mu / self.h_ref if kwargs.get("row_scaling", True)
                                 else 1.0)
        own = sf.sub_dofs < sf.n_own
        order = np.argsort(sf.sub_dofs[own])
        self._q, self._bulk = sf.sub_dofs[own][order], sf.bulk_dofs[own][order]
        self._Xk = sf.X_sub[self._q]
        # the nodes' lumped reference measures (axisymmetric: areas ∫ φ_k 2πR dS, ω of Surface)
        lumped = ufl.TestFunction(sf.Q) * (sf.weight if self.axisymmetric else 1) * sf.dsc
        self._w = sf.nodal(lumped)[self._q]
        self._w_c = sf.nodal(fem.form(ufl.TestFunction(self.gap.function_space)
                                      * self.nodal_dx))[self._q]
        self._facet_ref = self._facet_committed = None
        self._cache = None
        self.set_nodal_data()

    @property
    def axisymmetric(self) -> bool:
        """Whether the bodies are axisymmetric (meridian plane (r, z); forces are ring totals)."""
        return self.body.kind == "axisymmetric"

    def _derived_scales(self, V_body: Shape | None, V_counter: Shape | None) -> FilmScales:
        """Return the scales of :meth:`Film._derived_scales` for two moving bodies.

        The mean speed (|U1| + |U2|)/2 of the two surfaces and the composite modulus
        2/(1/E'₁ + 1/E'₂) of the two bodies.
        """
        U = 0.5 * (abs(float(self.U1.value)) + abs(float(self.U2.value)))
        E1, E2 = 4 * self.body.stiffness, 4 * self.master.stiffness
        return FilmScales.soft_ehl(self.mu, U, 0.5 * self.length, 2 / (1 / E1 + 1 / E2))

    def _kinematics(self, X: ufl.core.expr.Expr, disp: ufl.core.expr.Expr,
                    grad_disp: ufl.core.expr.Expr, N: ufl.core.expr.Expr, V_body: Shape | None,
                    V_counter: Shape | None) -> LubricationKinematics:
        """S = γ_l with the film's nodal gap and master velocity (bulk side or submesh)."""
        if self.gap is None:
            gdim = self.body.gdim
            self.gap = fem.Function(fem.functionspace(self.sub, ("Lagrange", 1)),
                                       name=f"{self.name}_gap")
            vec = ("Lagrange", 1, (gdim,))
            self.v_master = fem.Function(fem.functionspace(self.sub, vec),
                                       name=f"{self.name}_counter_velocity")
            self.t_nodal = fem.Function(fem.functionspace(self.sub, vec),
                                       name=f"{self.name}_traction_nominal")
        V = None if V_body is None else V_body(X)
        return tbf.layer_surface_kinematics(X, disp, grad_disp, N, self.gap, V, self.v_master)

    # -- time: the master's nodes move too ------------------------------------------------
    def transient(self, scheme: Scheme | str = BDF2, lumped: bool = False) -> Self:
        """Make the film transient (:meth:`Film.transient`); the master's history is kept too.

        The master's surface velocity at the projection gains its nodes' rates,
        ẋ_k = (c₀ (u_k − u_kⁿ) + c₁ (u_kⁿ − u_kⁿ⁻¹))/Δt, through the kernel's data
        k₀ = c₀/Δt, z_k = −k₀ (X_k + u_kⁿ) + (c₁/Δt)(u_kⁿ − u_kⁿ⁻¹).
        """
        super().transient(scheme, lumped)
        self._master_hist = [fem.Function(self.master.V, name=f"{self.name}_master_u_{k}")
                             for k in ("n", "nm1")]
        return self

    def history_fields(self) -> list[fem.Function | fem.Constant]:
        """Return the film's histories and the master's displacements at t_n, t_{n−1}."""
        return super().history_fields() + (self._master_hist if self.history is not None
                                           else [])

    def begin_step(self, dt: float) -> None:
        """Start a step (:meth:`Film.begin_step`) and move the master's history on."""
        super().begin_step(dt)
        m_n, m_nm1 = self._master_hist
        m_nm1.x.array[:] = m_n.x.array
        m_n.x.array[:] = self.master.u.x.array
        self._cache = None

    def _master_rates(self, keys: npt.NDArray[np.int64]
                      ) -> tuple[float, npt.NDArray[np.float64]]:
        """Per gathered master node: k₀ (1/s) and z (mm/s) of ẋ = k₀ x + z (0, 0 when steady)."""
        d = self.body.gdim
        if self.history is None:
            return 0.0, np.zeros((len(keys), d))
        inv_dt, c0, c1 = (float(c.value) for c in self.history.weights)
        # (the cast: mypy infers no lambda with a default argument against a context)
        u_n, u_nm1 = (self.side.gather(cast("Callable[[npt.NDArray[np.int64]], npt.NDArray[Any]]",
                                            lambda nd, f=f: f.x.array.reshape(-1, d)[nd]))[1]
                      for f in self._master_hist)
        k0 = inv_dt * c0
        return k0, -k0 * (self.side.reference(keys) + u_n) + inv_dt * c1 * (u_n - u_nm1)

    # -- kernel ----------------------------------------------------------------------------
    def _state_key(self) -> list[npt.NDArray[Any]]:
        fields = (self.body.u, self.master.u, self.gap, self.v_master, self.t_nodal)
        ref = list(self._facet_ref) if self._facet_ref is not None else []
        hist = []
        if self.history is not None:      # the master's rates: its history and the weights
            hist = [f.x.array for f in self._master_hist] + [
                np.array([float(c.value) for c in self.history.weights])]
        return [f.x.array for f in fields] + [np.array([float(self.U2.value)])] + ref + hist

    def _kernel(self) -> dict[str, Any]:
        """Kernel data of the owned nodes of Γ_l at the current state (cached per state).

        Returns a dict: ``q`` (n, 11), ``data`` (n, 7) (3D: (n, 19), (n, 16)), ``r``,
        ``J``, the pairing
        (``xm``, ``keys``, ``seg``, ``facet``, ``xi``) and ``rows`` (per problem).
        """
        key = self._state_key()
        hit = cached_state(self._cache, key, self.body.mesh.comm)
        if hit is not None:
            return hit
        d = self.body.gdim
        xs = self._Xk + self.body.u.x.array.reshape(-1, d)[self._bulk]
        xm, keys, seg, proj = self.side.project(xs, self._facet_ref, self.STICKY)
        f = proj["facet"]
        h_at = d + d * d                  # [x, the facet's d nodes, h, w, t]
        q = np.zeros((len(self._q), num_local_film(d)))
        q[:, 0:d] = xs
        for j in range(d):
            q[:, d + d * j:2 * d + d * j] = xm[seg[f, j]]
        q[:, h_at] = self.gap.x.array[self._q]
        q[:, h_at + 1:h_at + 1 + d] = self.v_master.x.array.reshape(-1, d)[self._q]
        q[:, h_at + 1 + d:] = self.t_nodal.x.array.reshape(-1, d)[self._q]
        data = np.zeros((len(self._q), num_data_film(d)))
        nc = d * (d - 1)                  # [c (d nodes × (d − 1)), k₀, z (d nodes × d)]
        if self._motion2 is not None:
            data[:, :nc] = self._tangential_speeds(self.side.reference(keys)[seg[f]])
        k0, z = self._master_rates(keys)
        data[:, nc] = k0
        for j in range(d):
            data[:, nc + 1 + d * j:nc + 1 + d * (j + 1)] = z[seg[f, j]]
        r, J = film_node_residuals(q, data, self._w, self._w_c, float(self.trace_scale.value),
                                   float(self._c_w.value))
        k = {"q": q, "data": data, "r": r, "J": J, "xm": xm, "keys": keys, "seg": seg,
             "facet": f, "xi": proj["xi"], "rows": {}}
        self._cache = ([a.copy() for a in key], k)
        return k

    def _tangential_speeds(self, X: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """Return the master's motion at the facet nodes X (n, d, d) in the facet's basis.

        2D: c_k = U₂ V(X_k)·T/|T|² (T = X₂ − X₁); 3D: c_k^a = U₂ M⁻¹[V(X_k)·T_b]
        (T_b = X_{b+1} − X₁, M = [T_a·T_b]); (n, d (d − 1)), node by node.
        """
        assert self._motion2 is not None
        U2, d = float(self.U2.value), self.body.gdim
        if d == 2:
            A, B = X[:, 0], X[:, 1]
            T = B - A
            T2 = np.sum(T * T, axis=1)
            return np.stack([U2 * np.sum(self._motion2(A) * T, axis=1) / T2,
                             U2 * np.sum(self._motion2(B) * T, axis=1) / T2], axis=1)
        T = np.stack([X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]], axis=1)     # (n, 2, 3)
        M = np.einsum("nai,nbi->nab", T, T)
        out = [np.linalg.solve(M, U2 * np.einsum("nbi,ni->nb", T, self._motion2(X[:, j]))
                               [..., None])[..., 0] for j in range(3)]
        return np.concatenate(out, axis=1)

    def set_nodal_data(self) -> None:
        """Set h and w to their kernel values at the current state (a start or a restart)."""
        k = self._kernel()
        d = self.body.gdim
        h_at = d + d * d
        self.gap.x.array[self._q] = -k["r"][:, h_at] / (float(self.trace_scale.value)
                                                         * self._w_c)
        w = self.v_master.x.array.reshape(-1, d)
        w[self._q] = -k["r"][:, h_at + 1:h_at + 1 + d] / (float(self._c_w.value)
                                                           * self._w_c[:, None])
        for f in (self.gap, self.v_master):
            f.x.scatter_forward()

    def _rows(self, problem: Problem, k: dict[str, Any]) -> RowsCols:
        """Global rows and columns (n, 11; 3D (n, 19)) of the local unknowns of ``k``."""
        if id(problem) in k["rows"]:
            return k["rows"][id(problem)]
        d = self.body.gdim
        rm, cm = self.side.rows(problem)
        seg, f = k["seg"], k["facet"]
        h_at = d + d * d
        rows = np.full((len(self._q), num_local_film(d)), -1, dtype=np.int64)
        cols = np.full_like(rows, -1)
        comp = np.arange(d)
        slots = ((0, self.body.u, d * self._bulk[:, None] + comp),
                 (h_at, self.gap, self._q[:, None]),
                 (h_at + 1, self.v_master, d * self._q[:, None] + comp),
                 (h_at + 1 + d, self.t_nodal, d * self._q[:, None] + comp))
        for j, fun, idx in slots:
            gr, gc = problem.global_rows(fun)
            rows[:, j:j + idx.shape[1]], cols[:, j:j + idx.shape[1]] = gr[idx], gc[idx]
        for k_ in range(d):               # the master facet's d nodes
            j = d + d * k_
            rows[:, j:j + d], cols[:, j:j + d] = rm[seg[f, k_]], cm[seg[f, k_]]
        k["rows"][id(problem)] = (rows, cols)
        return rows, cols

    # -- component protocol -------------------------------------------------------------------
    def unknowns(self) -> list[fem.Function]:
        """Return the film's unknowns and its nodal gap, master velocity and traction."""
        return super().unknowns() + [self.gap, self.v_master, self.t_nodal]

    def contributions(self) -> list[tuple[fem.Function, ufl.Form]]:
        """Film rows without the solid's (the kernel carries t to both bodies), nodal rows."""
        out = [c for c in super().contributions() if c[0] is not self.body.u]
        tests = [ufl.TestFunction(f.function_space) for f in (self.gap, self.v_master,
                                                               self.t_nodal)]
        return out + [
            (self.gap, tbf.nodal_equality(self.gap, tests[0], self.trace_scale, self.nodal_dx)),
            (self.v_master, tbf.nodal_equality(self.v_master, tests[1], self._c_w, self.nodal_dx)),
            (self.t_nodal, self._collocation(tests[2]))]

    def _collocation(self, dt: ufl.Argument) -> ufl.Form:
        """Return the rows that make t the nodal traction (plane strain) or ring traction.

        Plane strain: t_k is the traction (46) at node k (the vertex rule);
        axisymmetric: W_k t_k (W_k = ∫ φ_k 2πR dS, the exact lumped area) is the
        lumped ring force of the traction on the current radius r = R + u_r
        (:func:`tribofx.forms.two_body_film.ring_traction_collocation`), the node on
        the axis included.
        """
        sf = self._surface
        if not self.axisymmetric:
            return tbf.traction_collocation(self.t_nodal, self.traction, dt, sf.dsc)
        return tbf.ring_traction_collocation(self.t_nodal, self.traction, dt, sf.weight,
                                             self.body.u[0], sf.dsc)

    def refresh(self) -> None:
        """Copy the velocities to the submesh (the kernel runs inside the assembly)."""
        self._sync()

    def positions(self) -> npt.NDArray[np.float64]:
        """Nodal current positions of Γ_l (P1 dof order, mm)."""
        self._u1.interpolate(self.u_s)
        return self._X1 + self._u1.x.array.reshape(-1, self.body.gdim)

    def tolerances(self) -> dict[fem.Function, BlockTolerance]:
        """Return the film's tolerances and those of the gap, velocity and traction rows."""
        if "h" not in self._tol:
            out = dict(super().tolerances())
            gdim = self.body.gdim
            ones = ufl.as_vector([1.0] * gdim)
            for key, fun, unit, c in (("h", self.gap, "mm", self.trace_scale),
                                      ("w", self.v_master, "mm/s", self._c_w),
                                      ("t", self.t_nodal, "MPa", 1.0)):
                v = ufl.TestFunction(fun.function_space)
                v = v if key == "h" else ufl.dot(v, ones)
                if key == "t" and self.axisymmetric:     # rows of ring forces: ω-weighted
                    v = self._surface.weight * v
                self._tol[key] = BlockTolerance(0.0, unit, c * v * self.nodal_dx)
                out[fun] = self._tol[key]
            self._tol_out = out
            self.set_scales()
        return self._tol_out

    def set_scales(self, p_c: float | None = None, eps: float | None = None,
                   film_scale: float | None = None, speed_scale: float | None = None) -> None:
        """As :meth:`Film.set_scales`; also the nodal rows' tolerances."""
        super().set_scales(p_c, eps, film_scale, speed_scale)
        atol = {"h": self.rtol * self.h_ref, "w": self.rtol * self.U_ref,
                "t": self.rtol * float(self.p_c.value)}
        for key, a in atol.items():
            if key in self._tol:
                self._tol[key].atol = a

    def commit(self) -> None:
        """Accept the converged step: the pairing of the converged state is the reference."""
        k = self._kernel()
        self._facet_committed = self._facet_ref = (k["seg"].copy(), k["facet"].copy())

    # -- a dry start -------------------------------------------------------------------------
    def start_from_pressure(self,
                            pressure: Callable[[npt.NDArray[np.float64]], npt.NDArray[np.float64]],
                            h0: float, at: npt.ArrayLike, verbose: bool = False,
                            support: fem.Constant | None = None) -> NewtonReport:
        """Set an initial state: both bodies under a prescribed pressure, film ``h0`` at ``at``.

        The slave as :meth:`Film.start_from_pressure` (Γ_l under ``pressure``, p set
        to it); the master's lubricated boundary under the same ``pressure`` of its
        reference coordinates, a follower load in its own dry problem
        (:class:`~tribofx.interfaces.prescribed_pressure.BoundaryPressure`; e.g. the
        Hertz pressure about the contact point acts on both surfaces); then the
        master is translated (:meth:`place_master`, with ``support``) so that the gap
        is ``h0`` (mm) at the slave node nearest ``at``.  Returns the slave's report.
        """
        report = self._dry_start(pressure, verbose)
        if self._master_dry is None:
            load = BoundaryPressure(self.master, self._master_boundary)
            self._master_dry = (load, Problem([self.master, load],
                                              name=f"{self.name}_master_dry"))
        load, problem = self._master_dry
        load.p.interpolate(pressure)
        problem.solve(verbose=verbose)
        self.place_master(h0, at, support)
        return report

    def place_master(self, h0: float, at: npt.ArrayLike,
                     support: fem.Constant | None = None) -> None:
        """Translate the master so that the gap is ``h0`` (mm) at the slave node nearest ``at``.

        The master's displacement moves by Δn, n its outward normal at that node's
        projection and Δ = h − h0 (a rigid translation: equilibrium is kept);
        ``support``: the Constant of the Dirichlet condition that holds the master
        (:meth:`tribofx.body.Body.add_dirichlet`), moved with it.  The nodal gap and
        velocity are then set to the kernel's values.
        """
        self._cache = None
        self.set_nodal_data()
        k, d = self._kernel(), self.body.gdim
        d2 = np.sum((self._Xk - np.asarray(at, float)[:d]) ** 2, axis=1)
        loc: tuple[float, Any] = (np.inf, None)
        if len(d2):
            i = int(np.argmin(d2))
            X = k["xm"][k["seg"][k["facet"][i]]]                     # the facet's nodes
            if d == 2:
                tau = X[1] - X[0]
                n = np.array([tau[1], -tau[0]])
            else:
                n = np.cross(X[1] - X[0], X[2] - X[0])
            loc = (float(d2[i]), (float(self.gap.x.array[self._q[i]]), n / np.linalg.norm(n)))
        _, (h, n) = min(self.body.mesh.comm.allgather(loc), key=lambda t: t[0])
        shift = (h - h0) * n
        self.master.u.x.array.reshape(-1, d)[:] += shift
        if support is not None:
            support.value[:] += shift
        self._cache = None
        self.set_nodal_data()

    # -- outputs ---------------------------------------------------------------------------
    def forces(self) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """Film force on the slave and on the master, all ranks: equal and opposite.

        N/mm per unit thickness (plane strain); N of the revolved bodies (axisymmetric).
        """
        r = self._kernel()["r"]
        comm, d = self.body.mesh.comm, self.body.gdim
        on_slave = -comm.allreduce(r[:, 0:d].sum(axis=0), op=MPI.SUM)
        on_master = -comm.allreduce(sum(r[:, d + d * j:2 * d + d * j] for j in range(d))
                                    .sum(axis=0), op=MPI.SUM)
        return on_slave, on_master

    def force(self) -> npt.NDArray[np.float64]:
        """Film force on the slave (N/mm; axisymmetric: N), the nodal tractions' sum."""
        return self.forces()[0]
