"""Hydrodynamic lubrication between rigid surfaces: the Reynolds equation in 1D.

Two cases on an interval mesh (the planar, traditional form §6.6 of the chapter,
with the weak forms of ``forms/reynolds.py``):

``reynolds-slider`` — plane inclined slider (pad at rest, plane runner sliding
at U, so v̄ = U/2 and ∂h/∂t = 0 by eq. 61), gap h = h0(1 + K − K x/L) on
0 ≤ x ≤ L, p = 0 at both ends; compared with the closed-form pressure, load and
peak of :func:`tribofx.references.slider_reference` (Reynolds 1886, Cameron).

``reynolds-cylinder`` — rigid cylinder of radius R near a rigid plane, parabolic
gap h = h0 + x²/(2R) on x_in ≤ x ≤ x_out, mean entrainment speed u_m (both
surfaces rolling/sliding so that v̄ = u_m), p = 0 at the inlet.  Cavitation
models: ``none`` (full Sommerfeld, p = 0 also at x_out; the reported load is the
positive part, the half-Sommerfeld/Gümbel convention), ``penalty`` (p ≥ 0 by a
penalty; this is the variational-inequality solution, whose rupture satisfies
the Swift–Stieber conditions p = p' = 0), ``jfo`` (mass-conserving JFO model,
unknowns p and λ; inlet p = 0, λ = 0 (flooded), outlet natural: no Poiseuille
flux, and p = 0 there by complementarity since the outlet lies in the
cavitation zone).  References, computed by NumPy quadrature independently of
the FE code for the same inlet position: the half-Sommerfeld and the
Swift–Stieber solutions of :func:`tribofx.references.cylinder_references`.

Units: mm, N, s, MPa (viscosity MPa·s; loads per unit width/length N/mm).
"""

import math

import numpy as np
import ufl
from dolfinx import fem
from dolfinx import mesh as dmesh
from mpi4py import MPI

from ..forms import reynolds as rf
from ..newton import BlockNewton, NewtonDivergence
from ..params import InputError, Param
from ..references import cylinder_references, slider_pressure, slider_reference

# cylinder_references and slider_reference are re-exported from tribofx.references
__all__ = [
    "CylinderCase",
    "Reynolds1D",
    "SliderCase",
    "cylinder_references",
    "slider_reference",
]


# --------------------------------------------------------------------------- FE problem


