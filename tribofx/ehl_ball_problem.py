"""Soft-EHL problem in 3D: hyperelastic ball sliding on a rigid plane (chapter §7, §8.3).

Quarter model: the lower hemisphere (centre (0, 0, R)) of the half y ≥ 0; the
sliding direction x lies in the symmetry plane y = 0 (u_y = 0 there), the
horizontal mid-plane z = R is held (u = 0) and the rigid plane z = z_p = −s
moves instead (a rigid translation of the whole system, so this is the
chapter's mid-plane moving vertically as a rigid plane under the load W).
s is the clearance of the lowest point of the undeformed ball (s < 0:
indentation) and is found for a prescribed load by :class:`BallLoadControl`
(secant in ln W, the counterpart of :class:`tribofx.ehl_problem.LoadControl`).

Unknowns, all on the initial mesh (as :class:`tribofx.ehl_problem.EHLProblem`):
u (P1 vector, bulk), u_s (P1 vector trace of u on the facet submesh of the
lubricated cap Γ_l), p (P1 on the submesh), g = Grad_Γ p (vector DG0 on the
submesh, exact for P1 p; only with the shear tractions).

Ball frame (pure sliding, ball-on-disc): the ball material is at rest, the
plane moves with V = 2U e_x, so v̄ = ½(0 + V) = U e_x on S (U = V/2, the
entrainment speed; μU is the control parameter).  Lubrication surface
S = P(γ_l) on the plane (:func:`forms.ehl.plane_countersurface`, ν = e_z,
h = x_z − z_p), Reynolds (49) with SUPG and penalty cavitation on S pulled back
to Γ_l; p = 0 on the boundary circle of the cap (z = z_cap), zero flux
(natural) on the symmetry line y = 0.  Fluid traction (46) on the ball:
−p n − (μ/h)(0 − V) − (h/2) grad_S p (Nanson for the pressure, ds/dS = J|F⁻ᵀN|
for the shear).  The reference normal N of Γ_l on the submesh is the oriented
cell normal of the flat triangles, on the bulk side the facet normal (the same
vector).  Units: mm, N, s, MPa.
"""

import math

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from .ehl_problem import PositionedEHL
from .forms import ehl as ef
from .forms import hyperelastic as hf
from .newton import BlockNewton
from .references import hamrock_dowson, hertz
from .submesh import facet_submesh

# hamrock_dowson is re-exported from tribofx.references
__all__ = ["BallLoadControl", "EHLBallProblem", "hamrock_dowson", "hertz_ball"]


def hertz_ball(W, R, E_star):
    """Hertz radius a (mm), approach δ (mm), peak pressure p0 (MPa) of a ball on a rigid plane.

    Kept for existing callers; the formula is :func:`tribofx.references.hertz` (W in N,
    E* the composite modulus; a rigid plane: E* = E/(1 − ν²)).
    """
    h = hertz(W, R, E_star, 0.0)
    return h.a, h.delta, h.p0


