"""Soft-EHL problem: hyperelastic layer + Reynolds film against a rigid cylinder (chapter §7).

Unknowns, all on the initial mesh:

* u — displacement of the bulk (vector Lagrange, degree 1 or 2);
* p — film pressure, P1 on the facet submesh of Γ_l;
* u_s — trace of u on the submesh (same degree as u, tied to u by an L2
  projection that is the identity, see :func:`forms.ehl.trace_constraint`);
* g — tangential pressure derivative Grad_Γ p·T, DG0 on the submesh (only with
  the shear tractions).

The Reynolds equation is integrated over the submesh in (u_s, p), the solid
virtual work over the bulk and Γ_l in (u, p, g); one monolithic
:class:`tribofx.newton.BlockNewton` solves for all of them with the exact UFL
tangent.  The rows are scaled to a force per unit length (N/mm) so that the
convergence test weighs the blocks alike.

The cylinder (radius R, axis at X = 0) has its lowest point at height s above
the undeformed surface Y = 0 (s < 0: it indents the undeformed layer); s is
found for a prescribed load W (N/mm) by :class:`LoadControl`.  Units: mm, N, s,
MPa.
"""

import math

import numpy as np
import ufl
from dolfinx import fem
from dolfinx import mesh as dmesh
from mpi4py import MPI

from .forms import ehl as ef
from .forms import hyperelastic as hf
from .newton import BlockNewton, NewtonDivergence

__all__ = ["EHLProblem", "LoadControl", "rigid_clearance"]


def rigid_clearance(W, mu, U, R):
    """Minimum film (mm) of a rigid cylinder in pure sliding at load W: W = 2.45 μ U R/h0.

    (Martin's result W = 4.9 μ u_m R/h0 with Reynolds conditions, u_m = U/2.)
    """
    return 2.45 * mu * U * R / W