class Reynolds1D:
    """Steady Reynolds equation on the interval [x0, x1] with optional cavitation.

    Args:
        comm: MPI communicator.
        x0, x1: ends (mm); the flow enters at x0 (v̄ > 0).
        n: number of elements.  degree: Lagrange degree of p (JFO: 1).
        gap: callable x (UFL coordinate) → film thickness h (mm, UFL).
        vbar: mean velocity v̄ (mm/s).  mu: viscosity (MPa·s).
        cavitation: "none", "penalty" or "jfo".
        supg: add the SUPG term of Remark 3.2.
        p_c: pressure scale of the JFO constraint and of the SUPG Péclet number (MPa).
        eps: penalty parameter ε (MPa·s/mm) for ``penalty``.
        q_ref: flux scale (mm²/s) of the constraint rows (JFO).
        lam_in: void fraction at the inlet (JFO; 0: flooded, > 0: starved).
        clip_void: use min(λ, 1) in the Reynolds residual, so that an iterate with
            λ > 1 (negative density) cannot balance the fluxes (it otherwise yields
            spurious discrete solutions at a reformation boundary on fine meshes).
    """

    def __init__(self, comm, x0, x1, n, degree, gap, vbar, mu, cavitation="none",
                 supg=False, p_c=1.0, eps=None, q_ref=1.0, lam_in=0.0, clip_void=True):
        self.comm, self.x0, self.x1 = comm, x0, x1
        self.gap, self.vbar, self.lam_in = gap, float(vbar), float(lam_in)
        self.cavitation = cavitation
        msh = dmesh.create_interval(comm, n, [x0, x1])
        self.mesh = msh
        x = ufl.SpatialCoordinate(msh)
        self.h = gap(x[0])
        V = fem.functionspace(msh, ("Lagrange", degree))
        self.V = V
        self.p = fem.Function(V, name="pressure")
        # λ on its own (identical) space so that Dirichlet conditions find their block
        self.Vl = fem.functionspace(msh, ("Lagrange", degree)) if cavitation == "jfo" else None
        self.lam = fem.Function(self.Vl, name="void_fraction") if self.Vl else None
        self.h_fun = fem.Function(V, name="film_thickness")
        self.h_fun.interpolate(fem.Expression(self.h, V.element.interpolation_points))

        self.vbar_c = fem.Constant(msh, np.array([float(vbar)]))
        self.mu_c = fem.Constant(msh, float(mu))
        self.p_c = fem.Constant(msh, float(p_c))
        vb, mu_ = self.vbar_c, self.mu_c
        self.dx = ufl.Measure("dx", domain=msh, metadata={"quadrature_degree": 4 * degree + 6})
        dxn = rf.nodal_measure(ufl.Measure("dx", domain=msh)) if degree == 1 else self.dx
        h_e = ufl.CellDiameter(msh)
        h, p = self.h, self.p
        dp = ufl.TestFunction(V)
        lam = 0.0
        if self.lam is not None:
            lam = ufl.min_value(self.lam, 1.0) if clip_void else self.lam

        def transport(v):
            """Reynolds residual (57) (+ SUPG) tested by v, without cavitation terms."""
            F = rf.jfo_residual(p, lam, v, h, vb, mu_, self.dx)
            if supg:
                F += rf.supg_stabilisation(p, lam, v, h, vb, mu_, self._tau(), self.dx)
            return F

        self._transport = transport
        self.supg = supg
        self.h_e = h_e

        left = fem.locate_dofs_geometrical(V, lambda y: np.isclose(y[0], x0))
        right = fem.locate_dofs_geometrical(V, lambda y: np.isclose(y[0], x1))
        zero = np.float64(0.0)
        self._phi = {}
        for key, dofs in (("in", left), ("out", right)):
            phi = fem.Function(V)
            phi.x.array[dofs] = 1.0
            self._phi[key] = phi

        if cavitation == "jfo":
            dlam = ufl.TestFunction(self.Vl)
            self.q_ref = fem.Constant(msh, float(q_ref))
            Fp = transport(dp)
            Fl = rf.jfo_complementarity(p, self.lam, dlam, self.p_c, dxn, weight=self.q_ref / h_e)
            # inlet: λ = λ_in; flooded (λ_in = 0): also p = 0 (the reservoir supplies
            # what the film carries), starved (λ_in > 0): no Poiseuille flux, so the
            # inflow is the supplied (1 − λ_in) h v̄ and p = 0 by complementarity.
            # Outlet: natural (no Poiseuille flux; p = 0 by complementarity).
            left_l = fem.locate_dofs_geometrical(self.Vl, lambda y: np.isclose(y[0], x0))
            bcs = [fem.dirichletbc(np.float64(lam_in), left_l, self.Vl)]
            if lam_in == 0:
                bcs.append(fem.dirichletbc(zero, left, V))
            self.solver = BlockNewton([Fp, Fl], [self.p, self.lam], bcs=bcs, max_it=50,
                                      max_backtracks=8)
        else:
            F = rf.reynolds_residual(p, dp, h, vb, mu_, self.dx)
            if supg:
                F += rf.supg_stabilisation(p, 0.0, dp, h, vb, mu_, self._tau(), self.dx)
            if cavitation == "penalty":
                self.eps = fem.Constant(msh, float(eps))
                F += rf.cavitation_penalty(p, dp, self.eps, dxn)
            bcs = [fem.dirichletbc(zero, left, V), fem.dirichletbc(zero, right, V)]
            self.solver = BlockNewton(F, self.p, bcs=bcs, max_it=50, max_backtracks=8)
        self.iterations = []

    def _tau(self):
        if self.cavitation == "jfo":
            D = rf.jfo_diffusivity(self.p, self.lam, self.h, self.mu_c, self.p_c)
        else:
            D = self.h**2 * self.p_c / (12 * self.mu_c)
        return rf.supg_tau(self.h_e, self.vbar_c, D)

    def jfo_initial_guess(self):
        """Void fraction of a film that keeps its flux across the cavitated zones.

        Upstream of the minimum gap h_m the inlet film (flux (1 − λ_in) h(x0) v̄)
        is advected, λ = max(0, 1 − (1 − λ_in) h(x0)/h); downstream the film
        ruptures at h_m, λ = max(0, 1 − h_m/h); p = 0.  Starting from it the
        semismooth Newton iteration only has to move the two free boundaries
        (rather than discover the cavitated zones from a large negative Sommerfeld
        pressure), which makes it robust and its iteration count mesh independent.
        """
        xl = self.Vl.tabulate_dof_coordinates()[:, 0]
        hl = self.gap(xl)
        nown = self.Vl.dofmap.index_map.size_local
        loc = (float(hl[:nown].min(initial=np.inf)), float(xl[np.argmin(hl[:nown])])
               if nown else 0.0)
        h_m, x_m = min(self.comm.allgather(loc))
        h_in = (1 - self.lam_in) * float(self.gap(np.array(self.x0)))
        lam0 = np.where(xl < x_m, 1 - h_in / hl, 1 - h_m / hl)
        self.lam.x.array[:] = np.maximum(lam0, 0.0)
        self.p.x.array[:] = 0.0

    def set_from_profile(self, prof):
        """Set p (and λ) by linear interpolation of a (coarser) nodal profile (rank-0 dict)."""
        for fun in (self.p, self.lam):
            if fun is None:
                continue
            xs = fun.function_space.tabulate_dof_coordinates()[:, 0]
            fun.x.array[:] = np.interp(xs, prof["x"], prof["p" if fun is self.p else "lam"])

    # ------------------------------------------------------------------ solve & measures
    def solve(self, verbose=False):
        """Newton solve from the current state; returns the :class:`NewtonReport`."""
        report = self.solver.solve(verbose=verbose)
        self.iterations.append(report.iterations)
        return report

    def integral(self, expr, dx=None):
        """Global integral of the UFL expression ``expr`` over the interval."""
        val = fem.assemble_scalar(fem.form(expr * (dx or self.dx)))
        return self.comm.allreduce(val, op=MPI.SUM)

    def consistent_fluxes(self):
        """Volume fluxes (mm²/s) through the inlet and outlet from the discrete residual.

        With R(v) the transport residual (57) (+ SUPG, without cavitation penalty)
        and g = θ h v̄ the Couette flux, q_in = g(x0) + R(φ_in) and
        q_out = g(x1) − R(φ_out), φ the hat functions of the end nodes.  Since the
        hat functions sum to one, q_out − q_in is the sum of the interior
        equations: zero to solver tolerance for a conservative model.
        """
        R = {k: self.comm.allreduce(fem.assemble_scalar(fem.form(self._transport(phi))),
                                    op=MPI.SUM)
             for k, phi in self._phi.items()}
        prof = self.profile()
        g_in = g_out = None
        if self.comm.rank == 0:
            th = 1 - prof["lam"] if "lam" in prof else np.ones_like(prof["x"])
            v = float(self.vbar_c.value[0])
            g_in = th[0] * prof["h"][0] * v
            g_out = th[-1] * prof["h"][-1] * v
        g_in, g_out = self.comm.bcast((g_in, g_out), root=0)
        return g_in + R["in"], g_out - R["out"]

    def profile(self):
        """Nodal x, p, h (and λ) gathered and sorted on rank 0 (None elsewhere)."""
        nown = self.V.dofmap.index_map.size_local
        x = self.V.tabulate_dof_coordinates()[:nown, 0]
        fields = {"x": x, "p": self.p.x.array[:nown], "h": self.h_fun.x.array[:nown]}
        if self.lam is not None:
            fields["lam"] = self.lam.x.array[:nown]
        gathered = {k: self.comm.gather(np.asarray(v).copy(), root=0) for k, v in fields.items()}
        if self.comm.rank != 0:
            return None
        out = {k: np.concatenate(v) for k, v in gathered.items()}
        order = np.argsort(out["x"], kind="stable")
        return {k: v[order] for k, v in out.items()}


