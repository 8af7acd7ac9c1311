"""Soft-EHL problem: hyperelastic layer + Reynolds film against a rigid cylinder (chapter §7).

Unknowns, all on the initial mesh:

* u — displacement of the bulk (vector Lagrange, degree 1 or 2);
* p — film pressure, P1 on the facet submesh of Γ_l;
* u_s — trace of u on the submesh (same degree as u, tied to u by an L2
  projection that is the identity, see :func:`forms.ehl.trace_constraint`);
* g — tangential pressure derivative Grad_Γ p·T, DG0 on the submesh (only with
  the shear tractions);
* λ — void fraction of the JFO cavitation model, P1 on the submesh (only with
  ``cavitation="jfo"``).

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
from .references import rigid_clearance
from .submesh import facet_submesh

# rigid_clearance is re-exported from tribofx.references
__all__ = ["EHLProblem", "LoadControl", "PositionedEHL", "rigid_clearance"]


class PositionedEHL:
    """Solve / state / restore of an EHL problem whose rigid countersurface sits at ``s``.

    Needs ``solver`` (:class:`BlockNewton`), ``unknowns``, the constant ``s`` (position
    of the countersurface, mm) and the list ``iterations``.
    """

    def solve(self, verbose=False):
        """Newton solve at the current countersurface position; returns the NewtonReport."""
        report = self.solver.solve(verbose=verbose)
        self.iterations.append(report.iterations)
        return report

    def state(self):
        """Copy of the unknowns and of the countersurface position (for step cutting)."""
        return [f.x.array.copy() for f in self.unknowns] + [float(self.s.value)]

    def restore(self, state):
        """Restore a state from :meth:`state`."""
        for f, a in zip(self.unknowns, state[:-1]):
            f.x.array[:] = a
        self.s.value = state[-1]

    def set_speed(self, U, p_c=None, eps=None, h_ref=None):
        """Change the speed U (mm/s) and, optionally, the scales that depend on it.

        ``p_c``: SUPG pressure scale (MPa); ``eps``: cavitation penalty; ``h_ref``: film
        scale of the row scaling (mm).  Needs ``U_c``, ``p_c``, ``eps``, ``mu``, ``_E_ref``
        and the row-scale constants ``_c_p``, ``_c_u``, ``_c_g``.
        """
        self.U = float(U)
        self.U_c.value = self.U
        if p_c is not None:
            self.p_c.value = float(p_c)
        if eps is not None and self.eps is not None:
            self.eps.value = float(eps)
        if h_ref is not None:
            self._c_p.value = self.mu / h_ref
            self._c_u.value = self._E_ref / h_ref
            self._c_g.value = float(h_ref)


class EHLProblem(PositionedEHL):
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
        cavitation: "penalty" (ε⁻¹ min(p, 0), p = 0 at both ends of Γ_l) or "jfo"
            (mass-conserving, eq. 57 with λ and nodal complementarity; flooded inlet
            at X = −x_l: p = λ = 0 there; natural outlet).  Needs U > 0.
        alpha: None (S = P(γ_l)) or α ∈ [0, 1], the intermediate lubrication surface
            S_α = (1 − α) P(γ_l) + α γ_l (:func:`forms.ehl.intermediate_surface`).
    """

    CAVITATION = ("penalty", "jfo")

    def __init__(self, msh, cell_tags, facet_tags, materials, lub_tag, clamp_tag, R, U, mu,
                 model="finite", shear=True, supg=True, eps=None, p_c=1.0, h_ref=1e-2,
                 degree=1, s0=0.0, countersurface=None, cavitation="penalty", alpha=None):
        if model not in ef.MODELS:
            raise ValueError(f"unknown model {model!r}")
        if cavitation not in self.CAVITATION:
            raise ValueError(f"unknown cavitation model {cavitation!r}")
        if cavitation == "jfo" and not U > 0:
            raise ValueError("cavitation='jfo' needs U > 0 (inlet at X = -x_l)")
        self.cavitation = cavitation
        self.mesh, self.model, self.shear = msh, model, shear
        self.R, self.U, self.mu = float(R), float(U), float(mu)
        gdim = msh.geometry.dim
        if gdim != 2:
            raise ValueError("EHLProblem is plane strain (gdim = 2)")
        self.sub, self.emap, _ = facet_submesh(msh, facet_tags, lub_tag, "lubricated surface")
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
        self.U_c = fem.Constant(sub, self.U)
        V_slide = ufl.as_vector([self.U_c, 0.0])
        mu_c = fem.Constant(sub, self.mu)
        self.alpha = None if alpha is None else fem.Constant(sub, float(alpha))

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
                                                  self.R, V_slide, model, surface, self.alpha)
        self.kin_sub = ef.lubrication_kinematics(Xs, self.u_s, ufl.grad(self.u_s), N, center,
                                                 self.R, V_slide, model, surface, self.alpha)
        v = ufl.TestFunction(self.V)
        dus = ufl.TestFunction(self.Vs)
        dp = ufl.TestFunction(self.Q)
        # row scales: Reynolds rows (mm²/s) × μ/h_ref, trace rows (mm²) × E_ref/h_ref
        E_ref = max(_young(m, prm) for m, prm in materials.values())
        self._c_p = fem.Constant(sub, self.mu / h_ref)
        c_u = fem.Constant(sub, E_ref / h_ref)
        self._E_ref = E_ref

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
        self.p_c = fem.Constant(sub, float(p_c))
        h_e = ufl.CellDiameter(sub)
        PN = ufl.Identity(gdim) - ufl.outer(N, N)

        def grad_gamma(f):
            """Tangential gradient Grad_Γ f = grad f (I − N⊗N) on Γ_l.

            UFL's grad of an expression of the spatial coordinate on the submesh
            (a manifold) keeps the derivative along N (grad X = I), so it is
            projected explicitly.
            """
            g = ufl.grad(f)
            return PN * g if len(g.ufl_shape) == 1 else g * PN

        self.grad_gamma = grad_gamma
        self.eps = None
        self.lam = None
        if cavitation == "penalty":
            self.eps = None if eps is None else fem.Constant(sub, float(eps))
            R_p = self._c_p * ef.reynolds_on_surface(
                self.p, dp, self.kin_sub, mu_c, self.dx_s, eps=self.eps, supg=supg,
                p_c=self.p_c, h_e=h_e, nodal_dx=nodal, grad_gamma=grad_gamma)
        else:
            self.Ql = fem.functionspace(sub, ("Lagrange", 1))
            self.lam = fem.Function(self.Ql, name="void_fraction")
            self.q_ref = fem.Constant(sub, 0.5 * self.U * float(h_ref))
            dlam = ufl.TestFunction(self.Ql)

            def transport(test):
                return ef.jfo_on_surface(self.p, self.lam, test, dlam, self.kin_sub, mu_c,
                                         self.dx_s, self.p_c, self.q_ref, h_e, nodal,
                                         supg=supg, grad_gamma=grad_gamma, T=T,
                                         ds_ends=self._ds_ends())

            F_t, C = transport(dp)
            self._transport = lambda test: transport(test)[0]
            R_p = self._c_p * F_t
        self._c_g = fem.Constant(sub, float(h_ref))
        residuals = [R_u, R_us, R_p]
        if shear:
            dg = ufl.TestFunction(self.G)
            residuals.append(self._c_g
                             * ef.tangential_gradient_constraint(self.g, self.p, dg, T,
                                                                 self.dx_s))
        if self.lam is not None:
            unknowns.append(self.lam)
            residuals.append(self._c_p * C)
        self.unknowns, self.residuals = unknowns, residuals
        self._c_u = c_u

        fdim = msh.topology.dim - 1
        bdofs = fem.locate_dofs_topological(self.V, fdim, facet_tags.find(clamp_tag))
        self.bcs = [fem.dirichletbc(np.zeros(gdim), bdofs, self.V)]
        xs = self.sub.geometry.x
        x_l = msh.comm.allreduce(float(np.abs(xs[:, 0]).max(initial=0.0)), op=MPI.MAX)
        self.x_l = x_l
        if cavitation == "penalty":
            ends = fem.locate_dofs_geometrical(self.Q,
                                               lambda y: np.isclose(np.abs(y[0]), x_l))
            self.bcs.append(fem.dirichletbc(np.float64(0.0), ends, self.Q))
        else:  # flooded inlet: p = 0, λ = 0; outlet natural (p = 0 by complementarity)
            inlet = fem.locate_dofs_geometrical(self.Q, lambda y: np.isclose(y[0], -x_l))
            inlet_l = fem.locate_dofs_geometrical(self.Ql, lambda y: np.isclose(y[0], -x_l))
            self.bcs += [fem.dirichletbc(np.float64(0.0), inlet, self.Q),
                         fem.dirichletbc(np.float64(0.0), inlet_l, self.Ql)]
            self._phi = {}
            for key, xe in (("in", -x_l), ("out", x_l)):
                phi = fem.Function(self.Q)
                dofs = fem.locate_dofs_geometrical(self.Q, lambda y, xe=xe: np.isclose(y[0], xe))
                phi.x.array[dofs] = 1.0
                self._phi[key] = phi
            # Couette flux θ h v̄·t_S along S (t_S: unit tangent of S in the direction of +X)
            kin = self.kin_sub
            tS = kin.A * T
            tS = tS / ufl.sqrt(ufl.dot(tS, tS))
            self._g_expr = fem.Expression((1 - ufl.min_value(self.lam, 1.0)) * kin.h
                                          * ufl.dot(kin.vbar, tS),
                                          self.Q.element.interpolation_points)
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

    # -- JFO ----------------------------------------------------------------------
    def _ds_ends(self):
        """Measure of the two end points X = ±x_l of Γ_l (the submesh's true boundary).

        Tagged explicitly: in parallel the untagged ``ds`` of the facet submesh
        also contains the vertices on the partition boundary.
        """
        sub = self.sub
        xs = sub.geometry.x
        x_l = sub.comm.allreduce(float(np.abs(xs[:, 0]).max(initial=0.0)), op=MPI.MAX)
        sub.topology.create_connectivity(0, 1)
        ends = dmesh.locate_entities(sub, 0, lambda y: np.isclose(np.abs(y[0]), x_l))
        tags = dmesh.meshtags(sub, 0, ends, np.full(len(ends), 1, dtype=np.int32))
        return ufl.Measure("ds", sub, subdomain_data=tags, subdomain_id=1,
                           metadata={"quadrature_degree": 4})

    def jfo_initial_guess(self):
        """Void fraction of a film that ruptures at its minimum h_m and keeps its flux.

        λ = max(0, 1 − h_m/h) downstream of the minimum film, 0 upstream (as
        :meth:`tribofx.cases.reynolds.Reynolds1D.jfo_initial_guess`), from the
        current film h; p is left as it is.
        """
        if self.lam is None:
            return
        self.update_countersurface()
        h = fem.Function(self.Q)
        h.interpolate(self._h_expr)
        X = self.Q.tabulate_dof_coordinates()[:, 0]
        n = self.Q.dofmap.index_map.size_local
        loc = (float(h.x.array[:n].min(initial=np.inf)),
               float(X[np.argmin(h.x.array[:n])]) if n else 0.0)
        h_m, X_m = min(self.mesh.comm.allgather(loc))
        lam = np.where(X > X_m, np.maximum(0.0, 1 - h_m / h.x.array), 0.0)
        # λ and p share the P1 layout of the same submesh
        self.lam.x.array[:] = lam
        self.lam.x.scatter_forward()

    def consistent_fluxes(self):
        """JFO: volume fluxes (mm²/s) into and out of the film from the discrete residual.

        With R(φ) the transport residual (57) (+ SUPG) and g = θ h v̄·t_S the
        Couette flux along S: q_in = g(−x_l) + R(φ_in), q_out = g(x_l) − R(φ_out),
        φ the hat functions of the end nodes.  The hat functions sum to one, so
        q_out − q_in is the sum of the interior equations plus the quadrature
        error of ∫ d g/dX: zero to solver tolerance for the conservative model.
        """
        if self.lam is None:
            raise ValueError("consistent fluxes need cavitation='jfo'")
        self.update_countersurface()
        comm = self.mesh.comm
        R = {k: comm.allreduce(fem.assemble_scalar(fem.form(
            self._transport(phi), entity_maps=[self.emap])), op=MPI.SUM)
            for k, phi in self._phi.items()}
        g = fem.Function(self.Q)
        g.interpolate(self._g_expr)
        out = {}
        for k, phi in self._phi.items():
            n = self.Q.dofmap.index_map.size_local
            idx = np.nonzero(phi.x.array[:n] > 0.5)[0]
            val = float(g.x.array[idx[0]]) if len(idx) else None
            out[k] = next(v for v in comm.allgather(val) if v is not None)
        return out["in"] + R["in"], out["out"] - R["out"]

    def set_speed(self, U, p_c=None, eps=None, h_ref=None):
        """Change the sliding speed U (mm/s) and, optionally, the scales that depend on it."""
        super().set_speed(U, p_c, eps, h_ref)
        if self.lam is not None:
            self.q_ref.value = 0.5 * self.U * float(h_ref if h_ref is not None
                                                    else self.mu / self._c_p.value)

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
        if self.lam is not None:
            d["lam"] = self.lam.x.array[:n]
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

    def speed_sweep(self, speeds, scales=None, on_step=None, max_cuts=6):
        """Continuation in the sliding speed at the load reached last (``W_done``).

        For each U of ``speeds`` (mm/s) in turn the speed is moved from the
        current one in geometric increments (one increment first), the cylinder
        position found again for the same load; a failed increment restores the
        last converged state and halves the increment in log U (step cutting).
        ``scales(U)`` returns the speed-dependent (p_c, ε, h_ref) of the problem
        (None: unchanged); ``on_step(U, its, final)`` is called after each
        converged increment.
        """
        prob, W = self.prob, self.W_done
        if not W > 0:
            raise ValueError("speed_sweep needs a converged load (run sweep first)")
        for U in speeds:
            U = float(U)
            if not U > 0:
                raise ValueError("speeds must be positive")
            ratio = U / prob.U
            cuts = 0
            while abs(prob.U / U - 1) > 1e-12:
                U_old = prob.U
                Un = U_old * ratio if abs(math.log(ratio)) < abs(math.log(U / U_old)) else U
                saved = prob.state()
                slope_saved = self.slope
                self._set_speed(Un, scales)
                self.slope *= Un / U_old     # rigid film: s ∝ μU/W
                try:
                    self.W_done = W
                    its = self.find_position(W)
                except NewtonDivergence:
                    prob.restore(saved)
                    self._set_speed(U_old, scales)
                    self.slope = slope_saved
                    cuts += 1
                    if cuts > max_cuts:
                        raise
                    ratio = math.sqrt(Un / U_old)
                    if self.verbose and prob.mesh.comm.rank == 0:
                        print(f" step cut: speed ratio reduced to {ratio:.4g}")
                    continue
                if on_step is not None:
                    on_step(Un, its, final=abs(Un / U - 1) <= 1e-12)

    def _set_speed(self, U, scales):
        if scales is None:
            self.prob.set_speed(U)
        else:
            p_c, eps, h_ref = scales(U)
            self.prob.set_speed(U, p_c=p_c, eps=eps, h_ref=h_ref)
