"""Finite wear of a hyperelastic body on a rigid countersurface: θ-scheme in slow time (§4.4).

Everything lives on the initial mesh (DESIGN.md, "Working on the initial
mesh"): the displacement u from the initial configuration (x = X̂ + u), the
shape change w of the worn configuration (X = X̂ + w, the ALE field of Ψ), the
normal contact multiplier λ (traction per unit initial area, on the contact
facet submesh) and the multiplier ζ of the shape update (same submesh).

Residuals (forms from :mod:`tribofx.forms.ale`, :mod:`tribofx.forms.wear`,
:mod:`tribofx.forms.contact`):

* deformation on the worn body, pulled back to Ω̂:
  ∫ P(F) : (Grad δu G⁻¹) det G dV̂ − ∫ T*·δu j_w dŜ + G_c(u, λ) = 0,
  F = (I + Grad u) G⁻¹, G = I + Grad w;
* auxiliary elasticity for w with the discrete shape evolution law (28) as a
  nodal constraint on Γ̂_c (vertex quadrature, multiplier ζ):
  ∫ σ_aux(w) : ε(δw) dV̂ + ∫_Γ̂c ζ δw·a dŜ = 0,
  ∫_Γ̂c η [(w − w_n)·a + Δt k V |λ_{n+θ}|] dŜ = 0,
  with zero normal motion of the rest of the boundary as Dirichlet conditions.

The normal of (28) is taken as the step average of the Nanson vector,
a = ∫₀¹ cof(G(s)) N̂ ds along the linear path from w_n to w (2D: cof(G_{n+½}) N̂
of the mid-step shape; 3D: Simpson's rule, exact for the quadratic cofactor;
:func:`tribofx.forms.ale.swept_nanson_vector`).  This differs from N_{n+θ} by
O(Δt) per step (the first-order accuracy of the θ-scheme is unchanged), and it
makes (w − w_n)·a dŜ the exact volume (2D: area) swept by a linear boundary
facet, so the discrete worn volume equals the time integral of the wear rate
exactly (a discrete geometric conservation law).  k V |λ| = Ẇ j_w is the nominal Archard
rate (14) per unit initial area (frictionless pressure form, slip speed V);
options: the spatial law (15)–(16), k V |λ| / J with J = det F relative to the
worn configuration, and a depth-graded coefficient k(d), d = −w·N̂ (both taken
at t_{n+θ}).

Friction (chapter eqs. 13–14): with a Coulomb coefficient μ > 0 the contact
carries a friction multiplier λ_T and the rate is the dissipation form
Ẇ j_w = K T_T·v_T, K = k/μ (T_T per unit initial area), which equals k |λ| ‖v_T‖
in sliding.  Steady sliding uses the Eulerian slip velocity v_T of eq. 26–27
(slip = v_T Δτ, Δτ the pseudo-time ``dtau``).  With Lagrangian (incremental)
friction the deformation problem is a fast-time process and the shape is driven
by an externally supplied cycle-averaged rate (``averaged=True``, field
``rate_bar``, eqs. 21–23; see :mod:`tribofx.time_scale`).

Schemes: ``implicit`` (θ = 1) solves (u, λ, w, ζ) in one BlockNewton with the
exact tangent; ``explicit`` (θ = 0) first updates (w, ζ) with the rate of the
known state (λ_n), then solves the contact problem (u, λ) on the new shape.  A
shape update that inverts a cell (det G ≤ 0) or a Newton failure cuts the step.
Units: mm, N, s, MPa.
"""

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from .contact_problem import ContactProblem, _node_to_dof
from .forms import ale
from .forms import contact as cf
from .forms import wear as wf
from .newton import BlockNewton, NewtonDivergence

__all__ = ["MeshInversion", "WearProblem"]

SCHEMES = ("explicit", "implicit")
LAWS = ("nominal", "spatial")


class MeshInversion(NewtonDivergence):
    """The shape update inverted a cell (det(I + Grad w) ≤ 0); the step must be cut."""