def _peak_and_rupture(prof, crossing):
    """Nodal peak (p_max, x_p_max) and rupture point downstream of the peak.

    ``crossing``: linear zero crossing of p (no cavitation model); otherwise the
    first node with p ≤ 1e-9 p_max (p vanishes in the cavitation zone).
    """
    x, p = prof["x"], prof["p"]
    i = int(np.argmax(p))
    pm = float(p[i])
    if crossing:
        neg = np.nonzero(p[i:] < 0)[0]
        if not len(neg):
            return pm, float(x[i]), float(x[-1])
        j = i + neg[0]
        return pm, float(x[i]), float(x[j - 1] - p[j - 1] * (x[j] - x[j - 1]) / (p[j] - p[j - 1]))
    zero = np.nonzero(p[i:] <= 1e-9 * pm)[0]
    return pm, float(x[i]), float(x[i + zero[0]] if len(zero) else x[-1])


def _reformation(prof):
    """JFO: first node from the inlet where the film is full (λ = 0); None without λ."""
    if "lam" not in prof:
        return None
    full = np.nonzero(prof["lam"] <= 1e-12)[0]
    return float(prof["x"][full[0]]) if len(full) else None


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


# --------------------------------------------------------------------------- slider case


class SliderCase:
    """Case ``reynolds-slider``; see the module docstring."""

    name = "reynolds-slider"
    doc = "rigid plane inclined slider bearing (1D Reynolds), vs the analytic solution"
    params = (
        Param("K", float, 1.0, "-", "inclination: inlet gap h0(1+K) over outlet gap h0",
              lower=-1.0),
        Param("L", float, 10.0, "mm", "slider length", lower=0.0),
        Param("h0", float, 0.01, "mm", "outlet (minimum) film thickness", lower=0.0),
        Param("U", float, 1000.0, "mm/s", "speed of the sliding plane (pad at rest)",
              lower=0.0),
        Param("mu", float, 1e-7, "MPa·s", "viscosity (1e-7 MPa·s = 0.1 Pa·s oil)", lower=0.0),
        Param("mesh", int, 200, "-", "number of elements", lower=2, upper=10**7, closed=True),
        Param("degree", int, 1, "-", "Lagrange degree of the pressure", choices=(1, 2)),
    )

    @staticmethod
    def validate(v):
        """Parameter ranges are checked by :class:`Param`; nothing else to check."""

    @staticmethod
    def build(v, comm=MPI.COMM_WORLD):
        """Build the :class:`Reynolds1D` problem of the slider (not solved)."""
        K, L, h0 = v["K"], v["L"], v["h0"]
        return Reynolds1D(comm, 0.0, L, v["mesh"], v["degree"],
                          lambda x: h0 * (1 + K - K * x / L), 0.5 * v["U"], v["mu"])

    @classmethod
    def run(cls, v, record, progress=None, verbose=False):
        """Solve, then record load, peak pressure and the L2 error against the analytic p."""
        prob = cls.build(v)
        record.data["num_dofs"] = prob.solver.num_dofs
        try:
            report = prob.solve(verbose=verbose)
        except NewtonDivergence as err:
            err.problem = prob
            raise
        record.data["newton_iterations"].append([report.iterations])
        record.data["newton_residuals"] = [float(r) for r in report.residuals]
        if progress is not None:
            progress.update(1)
        K, L, h0, U, mu = (v[k] for k in ("K", "L", "h0", "U", "mu"))
        ref = slider_reference(K, L, h0, U, mu)
        load = prob.integral(prob.p)
        p_ex = slider_pressure(ufl.SpatialCoordinate(prob.mesh)[0], K, L, h0, U, mu)
        err = math.sqrt(prob.integral((prob.p - p_ex) ** 2))
        nrm = math.sqrt(prob.integral(p_ex**2))
        prof = prob.profile()
        peak = None
        if prob.comm.rank == 0:
            i = int(np.argmax(np.abs(prof["p"])))
            peak = (float(prof["p"][i]), float(prof["x"][i]))
            record.profile = {"x": prof["x"], "p": prof["p"], "h": prof["h"], "K": K, "L": L,
                              "h0": h0, "U": U, "mu": mu}
        pm, xm = prob.comm.bcast(peak, root=0)
        record.result("load_per_width", load, "N/mm")
        record.result("analytic_load_per_width", ref["load"], "N/mm")
        record.result("p_max", pm, "MPa")
        record.result("analytic_p_max", ref["p_max"], "MPa")
        record.result("x_p_max", xm, "mm")
        record.result("analytic_x_p_max", ref["x_p_max"], "mm")

        def rel(a, b):
            return a / b - 1 if b != 0 else None

        record.result("load_rel_error", rel(load, ref["load"]))
        record.result("p_max_rel_error", rel(pm, ref["p_max"]))
        record.result("pressure_l2_error", err, "MPa·mm^0.5")
        record.result("pressure_rel_l2_error", err / nrm if nrm > 0 else None)
        return prob

    @staticmethod
    def vtx_fields(prob):
        """Pressure and film thickness on the interval mesh."""
        return {"reynolds": [prob.p, prob.h_fun]}

    @staticmethod
    def plot(profile, outdir):
        """Pressure against the analytic solution and film thickness (``pressure.png``)."""
        plt = _pyplot()
        pr = profile
        ref = slider_reference(pr["K"], pr["L"], pr["h0"], pr["U"], pr["mu"])
        xf = np.linspace(0, pr["L"], 400)
        fig, (ax, axh) = plt.subplots(2, 1, figsize=(6, 5.5), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 1]})
        ax.plot(xf, ref["pressure"](xf), "k-", label="analytic")
        step = max(1, len(pr["x"]) // 60)
        ax.plot(pr["x"][::step], pr["p"][::step], "o", ms=3, label="tribofx (nodal)")
        ax.set_ylabel("pressure p (MPa)")
        ax.legend()
        ax.grid(alpha=0.3)
        axh.plot(pr["x"], 1e3 * pr["h"], "C1-")
        axh.set_ylabel("h (µm)")
        axh.set_xlabel("x (mm)")
        axh.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(outdir / "pressure.png", dpi=120)
        plt.close(fig)


# --------------------------------------------------------------------------- cylinder case


class CylinderCase:
    """Case ``reynolds-cylinder``; see the module docstring."""

    name = "reynolds-cylinder"
    doc = ("rigid cylinder on a rigid plane (1D Reynolds) with cavitation none|penalty|jfo, "
           "vs half-Sommerfeld and Swift–Stieber")
    params = (
        Param("R", float, 10.0, "mm", "cylinder radius", lower=0.0),
        Param("h0", float, 0.01, "mm", "minimum film thickness", lower=0.0),
        Param("um", float, 1000.0, "mm/s", "mean entrainment speed (u1 + u2)/2", lower=0.0),
        Param("mu", float, 1e-7, "MPa·s", "viscosity (1e-7 MPa·s = 0.1 Pa·s oil)", lower=0.0),
        Param("x_in", float, -2.0, "mm", "inlet position (p = 0)", upper=0.0),
        Param("x_out", float, 2.0, "mm", "outlet position", lower=0.0),
        Param("cavitation", str, "penalty", "-", "cavitation model",
              choices=("none", "penalty", "jfo")),
        Param("supg", bool, True, "-", "SUPG stabilisation (Remark 3.2)"),
        Param("mesh", int, 400, "-", "number of elements", lower=2, upper=10**7, closed=True),
        Param("degree", int, 1, "-", "Lagrange degree of p (jfo: 1 only)", choices=(1, 2)),
        Param("inlet_void", float, 0.0, "-",
              "void fraction λ of the supplied film at x_in (jfo; 0: fully flooded, "
              "> 0: starved inlet)", lower=0.0, upper=1.0, closed=True),
        Param("penalty", float, 1e-6, "-",
              "relative penalty ε/ε_ref, ε_ref = 12 μ ℓ²/h0³ (MPa·s/mm), ℓ = √(2 R h0)",
              lower=0.0),
    )

    @staticmethod
    def scales(v):
        """Contact length ℓ = √(2Rh0) (mm), pressure scale 12μu_mℓ/h0² (MPa), ε (MPa·s/mm)."""
        ell = math.sqrt(2 * v["R"] * v["h0"])
        p_s = 12 * v["mu"] * v["um"] * ell / v["h0"] ** 2
        eps = v["penalty"] * 12 * v["mu"] * ell**2 / v["h0"] ** 3
        return ell, p_s, eps

    @classmethod
    def validate(cls, v):
        """Check the interval and, with cavitation, that the outlet lies past the rupture."""
        if not v["x_in"] < v["x_out"]:
            raise InputError(f"x_in = {v['x_in']} mm must be < x_out = {v['x_out']} mm")
        if v["cavitation"] == "jfo" and v["degree"] != 1:
            raise InputError("cavitation=jfo needs degree=1 (nodal complementarity)")
        if v["inlet_void"] > 0 and v["cavitation"] != "jfo":
            raise InputError("inlet_void > 0 (starved inlet) needs cavitation=jfo")
        if v["cavitation"] != "none":
            try:
                refs = cylinder_references(v["R"], v["h0"], v["um"], v["mu"], v["x_in"],
                                           v["x_out"], n=20_000, inlet_void=v["inlet_void"])
            except ValueError as err:
                raise InputError(str(err)) from None
            xr = refs["swift_stieber"]["x_rupture"]
            if v["x_out"] < xr + 0.02 * (v["x_out"] - v["x_in"]):
                raise InputError(f"x_out = {v['x_out']} mm must lie downstream of the "
                                 f"cavitation boundary (Swift–Stieber x_r = {xr:.4g} mm)")

    @staticmethod
    def levels(n, coarsest=50):
        """Element counts of the nested iteration: n/2^k, ..., n/2, n with n/2^k ≥ coarsest.

        Each level starts from the solution of the previous one, so that the
        semismooth Newton iteration only moves the free boundaries by about one
        coarse element (a primal active-set iteration moves them by about one
        node per iteration).
        """
        out = [n]
        while out[0] // 2 >= coarsest:
            out.insert(0, out[0] // 2)
        return out

    @classmethod
    def build(cls, v, comm=MPI.COMM_WORLD):
        """Build the :class:`Reynolds1D` problem of the cylinder (not solved)."""
        R, h0 = v["R"], v["h0"]
        _, p_s, eps = cls.scales(v)
        prob = Reynolds1D(comm, v["x_in"], v["x_out"], v["mesh"], v["degree"],
                          lambda x: h0 + x**2 / (2 * R), v["um"], v["mu"],
                          cavitation=v["cavitation"], supg=v["supg"], p_c=p_s, eps=eps,
                          q_ref=h0 * v["um"], lam_in=v["inlet_void"])
        if v["cavitation"] == "jfo":
            prob.jfo_initial_guess()
        return prob

    @classmethod
    def run(cls, v, record, progress=None, verbose=False):
        """Solve and record load, peak, rupture point and fluxes against the references."""
        levels = cls.levels(v["mesh"])
        its, prev, prob = [], None, None
        try:
            for n in levels:
                prob = cls.build(dict(v, mesh=n))
                if prev is not None:
                    prob.set_from_profile(prev)
                report = prob.solve(verbose=verbose)
                its.append(report.iterations)
                prev = prob.comm.bcast(prob.profile(), root=0) if n != levels[-1] else None
        except NewtonDivergence as err:
            err.problem = prob
            raise
        record.data["num_dofs"] = prob.solver.num_dofs
        record.data["mesh_levels"] = levels
        record.data["newton_iterations"].append(its)
        record.data["newton_residuals"] = [float(r) for r in report.residuals]
        if progress is not None:
            progress.update(1)
        cls._report(prob, v, record)
        return prob

    @classmethod
    def _report(cls, prob, v, record):
        cav = v["cavitation"]
        ell, p_s, eps = cls.scales(v)
        refs = cylinder_references(v["R"], v["h0"], v["um"], v["mu"], v["x_in"], v["x_out"],
                                   inlet_void=v["inlet_void"])
        p = prob.p
        load = prob.integral(ufl.max_value(p, 0) if cav == "none" else p)
        q_in, q_out = prob.consistent_fluxes()
        prof = prob.profile()
        peak = None
        if prob.comm.rank == 0:
            peak = _peak_and_rupture(prof, crossing=(cav == "none"))
            peak = (*peak, _reformation(prof))
            record.profile = dict(prof, cavitation=cav, refs={
                k: {"x": r["x"][::50], "p": r["p"][::50], "x_rupture": r["x_rupture"]}
                for k, r in refs.items()})
        pm, xm, xr, xf = prob.comm.bcast(peak, root=0)
        record.result("load_per_length", load, "N/mm")
        record.result("p_max", pm, "MPa")
        record.result("x_p_max", xm, "mm")
        record.result("x_rupture", xr, "mm")
        if cav == "jfo":
            record.result("x_reformation", xf, "mm")
            record.result("swift_stieber_x_reformation", refs["swift_stieber"]["x_reformation"],
                          "mm")
        for key, r in refs.items():
            record.result(f"{key}_load_per_length", float(r["load"]), "N/mm")
            record.result(f"{key}_p_max", float(r["p_max"]), "MPa")
            record.result(f"{key}_x_p_max", float(r["x_p_max"]), "mm")
            record.result(f"{key}_x_rupture", float(r["x_rupture"]), "mm")
            record.result(f"{key}_flux", float(r["flux"]), "mm^2/s")
        ref = refs["half_sommerfeld" if cav == "none" else "swift_stieber"]
        record.result("reference", "half_sommerfeld" if cav == "none" else "swift_stieber")
        record.result("load_rel_error", float(load / ref["load"] - 1))
        record.result("p_max_rel_error", float(pm / ref["p_max"] - 1))
        record.result("flux_in", float(q_in), "mm^2/s")
        record.result("flux_out", float(q_out), "mm^2/s")
        record.result("mass_balance_rel_defect", float((q_out - q_in) / abs(q_in)))
        record.result("pressure_scale", p_s, "MPa")
        if cav == "penalty":
            record.result("penalty_epsilon", eps, "MPa·s/mm")
            record.result("p_min", prob.comm.allreduce(float(p.x.array.min(initial=0.0)),
                                                       op=MPI.MIN), "MPa")

    @staticmethod
    def vtx_fields(prob):
        """Pressure, film thickness (and void fraction for JFO) on the interval mesh."""
        fields = [prob.p, prob.h_fun] + ([prob.lam] if prob.lam is not None else [])
        return {"reynolds": fields}

    @staticmethod
    def plot(profile, outdir):
        """Pressure vs half-Sommerfeld / Swift–Stieber, film thickness, void fraction."""
        plt = _pyplot()
        pr = profile
        jfo = "lam" in pr
        n = 3 if jfo else 2
        fig, axes = plt.subplots(n, 1, figsize=(6.5, 2.2 + 2.0 * n), sharex=True,
                                 gridspec_kw={"height_ratios": [3] + [1] * (n - 1)})
        ax = axes[0]
        hs, ss = pr["refs"]["half_sommerfeld"], pr["refs"]["swift_stieber"]
        ax.plot(hs["x"], hs["p"], "k--", lw=1, label="half-Sommerfeld")
        ax.plot(ss["x"], ss["p"], "k-", lw=1, label="Swift–Stieber")
        ax.plot(pr["x"], pr["p"], "C0.-", ms=2, lw=0.8,
                label=f"tribofx (cavitation={pr['cavitation']})")
        ax.axvline(ss["x_rupture"], color="0.6", lw=0.5)
        ax.set_ylabel("pressure p (MPa)")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        axes[1].plot(pr["x"], 1e3 * pr["h"], "C1-")
        axes[1].set_ylabel("h (µm)")
        axes[1].set_yscale("log")
        axes[1].grid(alpha=0.3)
        if jfo:
            axes[2].plot(pr["x"], pr["lam"], "C2.-", ms=2, lw=0.8)
            axes[2].set_ylabel("void fraction λ")
            axes[2].grid(alpha=0.3)
        axes[-1].set_xlabel("x (mm)")
        fig.tight_layout()
        fig.savefig(outdir / "pressure.png", dpi=120)
        plt.close(fig)