class EHLProblem:
    """Coated layer ``msh`` lubricated on ``facet_tags == lub_tag`` against a rigid cylinder.

    Args:
        msh, cell_tags, facet_tags: mesh (affine) and its tags.
        materials: {cell tag: (material, params)} (see :mod:`forms.hyperelastic`).
        lub_tag, clamp_tag: facet tags of Γ_l and of the bonded bottom.
        R: cylinder radius (mm).  U: sliding speed (mm/s).  mu: viscosity (MPa·s).
        model: "finite" or "linear".  shear: shear tractions on the layer.
        supg: SUPG term in the Reynolds equation.
        eps: cavitation penalty (MPa·s/mm) or None.
        p_c: pressure scale of SUPG (MPa).  h_ref: film scale for row scaling (mm).
        degree: Lagrange degree of u.
        countersurface: None (analytic cylinder) or ``(nodes, facets, cell_type)``, the
            cylinder as a surface mesh in its own frame (axis at the origin, normal
            out of the cylinder), moved with the cylinder (offset (0, R + s)) and
            projected by :func:`tribofx.lubrication_projection.lubrication_projection`
            at the P1 nodes of Γ_l before every assembly (see :mod:`forms.ehl`).
    """

    def __init__(self, msh, cell_tags, facet_tags, materials, lub_tag, clamp_tag, R, U, mu,
                 model="finite", shear=True, supg=True, eps=None, p_c=1.0, h_ref=1e-2,
                 degree=1, s0=0.0, countersurface=None):
        if model not in ef.MODELS:
            raise ValueError(f"unknown model {model!r}")
        self.mesh, self.model, self.shear = msh, model, shear
        self.R, self.U, self.mu = float(R), float(U), float(mu)
        gdim = msh.geometry.dim
        if gdim != 2:
            raise ValueError("EHLProblem is plane strain (gdim = 2)")
        tdim = msh.topology.dim
        msh.topology.create_connectivity(tdim - 1, tdim)
        lub = facet_tags.find(lub_tag)
        if msh.comm.allreduce(len(lub), op=MPI.SUM) == 0:
            raise ValueError(f"mesh has no facets tagged {lub_tag} (lubricated surface)")
        self.sub, self.emap, _, _ = dmesh.create_submesh(msh, tdim - 1, lub)
        sub = self.sub
        self.V = fem.functionspace(msh, ("Lagrange", degree, (gdim,)))
        self.Vs = fem.functionspace(sub, ("Lagrange", degree, (gdim,)))
        self.Q = fem.functionspace(sub, ("Lagrange", 1))
        self.u = fem.Function(self.V, name="displacement")
        self.u_s = fem.Function(self.Vs, name="displacement_trace")
        self.p = fem.Function(self.Q, name="pressure")
        self.s = fem.Constant(sub, float(s0))
        N = ufl.as_vector([0.0, 1.0])
        T = ufl.as_vector([1.0, 0.0])
        self.N, self.T = N, T
        center = ufl.as_vector([0.0, self.R + self.s])
        V_slide = ufl.as_vector([self.U, 0.0])
        mu_c = fem.Constant(sub, self.mu)

        qd = {"quadrature_degree": 4}
        dx = ufl.Measure("dx", msh, subdomain_data=cell_tags)
        self.ds_l = ufl.Measure("ds", msh, subdomain_data=facet_tags, subdomain_id=lub_tag,
                                metadata=qd)
        self.dx_s = ufl.Measure("dx", sub, metadata=qd)
        nodal = ufl.Measure("dx", sub, metadata={"quadrature_rule": "vertex",
                                                 "quadrature_degree": 1})
        # bulk-side kinematics (solid tractions) and submesh kinematics (Reynolds)
        X = ufl.SpatialCoordinate(msh)
        Xs = ufl.SpatialCoordinate(sub)
        self._Q1v = fem.functionspace(sub, ("Lagrange", 1, (gdim,)))
        surface = None
        self.countersurface = countersurface
        if countersurface is not None:
            surface = self._meshed_surface(*countersurface)
        self.kin_bulk = ef.lubrication_kinematics(X, self.u, ufl.grad(self.u), N, center,
                                                  self.R, V_slide, model, surface)
        self.kin_sub = ef.lubrication_kinematics(Xs, self.u_s, ufl.grad(self.u_s), N, center,
                                                 self.R, V_slide, model, surface)
        v = ufl.TestFunction(self.V)
        dus = ufl.TestFunction(self.Vs)
        dp = ufl.TestFunction(self.Q)
        # row scales: Reynolds rows (mm²/s) × μ/h_ref, trace rows (mm²) × E_ref/h_ref
        E_ref = max(_young(m, prm) for m, prm in materials.values())
        self._c_p = fem.Constant(sub, self.mu / h_ref)
        c_u = fem.Constant(sub, E_ref / h_ref)

        R_u = 0
        for tag, (material, params) in materials.items():
            mat = "linear" if model == "linear" else material
            R_u += hf.internal_virtual_work(self.u, v, "plane_strain", mat, params, dx(tag))
        F2 = ufl.Identity(gdim) + ufl.grad(self.u)
        self.g = None
        dpdT = 0.0
        unknowns = [self.u, self.u_s, self.p]
        if shear:
            self.G = fem.functionspace(sub, ("DG", 0))
            self.g = fem.Function(self.G, name="pressure_tangential_derivative")
            dpdT = self.g
            unknowns.append(self.g)
        self.traction = ef.fluid_traction(self.p, dpdT, self.kin_bulk, F2, N, T, mu_c,
                                          shear=shear, model=model)
        R_u -= ufl.dot(self.traction, v) * self.ds_l
        R_us = c_u * ef.trace_constraint(self.u_s, self.u, dus, self.ds_l)
        self.eps = None if eps is None else fem.Constant(sub, float(eps))
        R_p = self._c_p * ef.reynolds_on_surface(
            self.p, dp, self.kin_sub, mu_c, self.dx_s, eps=self.eps, supg=supg,
            p_c=fem.Constant(sub, float(p_c)), h_e=ufl.CellDiameter(sub), nodal_dx=nodal)
        residuals = [R_u, R_us, R_p]
        if shear:
            dg = ufl.TestFunction(self.G)
            residuals.append(fem.Constant(sub, float(h_ref))
                             * ef.tangential_gradient_constraint(self.g, self.p, dg, T,
                                                                 self.dx_s))
        self.unknowns, self.residuals = unknowns, residuals

        fdim = tdim - 1
        bdofs = fem.locate_dofs_topological(self.V, fdim, facet_tags.find(clamp_tag))
        self.bcs = [fem.dirichletbc(np.zeros(gdim), bdofs, self.V)]
        xs = self.sub.geometry.x
        x_l = msh.comm.allreduce(float(np.abs(xs[:, 0]).max(initial=0.0)), op=MPI.MAX)
        self.x_l = x_l
        ends = fem.locate_dofs_geometrical(self.Q, lambda y: np.isclose(np.abs(y[0]), x_l))
        self.bcs.append(fem.dirichletbc(np.float64(0.0), ends, self.Q))
        self.solver = BlockNewton(residuals, unknowns, bcs=self.bcs, entity_maps=[self.emap],
                                  rtol=1e-10, atol=1e-12, max_it=25, max_backtracks=6,
                                  pre_evaluate=self.update_countersurface)
        # post-processing forms
        self._force = [fem.form(self.traction[i] * self.ds_l, entity_maps=[self.emap])
                       for i in range(gdim)]
        Q1v = self._Q1v
        pts = self.Q.element.interpolation_points
        self._h_expr = fem.Expression(self.kin_sub.h, pts)
        self._y_expr = fem.Expression(self.kin_sub.y, Q1v.element.interpolation_points)
        self._x_expr = fem.Expression(Xs + self.u_s, Q1v.element.interpolation_points)
        self.iterations = []

    # -- meshed countersurface ---------------------------------------------------
    def _meshed_surface(self, nodes, facets, cell_type):
        """Nodal P1 fields of the kernel data on Γ_l; returns the UFL surface map."""
        from .lubrication_projection import lubrication_projection

        self._lub_project = lubrication_projection
        self._cs = (np.asarray(nodes, dtype=float), np.asarray(facets, dtype=np.int32),
                    cell_type)
        sub, gdim = self.sub, self.mesh.geometry.dim
        T = fem.functionspace(sub, ("Lagrange", 1, (gdim, gdim)))
        S = fem.functionspace(sub, ("Lagrange", 1))
        V1 = self._Q1v
        self._cs_u = fem.Function(V1)
        self._cs_X = V1.tabulate_dof_coordinates()[:, :gdim]
        self.cs_x0 = fem.Function(V1, name="cs_x0")
        self.cs_h0 = fem.Function(S, name="cs_h0")
        self.cs_nu0 = fem.Function(V1, name="cs_nu0")
        self.cs_y0 = fem.Function(V1, name="cs_y0")
        self.cs_dy0 = fem.Function(T, name="cs_dy_dx")
        self.cs_dnu0 = fem.Function(T, name="cs_dnu_dx")
        self.cs_d2y0 = [fem.Function(T, name=f"cs_d2y_dx{k}") for k in range(gdim)]
        fields = (self.cs_x0, self.cs_h0, self.cs_nu0, self.cs_y0, self.cs_dy0, self.cs_dnu0,
                  self.cs_d2y0)
        self.update_countersurface()
        return lambda x: ef.meshed_countersurface(x, *fields)

    def update_countersurface(self):
        """Project the nodes of Γ_l (current, or reference for ``model="linear"``)."""
        if self.countersurface is None:
            return
        nodes, facets, cell_type = self._cs
        gdim = self.mesh.geometry.dim
        x = self._cs_X.copy()
        if self.model == "finite":
            self._cs_u.interpolate(self.u_s)
            x += self._cs_u.x.array.reshape(-1, gdim)
        off = np.array([0.0, self.R + float(self.s.value)])
        r = self._lub_project(x - off, nodes, facets, cell_type)
        if not np.all(r.facet >= 0):
            raise ValueError("meshed countersurface: projection failed")
        self.cs_x0.x.array[:] = x.ravel()
        self.cs_h0.x.array[:] = r.h
        self.cs_nu0.x.array[:] = r.nu.ravel()
        self.cs_y0.x.array[:] = (r.y + off).ravel()
        self.cs_dy0.x.array[:] = r.dy_dx.ravel()
        self.cs_dnu0.x.array[:] = r.dnu_dx.ravel()
        for k, f in enumerate(self.cs_d2y0):
            f.x.array[:] = np.ascontiguousarray(r.d2y_dx2[..., k]).ravel()

    # -- solving ---------------------------------------------------------------
    def solve(self, verbose=False):
        """Newton solve at the current cylinder position; returns the NewtonReport."""
        report = self.solver.solve(verbose=verbose)
        self.iterations.append(report.iterations)
        return report

    def state(self):
        """Copy of the unknowns and of the cylinder position (for step cutting)."""
        return [f.x.array.copy() for f in self.unknowns] + [float(self.s.value)]

    def restore(self, state):
        """Restore a state from :meth:`state`."""
        for f, a in zip(self.unknowns, state[:-1]):
            f.x.array[:] = a
        self.s.value = state[-1]

    # -- results ---------------------------------------------------------------
    def film_force(self):
        """Force (N/mm) the film exerts on the layer, [tangential, vertical]."""
        comm = self.mesh.comm
        return np.array([comm.allreduce(fem.assemble_scalar(f), op=MPI.SUM)
                         for f in self._force])

    def load(self):
        """Load carried by the film, W = −(vertical film force on the layer) (N/mm)."""
        return -float(self.film_force()[1])

    def profile(self):
        """Nodal X, current x, projection y, film h and pressure p on rank 0 (sorted by X)."""
        self.update_countersurface()
        h = fem.Function(self.Q)
        h.interpolate(self._h_expr)
        y = fem.Function(self._Q1v)
        y.interpolate(self._y_expr)
        x = fem.Function(self._Q1v)
        x.interpolate(self._x_expr)
        n = self.Q.dofmap.index_map.size_local
        X = self.Q.tabulate_dof_coordinates()[:n, :2]
        d = {"X": X[:, 0], "x": x.x.array.reshape(-1, 2)[:n], "y": y.x.array.reshape(-1, 2)[:n],
             "h": h.x.array[:n], "p": self.p.x.array[:n]}
        allp = self.mesh.comm.gather(d, root=0)
        if self.mesh.comm.rank != 0:
            return None
        out = {k: np.concatenate([a[k] for a in allp]) for k in d}
        order = np.argsort(out["X"])
        return {k: v[order] for k, v in out.items()}

    def measures(self):
        """Return h_min, h_central (film below the cylinder axis), p_max, forces (all ranks)."""
        prof = self.profile()
        res = None
        if self.mesh.comm.rank == 0:
            yx = prof["y"][:, 0] if self.model == "finite" else prof["X"]
            res = {"h_min": float(prof["h"].min()),
                   "h_central": float(np.interp(0.0, yx, prof["h"])),
                   "p_max": float(prof["p"].max()),
                   "x_p_max": float(yx[np.argmax(prof["p"])])}
        res = self.mesh.comm.bcast(res, root=0)
        f = self.film_force()
        res["W"] = -float(f[1])
        res["tangential_force"] = float(f[0])
        res["friction_coefficient"] = abs(float(f[0])) / res["W"] if res["W"] > 0 else math.nan
        res["clearance"] = float(self.s.value)
        return res