class WearProblem(ContactProblem):
    """A :class:`ContactProblem` whose body wears (Archard, pressure or dissipation form).

    Extra args (others as :class:`ContactProblem`; ``settings.friction`` = μ > 0 selects
    the dissipation form Ẇ = (k/μ) T_T·v_T of eqs. 13–14):
        k: Archard coefficient (mm³/(N·mm)).
        slip_speed: sliding speed V of the countersurface relative to the body (mm/s).
        scheme: "explicit" (θ = 0) or "implicit" (θ = 1).
        aux_E, aux_nu: fictitious Young's modulus (MPa) and Poisson ratio of the
            auxiliary elasticity problem (default: E of the body scale, 0.3).
        law: "nominal" (eq. 14, Ẇ = k p V) or "spatial" (eqs. 15–16, Ẇ = (k/J) p V,
            J = det F relative to the worn configuration, evaluated at t_{n+θ}).
        k_grad: relative depth gradient g (1/mm) of the wear coefficient,
            k(d) = k max(1 + g d, 0), d = −w·N̂ the wear depth at t_{n+θ} (0: constant).
        averaged: the shape update (28) is driven by the nodal field ``rate_bar``
            (cycle-averaged rate per unit initial area, mm/s, set by a slow-time
            driver) instead of the instantaneous rate; the shape and deformation
            problems are then solved one after the other (as for ``explicit``).
    """

    def __init__(self, msh, facet_tags, contact_tag, kind, material, mat_params,
                 obstacle_factory, settings, k, slip_speed, scheme="implicit", aux_E=1.0,
                 aux_nu=0.3, quadrature_degree=None, law="nominal", k_grad=0.0,
                 averaged=False):
        if scheme not in SCHEMES:
            raise ValueError(f"unknown wear scheme {scheme!r}; expected one of {SCHEMES}")
        if law not in LAWS:
            raise ValueError(f"unknown wear law {law!r}; expected one of {LAWS}")
        if settings.friction < 0:
            raise ValueError("friction coefficient must be >= 0")
        if settings.friction > 0 and settings.slip != "eulerian" and not averaged:
            raise ValueError("Lagrangian (fast-time) friction needs averaged=True and a "
                             "slow-time driver (tribofx.time_scale)")
        super().__init__(msh, facet_tags, contact_tag, kind, material, mat_params,
                         obstacle_factory, settings, quadrature_degree=quadrature_degree)
        self.scheme = scheme
        self.averaged = averaged
        self.mu = settings.friction
        self.law = law
        self.kind = kind
        # a distinct (equal) space: Dirichlet conditions are sorted into blocks by space
        self.Vw = fem.functionspace(msh, self.V.ufl_element())
        self.w = fem.Function(self.Vw, name="shape_change")
        self.w_n = fem.Function(self.Vw, name="shape_change_old")
        self.zeta = fem.Function(self.Q, name="shape_multiplier")
        self.lam_old = fem.Function(self.Q, name="contact_multiplier_old")
        self.rate_bar = fem.Function(self.Q, name="cycle_averaged_wear_rate")
        self.dt = fem.Constant(msh, 0.0)  # 0: no wear in a plain contact solve
        self.k = fem.Constant(msh, float(k))
        self.k_grad = fem.Constant(msh, float(k_grad))
        self.slip_speed = fem.Constant(msh, float(slip_speed))
        self.N_hat = ufl.FacetNormal(msh)
        du = self._v
        # deformation problem on the worn configuration (replaces the parent's R_u)
        ca = self._contact_args
        mu_t = ufl.TestFunction(self.Vs) if self.lam_t is not None else None
        R_uc, R_n, R_t = cf.augmented_lagrangian_contact(
            self.u, du, self.geometry, self.lam_n, ufl.TestFunction(self.Q), settings.rho_n,
            self.dsc, self.lam_t, mu_t, ca["rho_t"], ca["slip"], ca["mu"], weight=self.weight)
        self.R_u = ale.internal_virtual_work_worn(self.u, self.w, du, kind, material,
                                                  mat_params, self.dx) + R_uc
        self.R_n = R_n
        self.R_t = R_t
        # shape evolution: auxiliary elasticity + nodal normal constraint (28)
        dw = ufl.TestFunction(self.Vw)
        eta = ufl.TestFunction(self.Q)
        a = ale.swept_nanson_vector(self.w, self.w_n, self.N_hat)
        # rate at t_{n+θ}: implicit (u, λ, w)_{n+1}; explicit (u, λ, w)_n (during the
        # shape update u still holds u_n)
        if averaged:
            self.rate_density = self.rate_bar
        elif scheme == "implicit":
            self.rate_density = self._rate(self.lam_n, self.u, self.w)
        else:
            self.rate_density = self._rate(self.lam_old, self.u, self.w_n)
        mu_a = aux_E / (2 * (1 + aux_nu))
        lmbda_a = aux_E * aux_nu / ((1 + aux_nu) * (1 - 2 * aux_nu))
        self.R_w = (ale.aux_elasticity(self.w, dw, mu_a, lmbda_a, self.dx)
                    + self.zeta * ufl.dot(dw, a) * self.dsc)
        self.R_z = wf.shape_update_residual(self.w, self.w_n, a, self.rate_density, self.dt,
                                            eta, self.dsc)
        self.w_bcs = []
        self.shape_solver = None
        gmap_w = _node_to_dof(self.Vw)
        node_of_bulk = np.full(len(gmap_w), -1, dtype=np.int64)
        node_of_bulk[_node_to_dof(self.V)] = np.arange(len(gmap_w))
        self._bulk_dofs_w = gmap_w[node_of_bulk[self._bulk_dofs]]

    def _rate(self, lam, u, w, slip=None):
        """Wear rate per unit initial area Ẇ j_w at the state (λ, u, w).

        Frictionless: k(d) V |λ| (pressure form).  With friction μ > 0: the
        dissipation form (k(d)/μ) T_T·v_T, v_T = slip/Δτ (Eulerian slip) or, with
        ``slip`` given (e.g. a Lagrangian slip increment), the increment
        (k(d)/μ) T_T·slip.  Spatial law: divided by J = det F (worn reference).
        """
        k = wf.depth_graded_coefficient(self.k, self.k_grad, -ufl.dot(w, self.N_hat))
        J = None
        if self.law == "spatial":
            J = ufl.det(ale.deformation_gradient_worn(u, w, self.kind))
        if self.lam_t is None:
            return wf.archard_pressure_form(k, lam, self.slip_speed, J)
        _, t_t = cf.contact_tractions(self.geometry, lam, **self._contact_args)
        if slip is None:
            slip = self._contact_args["slip"] / self.settings.dtau
        return wf.archard_dissipation_form(k, self.mu, t_t, slip, J)

    # -- set-up -------------------------------------------------------------
    def add_traction(self, tag, traction):
        """Dead nominal traction (UFL vector, MPa) per unit *worn* area on facets ``tag``."""
        self.R_u = self.R_u - ale.traction_work_worn(traction, self.w, self._v, self.N_hat,
                                                     self.ds(tag))

    def add_shape_dirichlet(self, tag, component):
        """Zero normal motion of the worn boundary: w[component] = 0 on facets ``tag``."""
        fdim = self.mesh.topology.dim - 1
        Vc = self.Vw.sub(component)
        dofs = fem.locate_dofs_topological(Vc, fdim, self.facet_tags.find(tag))
        self.w_bcs.append(fem.dirichletbc(fem.Constant(self.mesh, 0.0), dofs, Vc))

    def finalize(self, **newton_kw):
        """Compile forms and create the Newton solver(s) of the chosen scheme."""
        fr = [self.R_t] if self.lam_t is not None else []
        fu = [self.lam_t] if self.lam_t is not None else []
        if self.scheme == "implicit" and not self.averaged:
            self.residuals = [self.R_u, self.R_n] + fr + [self.R_w, self.R_z]
            self.unknowns = [self.u, self.lam_n] + fu + [self.w, self.zeta]
            self.bcs = self.bcs + self.w_bcs
        else:
            self.residuals = [self.R_u, self.R_n] + fr
            self.unknowns = [self.u, self.lam_n] + fu
            self.shape_solver = BlockNewton([self.R_w, self.R_z], [self.w, self.zeta],
                                            bcs=self.w_bcs, entity_maps=[self.emap],
                                            **newton_kw)
        super().finalize(**newton_kw)
        msh = self.mesh
        G = ale.shape_gradient(self.w)
        self._worn_volume = fem.form((1 - ufl.det(G)) * self.dx)
        lam_now = self.rate_bar if self.averaged else self._rate(self.lam_n, self.u, self.w)
        self._rate_form = fem.form(lam_now * self.dsc, entity_maps=[self.emap])
        if self.averaged and self.lam_t is not None:
            # wear increment of a fast sub-step, K T_T·Δs (lumped: nodal values × weight)
            incr = self._rate(self.lam_n, self.u, self.w, slip=self._contact_args["slip"])
            self._increment_form = fem.form(incr * ufl.TestFunction(self.Q) * self.dsc,
                                            entity_maps=[self.emap])
            self._lumped_plain = fem.form(ufl.TestFunction(self.Q) * self.dsc,
                                          entity_maps=[self.emap])
        vs = ufl.TestFunction(self.Vs)
        self._normal_form = fem.form(ufl.dot(vs, self.N_hat) * self.dsc, entity_maps=[self.emap])
        self._DG0 = fem.functionspace(msh, ("DG", 0))
        self._detG = fem.Function(self._DG0)
        self._detG_expr = fem.Expression(ufl.det(G), self._DG0.element.interpolation_points)
        n = self._nodal(self._normal_form).reshape(-1, msh.geometry.dim)
        self._N_nodal = n / np.linalg.norm(n, axis=1)[:, None]

    # -- state --------------------------------------------------------------
    def _all(self):
        extra = [self.lam_t] if self.lam_t is not None else []
        return [self.u, self.lam_n, self.w, self.w_n, self.zeta, self.lam_old, self.xbar_n,
                self.rate_bar] + extra

    def state(self):
        """Copy of all unknowns, history and obstacle position (for step cutting)."""
        return ([f.x.array.copy() for f in self._all()]
                + [c.value.copy() for c in self._state_constants()])

    def restore(self, state):
        """Restore a state obtained from :meth:`state`."""
        fs = self._all()
        for f, a in zip(fs, state):
            f.x.array[:] = a
        for c, a in zip(self._state_constants(), state[len(fs):]):
            c.value[:] = a
        self._pre_evaluate()

    def nodal_wear_increment(self):
        """Wear increment K T_T·Δs of the last fast sub-step per unit initial area (mm).

        Lagrangian friction with ``averaged=True`` only; to be called after the
        sub-step's solve and before :meth:`commit` (Δs is measured from the last
        committed projection point).  Returns the local array on the Q dofs.
        """
        num = self._nodal(self._increment_form)
        den = self._nodal(self._lumped_plain)
        return np.divide(num, den, out=np.zeros_like(num), where=den > 0)

    def shape_step(self, dt, rate, verbose=False):
        """Shape update (28) over Δt with the given nodal rate (``averaged`` problems).

        Solves the shape subproblem (w, ζ) for (w − w_n)·a = −Δt rate with w_n
        the current shape and checks the mesh; the deformation problem is not
        re-solved.  Raises :class:`MeshInversion` (state restored) or
        :class:`NewtonDivergence`.
        """
        saved = self.state()
        self.dt.value = dt
        self.rate_bar.x.array[:] = rate
        self.w_n.x.array[:] = self.w.x.array
        try:
            report = self.shape_solver.solve(verbose=verbose)
            self._check_mesh()
        except NewtonDivergence:
            self.restore(saved)
            raise
        return report

    # -- time stepping ------------------------------------------------------
    def min_volume_factor(self):
        """Smallest det(I + Grad w) over all cells (≤ 0: the worn mesh is inverted)."""
        self._detG.interpolate(self._detG_expr)
        n = self._DG0.dofmap.index_map.size_local
        return self.mesh.comm.allreduce(float(np.min(self._detG.x.array[:n], initial=np.inf)),
                                        op=MPI.MIN)

    def _check_mesh(self):
        m = self.min_volume_factor()
        if not m > 0:
            raise MeshInversion(f"shape update inverts the mesh (min det(I + Grad w) = {m:.3e})")

    def step(self, dt, verbose=False, solve=None):
        """Advance the shape by one step Δt (s); returns the list of Newton reports.

        ``solve(verbose)``, if given, replaces the Newton solve of the (implicit:
        coupled; explicit: deformation) problem and returns a list of reports,
        e.g. an outer iteration on the obstacle position for a prescribed force.
        On failure (Newton divergence or inverted mesh) the state at entry is
        restored and :class:`NewtonDivergence` (or :class:`MeshInversion`) raised.
        """
        saved = self.state()
        self.dt.value = dt
        self.w_n.x.array[:] = self.w.x.array
        if solve is None:
            def solve(verbose):
                return [self.solver.solve(verbose=verbose)]
        try:
            if self.scheme == "implicit":
                reports = solve(verbose)
                self._check_mesh()
            else:
                self.lam_old.x.array[:] = self.lam_n.x.array
                reports = [self.shape_solver.solve(verbose=verbose)]
                self._check_mesh()
                # warm start: keep the deformed configuration x = X̂ + u (the gaps and
                # the active set stay), only the worn reference has changed
                reports += solve(verbose)
        except NewtonDivergence:
            self.restore(saved)
            raise
        finally:
            self.dt.value = 0.0  # a later plain solve() must not wear again
        self.commit()
        return reports

    # -- post-processing ----------------------------------------------------
    def _sum(self, form):
        return self.mesh.comm.allreduce(fem.assemble_scalar(form), op=MPI.SUM)

    def worn_volume(self):
        """Worn volume ∫_Ω̂ (1 − det G) dV̂ (mm³; per unit thickness, mm², in plane strain)."""
        return self._sum(self._worn_volume)

    def wear_rate_integral(self):
        """∫_Γc Ẇ dS = ∫_Γ̂c Ẇ j_w dŜ at the current state (mm³/s; mm²/s per mm in 2D)."""
        return self._sum(self._rate_form)

    def nodal_shape_data(self):
        """Per owned contact node: initial X̂, worn X = X̂ + w, wear depth −w·N̂, pressure, active."""
        gdim = self.mesh.geometry.dim
        d = self.nodal_contact_data()
        n_own = len(d["p"])
        wb = self.w.x.array.reshape(-1, gdim)
        ws = np.zeros_like(self._X_sub)
        ws[self._sub_dofs] = wb[self._bulk_dofs_w]
        d["X_hat"] = self._X_sub[:n_own]
        d["X_worn"] = self._X_sub[:n_own] + ws[:n_own]
        d["depth"] = -np.sum(ws[:n_own] * self._N_nodal[:n_own], axis=1)
        return d

    def gather_shape(self):
        """:meth:`nodal_shape_data` of all ranks on rank 0 (None elsewhere), sorted by X̂[0]."""
        d = self.nodal_shape_data()
        allp = self.mesh.comm.gather(d, root=0)
        if self.mesh.comm.rank != 0:
            return None
        out = {k: np.concatenate([a[k] for a in allp]) for k in d}
        order = np.argsort(out["X_hat"][:, 0])
        return {k: v[order] for k, v in out.items()}