class EHLBallProblem(PositionedEHL):
    """Quarter ball ``msh`` lubricated on ``facet_tags == lub_tag`` against a rigid plane.

    Args:
        msh, cell_tags, facet_tags: tetrahedral mesh (affine) and its tags
            (:func:`tribofx.meshes.ball.quarter_ball`).
        material, params: strain-energy law and its parameters (forms/hyperelastic).
        lub_tag, mid_tag, sym_tag: facet tags of Γ_l, the mid-plane, y = 0.
        R: ball radius (mm).  z_cap: height of the cap boundary circle (mm).
        U: entrainment speed (mm/s; the plane slides at 2U).  mu: viscosity (MPa·s).
        model: "finite" or "linear".  shear: shear tractions on the ball.
        supg: SUPG term.  eps: cavitation penalty (MPa·s/mm) or None.
        p_c: pressure scale of SUPG (MPa).  h_ref: film scale for row scaling (mm).
        s0: initial clearance (mm).
    """

    def __init__(self, msh, cell_tags, facet_tags, material, params, lub_tag, mid_tag, sym_tag,
                 R, z_cap, U, mu, model="finite", shear=True, supg=True, eps=None, p_c=1.0,
                 h_ref=1e-2, s0=0.0):
        if model not in ef.MODELS:
            raise ValueError(f"unknown model {model!r}")
        gdim = msh.geometry.dim
        if gdim != 3:
            raise ValueError("EHLBallProblem is three-dimensional (gdim = 3)")
        self.mesh, self.model, self.shear = msh, model, shear
        self.cell_tags, self.facet_tags = cell_tags, facet_tags
        self.R, self.U, self.mu, self.z_cap = float(R), float(U), float(mu), float(z_cap)
        self.sub, self.emap, _ = facet_submesh(msh, facet_tags, lub_tag, "lubricated cap")
        sub = self.sub
        self.V = fem.functionspace(msh, ("Lagrange", 1, (gdim,)))
        self.Vs = fem.functionspace(sub, ("Lagrange", 1, (gdim,)))
        self.Q = fem.functionspace(sub, ("Lagrange", 1))
        self.u = fem.Function(self.V, name="displacement")
        self.u_s = fem.Function(self.Vs, name="displacement_trace")
        self.p = fem.Function(self.Q, name="pressure")
        self.s = fem.Constant(sub, float(s0))
        self.U_c = fem.Constant(sub, self.U)
        mu_c = fem.Constant(sub, self.mu)
        center = ufl.as_vector([0.0, 0.0, self.R])
        zero = ufl.as_vector([0.0, 0.0, 0.0])             # ball material at rest
        V_plane = ufl.as_vector([2 * self.U_c, 0.0, 0.0])  # plane slides at V = 2U e_x

        def surface(x):
            return ef.plane_countersurface(x, -self.s)        # plane z = z_p = −s

        qd = {"quadrature_degree": 2}
        dx = ufl.Measure("dx", msh, subdomain_data=cell_tags)
        self.ds_l = ufl.Measure("ds", msh, subdomain_data=facet_tags, subdomain_id=lub_tag,
                                metadata=qd)
        self.dx_s = ufl.Measure("dx", sub, metadata=qd)
        nodal = ufl.Measure("dx", sub, metadata={"quadrature_rule": "vertex",
                                                 "quadrature_degree": 1})
        X, Xs = ufl.SpatialCoordinate(msh), ufl.SpatialCoordinate(sub)
        N_b = ufl.FacetNormal(msh)
        N_s = ef.oriented_cell_normal(sub, center)
        self.N_s = N_s
        grad_gamma = ef.tangential_gradient(N_s)
        self.grad_gamma = grad_gamma
        self.kin_bulk = ef.lubrication_kinematics(X, self.u, ufl.grad(self.u), N_b, None, None,
                                                  zero, model, surface, V_counter=V_plane)
        self.kin_sub = ef.lubrication_kinematics(Xs, self.u_s, grad_gamma(self.u_s), N_s, None,
                                                 None, zero, model, surface, V_counter=V_plane)
        v = ufl.TestFunction(self.V)
        dus = ufl.TestFunction(self.Vs)
        dp = ufl.TestFunction(self.Q)
        E_ref = _young(params)
        self._E_ref = E_ref
        self._c_p = fem.Constant(sub, self.mu / h_ref)
        self._c_u = fem.Constant(sub, E_ref / h_ref)
        self._c_g = fem.Constant(sub, float(h_ref))
        mat = "linear" if model == "linear" else material
        R_u = hf.internal_virtual_work(self.u, v, "3d", mat, params, dx)
        F = ufl.Identity(gdim) + ufl.grad(self.u)
        unknowns = [self.u, self.u_s, self.p]
        self.g = None
        grad_p = ufl.zero(gdim)
        if shear:
            self.G = fem.functionspace(sub, ("DG", 0, (gdim,)))
            self.g = fem.Function(self.G, name="pressure_tangential_gradient")
            grad_p = self.g
            unknowns.append(self.g)
        self.traction = ef.fluid_traction(self.p, grad_p, self.kin_bulk, F, N_b, None, mu_c,
                                          shear=shear, model=model)
        R_u -= ufl.dot(self.traction, v) * self.ds_l
        R_us = self._c_u * ef.trace_constraint(self.u_s, self.u, dus, self.ds_l)
        self.p_c = fem.Constant(sub, float(p_c))
        self.eps = None if eps is None else fem.Constant(sub, float(eps))
        R_p = self._c_p * ef.reynolds_on_surface(
            self.p, dp, self.kin_sub, mu_c, self.dx_s, eps=self.eps, supg=supg, p_c=self.p_c,
            h_e=ufl.CellDiameter(sub), nodal_dx=nodal, grad_gamma=grad_gamma)
        residuals = [R_u, R_us, R_p]
        if shear:
            dg = ufl.TestFunction(self.G)
            residuals.append(self._c_g * ef.tangential_gradient_constraint(
                self.g, self.p, dg, None, self.dx_s, grad_gamma))
        self.unknowns, self.residuals = unknowns, residuals

        fdim = msh.topology.dim - 1
        mid = fem.locate_dofs_topological(self.V, fdim, facet_tags.find(mid_tag))
        Vy = self.V.sub(1)
        sym = fem.locate_dofs_topological(Vy, fdim, facet_tags.find(sym_tag))
        tol = 1e-6 * self.R
        rim = fem.locate_dofs_geometrical(self.Q, lambda y: np.abs(y[2] - self.z_cap) < tol)
        self.bcs = [fem.dirichletbc(np.zeros(gdim), mid, self.V),
                    fem.dirichletbc(np.float64(0.0), sym, Vy),
                    fem.dirichletbc(np.float64(0.0), rim, self.Q)]
        self.solver = BlockNewton(residuals, unknowns, bcs=self.bcs, entity_maps=[self.emap],
                                  rtol=1e-10, atol=1e-12, max_it=25, max_backtracks=6)
        # dry problem: the same ball under a prescribed (Hertz) pressure p_d, follower load
        self.p_dry = fem.Function(self.Q, name="prescribed_pressure")
        T_dry = ef.fluid_traction(self.p_dry, grad_p, self.kin_bulk, F, N_b, None, mu_c,
                                  shear=False, model=model)
        R_dry = hf.internal_virtual_work(self.u, v, "3d", mat, params, dx)
        R_dry -= ufl.dot(T_dry, v) * self.ds_l
        self.dry_solver = BlockNewton([R_dry, R_us], [self.u, self.u_s], bcs=self.bcs[:2],
                                      entity_maps=[self.emap], rtol=1e-10, atol=1e-12,
                                      max_it=25)
        self._force = [fem.form(self.traction[i] * self.ds_l, entity_maps=[self.emap])
                       for i in range(gdim)]
        # Couette drag alone (post-processing, also when it does not load the ball)
        couette = ef.fluid_traction(0.0, ufl.zero(gdim), self.kin_bulk, F, N_b, None, mu_c,
                                    shear=True, model=model)
        self._couette = fem.form(couette[0] * self.ds_l, entity_maps=[self.emap])
        pts = self.Q.element.interpolation_points
        self._h_expr = fem.Expression(self.kin_sub.h, pts)
        self._x_expr = fem.Expression(Xs + self.u_s, self.Vs.element.interpolation_points)
        self.iterations = []

    # -- solving ---------------------------------------------------------------
    def hertz_start(self, W, E_star, h0):
        """Set the initial state for load W (N): ball under Hertz pressure, film h0 at the centre.

        p = p0 √(1 − r²/a²)⁺ (r = in-plane distance of the reference point from
        the contact axis) loads the dry ball (:attr:`dry_solver`, follower
        pressure, same material); then the plane is put at the clearance giving
        the film ``h0`` below the deformed contact centre and p is kept as the
        first pressure iterate.  Soft EHL at moderate load is close to this state
        (the pressure is nearly Hertzian), which a Newton solve from the
        undeformed ball is not.  Returns the dry Newton report.
        """
        h = hertz(W, self.R, E_star, 0.0)     # E* given: ν = 0 makes E₁ = E*
        a, p0 = h.a, h.p0
        self.p_dry.interpolate(
            lambda x: p0 * np.sqrt(np.maximum(0.0, 1 - (x[0] ** 2 + x[1] ** 2) / a**2)))
        rep = self.dry_solver.solve()
        self.p.x.array[:] = self.p_dry.x.array
        if self.g is not None:
            self.g.x.array[:] = 0.0
        x = fem.Function(self.Vs)
        x.interpolate(self._x_expr)
        n = self.Q.dofmap.index_map.size_local
        X = self.Q.tabulate_dof_coordinates()[:n]
        xz = x.x.array.reshape(-1, 3)[:n, 2]
        r2 = X[:, 0] ** 2 + X[:, 1] ** 2
        loc = (float(r2.min(initial=np.inf)), float(xz[np.argmin(r2)]) if n else 0.0)
        z_c = min(self.mesh.comm.allgather(loc))[1]
        self.s.value = h0 - z_c
        return rep

    # -- results ---------------------------------------------------------------
    def film_force(self):
        """Force (N) of the film on the modelled half of the ball, [x, y, z]."""
        comm = self.mesh.comm
        return np.array([comm.allreduce(fem.assemble_scalar(f), op=MPI.SUM)
                         for f in self._force])

    def min_film(self):
        """Smallest nodal film thickness on Γ_l (mm, all ranks)."""
        h = fem.Function(self.Q)
        h.interpolate(self._h_expr)
        n = self.Q.dofmap.index_map.size_local
        return self.mesh.comm.allreduce(float(h.x.array[:n].min(initial=np.inf)), op=MPI.MIN)

    def load(self):
        """Load W (N) carried by the film on the whole ball: twice the half model's F_z."""
        return 2.0 * float(self.film_force()[2])

    def profile(self):
        """Nodal data of the film on rank 0: X, x (current), h, p (all nodes of Γ_l).

        ``xy`` are the in-plane coordinates on S: (x_x, x_y) of the projection
        y = P(x) for ``model="finite"``, (X_x, X_y) of the reference surface
        for ``"linear"`` (S0 = P(Γ_l)).
        """
        h = fem.Function(self.Q)
        h.interpolate(self._h_expr)
        x = fem.Function(self.Vs)
        x.interpolate(self._x_expr)
        n = self.Q.dofmap.index_map.size_local
        X = self.Q.tabulate_dof_coordinates()[:n]
        # Vs and Q share the P1 layout of the same submesh
        xc = x.x.array.reshape(-1, 3)[:n]
        d = {"X": X, "x": xc, "h": h.x.array[:n].copy(), "p": self.p.x.array[:n].copy()}
        allp = self.mesh.comm.gather(d, root=0)
        if self.mesh.comm.rank != 0:
            return None
        out = {k: np.concatenate([a[k] for a in allp]) for k in d}
        out["xy"] = (out["x"] if self.model == "finite" else out["X"])[:, :2]
        return out

    def centerline(self, prof):
        """Film h and pressure p on the symmetry line y = 0, sorted by x (rank 0)."""
        on = np.abs(prof["X"][:, 1]) < 1e-9 * self.R
        xx = prof["xy"][on, 0]
        order = np.argsort(xx)
        return xx[order], prof["h"][on][order], prof["p"][on][order]

    def measures(self):
        """h_central (on the axis, x = 0), h_min, p_max, W, friction coefficients (all ranks).

        ``friction_coefficient``: x-force of the film traction on the ball / W (all
        terms that load the ball; with ``shear=False`` only the pressure part);
        ``couette_friction_coefficient``: the Couette drag ∫ j (μ/h)|V| dS / W,
        evaluated also when the shear does not load the ball.
        """
        prof = self.profile()
        res = None
        if self.mesh.comm.rank == 0:
            xx, hh, pp = self.centerline(prof)
            i = int(np.argmin(prof["h"]))
            res = {"h_central": float(np.interp(0.0, xx, hh)),
                   "h_min": float(prof["h"][i]), "x_h_min": float(prof["xy"][i, 0]),
                   "y_h_min": float(prof["xy"][i, 1]), "p_max": float(prof["p"].max())}
        res = self.mesh.comm.bcast(res, root=0)
        f = self.film_force()
        res["W"] = 2.0 * float(f[2])
        res["friction_force"] = 2.0 * float(f[0])
        res["friction_coefficient"] = (abs(float(f[0])) / float(f[2]) if f[2] > 0
                                       else math.nan)
        fc = self.mesh.comm.allreduce(fem.assemble_scalar(self._couette), op=MPI.SUM)
        res["couette_friction_coefficient"] = (abs(fc) / float(f[2]) if f[2] > 0
                                               else math.nan)
        res["clearance"] = float(self.s.value)
        return res