def _young(material, params):
    if "mu" in params and "lmbda" in params:
        mu, lm = params["mu"], params["lmbda"]
        return mu * (3 * lm + 2 * mu) / (lm + mu)
    return 3 * (params["mu1"] + params["mu2"])


class LoadControl:
    """Cylinder position for a prescribed load, with load continuation and step cutting.

    :meth:`find_position` runs a secant iteration on f(s) = 1/W(s) − 1/W* (linear
    in s for a rigid film, W ∝ 1/h0), each trial a full Newton solve warm-started
    from the previous trial; a failed trial is restored and moved halfway back
    to the last converged position.  :meth:`sweep` increases the load to the
    targets, halving the load increment when a step fails and restoring the
    last converged state.
    """

    def __init__(self, prob, rtol=1e-6, max_trials=30, verbose=False):
        self.prob, self.rtol, self.max_trials, self.verbose = prob, rtol, max_trials, verbose
        # ds/d(1/W), initially that of the rigid cylinder (s = 2.45 μUR/W)
        self.slope = rigid_clearance(1.0, prob.mu, prob.U, prob.R)
        self.W_done = 0.0
        self.trials = []

    def find_position(self, W):
        """Move the cylinder until the film carries ``W`` (N/mm); returns Newton iterations."""
        prob = self.prob
        saved = prob.state()
        s_ok = float(prob.s.value)
        s1 = s_ok if self.W_done > 0 else rigid_clearance(W, prob.mu, prob.U, prob.R)
        if self.W_done > 0:
            s1 = s_ok + self.slope * (1 / W - 1 / self.W_done)
        its, prev = [], None
        for _ in range(self.max_trials):
            prob.s.value = s1
            try:
                its.append(prob.solve(verbose=self.verbose).iterations)
            except NewtonDivergence:
                its.append(-1)
                if prev is not None:
                    good_s, state = prev[0], prev[2]
                elif self.W_done > 0:
                    good_s, state = s_ok, saved
                else:
                    good_s, state = None, saved
                prob.restore(state)
                s1 = 2 * s1 if good_s is None else 0.5 * (s1 + good_s)
                continue
            Wt = prob.load()
            if self.verbose and prob.mesh.comm.rank == 0:
                print(f" s = {s1:.6e} mm: W = {Wt:.6e} N/mm (target {W:.6e})")
            if Wt > 0 and abs(Wt - W) <= self.rtol * W:
                self.W_done = W
                self.trials.append(its)
                return its
            if Wt <= 0:
                s_new = s1 - abs(self.slope) / W
            elif prev is not None and prev[1] != 1 / Wt:
                self.slope = (s1 - prev[0]) / (1 / Wt - prev[1])
                s_new = s1 + self.slope * (1 / W - 1 / Wt)
            else:
                s_new = s1 + self.slope * (1 / W - 1 / Wt)
            prev = (s1, 1 / Wt if Wt > 0 else math.inf, prob.state())
            s1 = s_new
        prob.restore(saved)
        raise NewtonDivergence(f"load {W:g} N/mm not reached in {self.max_trials} trials")

    def sweep(self, targets, on_step=None, max_cuts=6):
        """Reach each load of ``targets`` in turn with step cutting; calls on_step(W, its)."""
        for W in targets:
            dW = W - self.W_done
            cuts = 0
            while self.W_done < W * (1 - 1e-12):
                Wn = min(W, self.W_done + dW)
                saved = self.prob.state()
                W_saved, slope_saved = self.W_done, self.slope
                try:
                    its = self.find_position(Wn)
                except NewtonDivergence:
                    self.prob.restore(saved)
                    self.W_done, self.slope = W_saved, slope_saved
                    cuts += 1
                    if cuts > max_cuts:
                        raise
                    dW *= 0.5
                    if self.verbose and self.prob.mesh.comm.rank == 0:
                        print(f" step cut: load increment halved to {dW:.4g} N/mm")
                    continue
                if on_step is not None:
                    on_step(Wn, its, final=(Wn >= W * (1 - 1e-12)))