def _young(params):
    mu, lm = params["mu"], params["lmbda"]
    return mu * (3 * lm + 2 * mu) / (lm + mu)


class BallLoadControl:
    """Plane position for a prescribed load W (N), with load continuation and step cutting.

    The load of a soft ball grows like a power of the approach (Hertz: W ∝ δ^{3/2}),
    so :meth:`find_position` runs a secant iteration on f(s) = ln W(s) − ln W* in the
    clearance s, each trial a Newton solve warm-started from the last converged
    state.  Before two converged points are known it moves s down by ``ds0``.
    A trial step is limited to ``max_step`` (mm); a failed trial is restored and
    its step halved (step cutting).  Every converged trial is kept (``points``)
    so the next load starts from the secant through the last two.
    """

    def __init__(self, prob, rtol=1e-4, max_trials=40, ds0=1e-3, max_step=None, verbose=False):
        self.prob, self.rtol, self.max_trials, self.verbose = prob, rtol, max_trials, verbose
        self.ds0 = float(ds0)
        self.max_step = max_step
        self.points = []          # converged (s, ln W)
        self.history = []         # last two converged (W, state)
        self.trials = []
        self.W_done = 0.0

    def _solve_at(self, s):
        from .newton import NewtonDivergence

        prob = self.prob
        saved = prob.state()
        prob.s.value = s
        try:
            its = prob.solve().iterations
        except NewtonDivergence:
            prob.restore(saved)
            return None, -1
        W = prob.load()
        if self.verbose and prob.mesh.comm.rank == 0:
            print(f" s = {s:.6e} mm: W = {W:.6e} N ({its} Newton iterations)")
        if not prob.min_film() > 0:       # a converged but unphysical branch (h ≤ 0)
            prob.restore(saved)
            return None, -1
        return W, its

    def find_position(self, W, predicted=None):
        """Move the plane until the film carries ``W`` (N); returns the Newton iterations.

        ``predicted``: a predicted state (:meth:`EHLBallProblem.state`) for the
        first trial; if its Newton solve fails the iteration restarts from the
        current (converged) state.
        """
        from .newton import NewtonDivergence

        prob = self.prob
        saved = prob.state()
        points = list(self.points)
        its_all = []
        step_max = self.max_step
        if predicted is not None:
            prob.restore(predicted)
            Wt, its = self._solve_at(float(prob.s.value))
            its_all.append(its)
            if Wt is None or not Wt > 0:
                prob.restore(saved)
            else:
                points.append((float(prob.s.value), math.log(Wt)))
                if abs(Wt - W) <= self.rtol * W:
                    return self._done(W, points, its_all)
        for _ in range(self.max_trials):
            s1 = float(prob.s.value)
            if len(points) >= 2 and points[-1][1] != points[-2][1]:
                (s0, l0), (sa, la) = points[-2], points[-1]
                target = sa + (sa - s0) / (la - l0) * (math.log(W) - la)
                step = target - s1
            elif points and points[-1][1] > math.log(W):
                step = self.ds0
            else:
                step = -self.ds0
            if step_max is not None and abs(step) > step_max:
                step = math.copysign(step_max, step)
            before = prob.state()
            Wt, its = self._solve_at(s1 + step)
            its_all.append(its)
            if Wt is None or not Wt > 0:
                prob.restore(before)
                step_max = 0.5 * abs(step)
                if self.verbose and prob.mesh.comm.rank == 0:
                    print(f" step cut: |Δs| ≤ {step_max:.3e} mm")
                continue
            points.append((s1 + step, math.log(Wt)))
            if step_max is not None:      # let a cut step grow back after a success
                grow = 1.5 * step_max
                step_max = grow if self.max_step is None else min(self.max_step, grow)
            if abs(Wt - W) <= self.rtol * W:
                return self._done(W, points, its_all)
        prob.restore(saved)
        raise NewtonDivergence(f"load {W:g} N not reached in {self.max_trials} trials")

    def indent(self, W, ds, scales=None, on_step=None, min_ds=1e-4):
        """Displacement control: lower the plane from the current converged state until W (N).

        Each step moves the plane by −Δs from the last converged state (its
        unknowns are the initial guess: no extrapolation), Newton solves at the
        fixed position and the load W(s) is an output.  A step whose Newton
        solve fails or whose film has min h ≤ 0 (the unphysical branch) is
        restored and halved; a success lets Δs grow by 1.5 (never above
        ``ds``).  ``scales(W)`` gives (p_c, ε, h_ref) at the load reached last
        (they follow the load: p0 ∝ W^{1/3}); ``on_step(W, its)`` per converged
        step.  Once a step passes W, :meth:`find_position` hits W by the
        secant through the two bracketing converged states, starting from the
        nearer one.  Raises NewtonDivergence (state: last converged) when Δs
        falls below ``min_ds``·``ds``.  Returns the Newton iterations per step.
        """
        from .newton import NewtonDivergence

        prob = self.prob
        step, its_all = float(ds), []
        W_cur = prob.load()
        lnW = math.log(W_cur) if W_cur > 0 else None
        self.points = [(float(prob.s.value), lnW)] if lnW is not None else []
        while W_cur < W * (1 - self.rtol):
            if scales is not None and W_cur > 0:
                p_c, eps, h_ref = scales(W_cur)
                prob.set_speed(prob.U, p_c=p_c, eps=eps, h_ref=h_ref)
            s1, before = float(prob.s.value), prob.state()
            Wt, its = self._solve_at(s1 - step)
            its_all.append(its)
            if Wt is None or not Wt > W_cur:
                prob.restore(before)
                step *= 0.5
                if self.verbose and prob.mesh.comm.rank == 0:
                    print(f" indentation step cut: Δs = {step:.3e} mm")
                if step < min_ds * ds:
                    raise NewtonDivergence(f"displacement control stalled at W = {W_cur:g} N "
                                           f"(step {step:.2e} mm)")
                continue
            W_cur = Wt
            self.points = (self.points + [(s1 - step, math.log(Wt))])[-2:]
            if on_step is not None:
                on_step(Wt, its)
            step = min(float(ds), 1.5 * step)
        if scales is not None:
            p_c, eps, h_ref = scales(W)
            prob.set_speed(prob.U, p_c=p_c, eps=eps, h_ref=h_ref)
        if abs(W_cur - W) > self.rtol * W:
            its_all += self.find_position(W)
        else:
            self._done(W, self.points, [])
        return its_all

    def _done(self, W, points, its_all):
        self.points = points[-2:]
        self.trials.append(its_all)
        self.W_done = W
        self.history = (self.history + [(W, self.prob.state())])[-2:]
        return its_all

    def sweep(self, targets, on_step=None, restart=None):
        """Reach each load of ``targets`` in turn; calls ``on_step(W, its, final=True)``.

        Predictor of each load: ``restart(W)`` when given (e.g.
        :meth:`EHLBallProblem.hertz_start` at W: for soft EHL the Hertz state is
        closer to the solution than an extrapolation, which can cut the thin
        film), else linear extrapolation in W of the last two converged states
        (unknowns and plane position); the secant corrector then follows.
        """
        for W in targets:
            pred = None
            if self.history and restart is not None:
                current = self.prob.state()
                restart(W)
                pred = self.prob.state()
                self.prob.restore(current)
            elif len(self.history) == 2:
                (W0, x0), (W1, x1) = self.history
                t = (W - W1) / (W1 - W0)
                pred = [a1 + t * (a1 - a0) if isinstance(a1, np.ndarray) else
                        a1 + t * (a1 - a0) for a0, a1 in zip(x0, x1)]
            its = self.find_position(W, pred)
            if on_step is not None:
                on_step(W, its, final=True)

    def speed_sweep(self, speeds, scales=None, on_step=None, max_cuts=4, restart=None):
        """Continuation in the entrainment speed U (mm/s) at the load reached last.

        Geometric increments to each U of ``speeds``; a failed increment restores
        the last converged state and halves the increment in log U.  ``scales(U)``
        gives (p_c, ε, h_ref) at speed U; ``on_step(U, its, final)`` per increment.
        ``restart(U)`` (e.g. the Hertz start with the film of speed U) predicts the
        state of each increment; without it the plane is shifted by the change
        h_c ((U_new/U_old)^0.64 − 1) of the Hamrock–Dowson film.
        """
        from .newton import NewtonDivergence

        prob, W = self.prob, self.W_done
        if not W > 0:
            raise ValueError("speed_sweep needs a converged load (run sweep first)")
        for U in speeds:
            U = float(U)
            ratio, cuts = U / prob.U, 0
            while abs(prob.U / U - 1) > 1e-12:
                U_old = prob.U
                Un = U_old * ratio if abs(math.log(ratio)) < abs(math.log(U / U_old)) else U
                saved, points = prob.state(), list(self.points)
                h_c = prob.measures()["h_central"]
                self._set_speed(Un, scales)
                ds0 = self.ds0
                self.ds0 = ds0 * (Un / U_old) ** 0.64      # film scale follows the speed
                pred = None
                if restart is not None:
                    restart(Un)
                    pred = prob.state()
                    prob.restore(saved)
                    self.points = []
                else:
                    # film ∝ U^0.64 (Hamrock–Dowson): shift the secant points by the change
                    dh = h_c * ((Un / U_old) ** 0.64 - 1)
                    self.points = [(s + dh, lw) for s, lw in points]
                    prob.s.value = float(prob.s.value) + dh
                try:
                    its = self.find_position(W, pred)
                except NewtonDivergence:
                    prob.restore(saved)
                    self._set_speed(U_old, scales)
                    self.points, self.ds0 = points, ds0
                    cuts += 1
                    if cuts > max_cuts:
                        raise
                    ratio = math.sqrt(Un / U_old)
                    continue
                if on_step is not None:
                    on_step(Un, its, final=abs(Un / U - 1) <= 1e-12)

    def _set_speed(self, U, scales):
        if scales is None:
            self.prob.set_speed(U)
        else:
            p_c, eps, h_ref = scales(U)
            self.prob.set_speed(U, p_c=p_c, eps=eps, h_ref=h_ref)
