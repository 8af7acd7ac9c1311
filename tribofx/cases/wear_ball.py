"""Elastic ball on a rigid flat: quasi-steady-state sliding wear (chapter §5.2): ``wear-ball-flat``.

An elastic ball (radius R, neo-Hookean with E, ν; small strains here) is pressed
by a normal force F against a rigid plane z = 0 that slides by at speed V in the
x direction.  In the frame of the ball the ball material is at rest, the
deformation problem is a steady frictional contact problem (Eulerian slip,
eqs. 26–27: v_T = −V e_x, fixed direction, Coulomb μ: sliding everywhere in
contact), and the ball wears by the dissipation form of Archard's law (eqs.
13–14) Ẇ = K T_T·v_T, K = k/μ, i.e. Ẇ = k p V per unit area.  The shape
evolution (28) is integrated on the initial mesh by the implicit (θ = 1,
monolithic Newton in u, λ_N, λ_T, w, ζ) or explicit (θ = 0) scheme; see
:mod:`tribofx.wear_problem`.  A step that fails (Newton divergence or an
inverted cell) is halved (``max_cuts``) and the step size is doubled back as
soon as the time is aligned with the coarser step (substepping at the start).

Model: quarter ball (the lower hemisphere cut by the symmetry plane y = 0 that
contains the sliding direction), :func:`tribofx.meshes.wear_ball.quarter_ball`,
P1 tetrahedra of size h = a_H/(2·2^mesh) within r_fine = 1.25 a_T (a_T the
rigid-cap scar radius at T, at least 2 a_H) of the initial contact point, R/4
far away.  Loading (chapter: at the mid-plane, which moves vertically as a
rigid plane): in the ball frame the mid-plane z = R is clamped (u = 0, it also
supports the friction force and its moment) and the rigid flat is translated
vertically by δ (``approach``), found in every solve by an outer secant
iteration (:class:`ForceControl`, the Newton solve of the step inside) so that
the contact force of the half contact is F/2 to 10⁻⁸.  A uniform traction on a
free mid-plane is not used: the friction moment μ F R would tilt the ball.
Symmetry: u_y = 0, w_y = 0 on y = 0; the shape change has no normal motion on
the mid-plane (w_z = 0).

Parameters (chapter §5.2: R = 5 mm, E = 100 GPa, ν = 0.3, F = 100 N, Hertz
radius a_H = 0.15 mm, p₀ = 2.1 GPa, T = 1000 s, implicit Δt = 100 s).  Left
open by the chapter (Stupkiewicz 2013), chosen here: V = 10 mm/s (a typical
ball-on-disc sliding speed), μ = 0.4 (dry steel on steel, 0.3–0.5), k = 10⁻⁸
mm³/(N·mm) (mild-wear range of steels, 10⁻⁹–10⁻⁷), so that the sliding
distance s = V T = 10⁴ mm gives a scar of radius a = (4kFRs/π)^{1/4} = 0.50 mm
≈ 3.3 a_H and a uniform pressure of F/(πa²) ≈ 127 MPa at T.

Rigid-cap Archard law (the late-time reference,
:func:`tribofx.references.rigid_cap_radius`): once the scar radius a is well
beyond a_H the elastic approach (∼ a_H²/R) is small against the worn depth, the
worn surface is a plane and the ball wears as a rigid sphere truncated flat,
a(s) = (4kFRs/π)^{1/4}, at the uniform pressure F/(πa²).

Recorded per step: ``time``, ``wear_volume`` (full ball, mm³), ``max_wear_depth``,
``contact_radius`` (from the active contact area A of the half disc, √(2A/π)),
``scar_radius`` (√(2Rh − h²) from the max depth h, the flat-scar radius),
``pressure_ratio`` (max/min nodal pressure over the nodes within 0.7 of the
contact radius), ``approach`` (flat position δ, mm), ``newton_iterations``
(all trials of the force iteration), ``wear_rate_integral`` (full ball,
mm³/s), ``dt``; ``final_profile``: worn contact boundary along the symmetry
line y = 0 ([x, z] points, mm).
"""

import math
import time

import numpy as np
from mpi4py import MPI

from ..contact_problem import ContactSettings
from ..forms.hyperelastic import lame_parameters
from ..meshes.wear_ball import CONTACT, LOADED, SYMMETRY_Y, quarter_ball
from ..newton import NewtonDivergence
from ..obstacles import AnalyticObstacle
from ..params import InputError, Param
from ..references import composite_modulus, hertz, rigid_cap_depth, rigid_cap_radius
from ..wear_problem import WearProblem
from .wear import bisect_critical_step

# rigid_cap_radius is re-exported from tribofx.references
__all__ = ["ForceControl", "WearBallCase", "explicit_critical_step", "hertz_radius",
           "pressure_nonuniformity", "rigid_cap_radius", "shape_unknown_fraction"]

MODEL_FRACTION = 0.5  # the quarter ball carries half of the contact (and of the wear)


def hertz_radius(F, R, E, nu):
    """Hertz radius (mm) of the ball on the rigid flat; kept for existing callers.

    The formula is :func:`tribofx.references.hertz` (``hertz(F, R, E, nu).a``).
    """
    return hertz(F, R, E, nu).a


def shape_unknown_fraction(prob):
    """Fraction of the global unknowns that belong to the shape field w (and its multiplier ζ)."""
    def n(f):
        im = f.function_space.dofmap.index_map
        return im.size_global * f.function_space.dofmap.index_map_bs
    total = sum(n(f) for f in prob.unknowns)
    shape = n(prob.w) + n(prob.zeta)
    if prob.shape_solver is not None:  # explicit: separate shape solve
        total += shape
    return shape / total


def pressure_nonuniformity(prob):
    """Relative standard deviation of the nodal contact pressure over the inner scar.

    Area-weighted over the active nodes within 0.7 of the contact radius (the
    edge nodes carry partial lumped areas); 0 for a uniform pressure.
    """
    comm = prob.mesh.comm
    d = prob.nodal_contact_data()
    area = comm.allreduce(float(np.sum(d["weight"][d["active"]])), op=MPI.SUM)
    a_c = math.sqrt(2 * area / math.pi)
    r = np.linalg.norm(d["x"][:, :2], axis=1)
    sel = d["active"] & (r < 0.7 * a_c)
    w, p = d["weight"][sel], d["p"][sel]
    sw, swp, swp2 = (comm.allreduce(float(np.sum(x)), op=MPI.SUM) for x in (w, w * p, w * p * p))
    if sw <= 0:
        return math.inf
    mean = swp / sw
    return math.sqrt(max(swp2 / sw - mean * mean, 0.0)) / mean if mean > 0 else math.inf


def explicit_critical_step(v, t0, lo, hi, steps=5, iters=4, growth_tol=2.0,
                           comm=MPI.COMM_WORLD):
    """Largest stable explicit Δt (s) from a developed scar, by experiment (bisection).

    The implicit scheme (``v["dt"]``) runs to ``t0`` on the mesh of ``v``; its
    state is copied into an explicit problem on the same mesh, which takes
    ``steps`` steps of Δt.  Wear evens out the pressure (the continuous
    problem is dissipative): an unstable Δt amplifies the highest mode
    geometrically, a stable one leaves the pressure nonuniformity
    (:func:`pressure_nonuniformity`) near its value at t0 (the implicit state
    at t0 is not exactly on the accurate path, so it may rebound by a few per
    cent).  Δt counts as stable iff the nonuniformity after the steps is at
    most ``growth_tol`` times the one at t0 and no step fails (Newton
    divergence, inverted mesh).
    Bisection on log Δt in [lo, hi] (lo stable, hi unstable, both checked).
    Returns ``(dt_cr, probe)``, ``probe`` the list of (Δt, nonuniformity ratio).
    """
    class _Rec:
        def __init__(self):
            self.data = {"newton_iterations": [], "results": {}}
            self.profile = None

        def result(self, key, value, unit="-"):
            self.data["results"][key] = value

    rec = _Rec()
    cls = WearBallCase
    cls.run({**v, "scheme": "implicit"}, rec, comm=comm, t_stop=t0)
    start = rec.problem.state()
    s0 = pressure_nonuniformity(rec.problem)
    prob = cls.build({**v, "scheme": "explicit"}, comm=comm)
    if not np.array_equal(prob.mesh.geometry.x, rec.problem.mesh.geometry.x):
        raise RuntimeError("rebuilt mesh differs from the implicit run's: cannot restore its state")
    ctrl = ForceControl(prob, v)
    probe = []

    def growth(dt):
        prob.restore(start)
        try:
            for _ in range(steps):
                ctrl.step(dt)
        except NewtonDivergence:
            probe.append((dt, math.inf))
            return math.inf
        g = pressure_nonuniformity(prob) / s0
        probe.append((dt, g))
        return g

    return bisect_critical_step(growth, lo, hi, iters, tol=growth_tol, probe=probe), probe


class ForceControl:
    """Position δ of the rigid flat (obstacle offset along z) that carries the force F/2.

    In the ball frame the mid-plane is clamped and the flat is pushed up by δ
    (equivalently the mid-plane moves down by δ as a rigid plane, chapter §5.2).
    :meth:`solve` is an outer secant iteration on δ around the Newton solve of
    the problem (implicit: the coupled wear step), started from the predictor
    :meth:`predicted_position` and the stiffness estimate dF/dδ ≈ E* a of the half contact
    (a the current contact radius); it stops at |F_z − F/2| ≤ rtol F/2.
    """

    def __init__(self, prob, v, rtol=1e-8, max_trials=12):
        self.prob, self.v = prob, v
        self.target = MODEL_FRACTION * v["F"]
        self.Es = composite_modulus(v["E"], v["nu"])
        self.rtol, self.max_trials = rtol, max_trials
        self.trials = []

    @property
    def delta(self):
        """Current position of the flat (mm, positive towards the ball)."""
        return float(self.prob.obstacle.offset.value[2])

    def _slope(self):
        """Stiffness estimate dF/dδ of the half contact (N/mm).

        Flat punch of radius a: compliance πa/(2E*) per unit pressure, in series
        (implicit step) with the wear compliance k V Δt.
        """
        area, _ = self.prob.contact_measures()
        a = max(math.sqrt(2 * area / math.pi),
                hertz(self.v["F"], self.v["R"], self.v["E"], self.v["nu"]).a)
        c_wear = self.v["k"] * self.v["V"] * float(self.prob.dt.value) \
            if self.prob.scheme == "implicit" else 0.0
        return 0.5 * math.pi * a * a / (math.pi * a / (2 * self.Es) + c_wear)

    def predicted_position(self, dt):
        """Position of the flat after Δt by the rigid-cap wear-depth increment (predictor).

        Computed from the state at step entry; the flat is not moved, so the explicit
        scheme's wear rate is that of the known state n (θ = 0).
        """
        v, comm = self.v, self.prob.mesh.comm
        d = self.prob.nodal_shape_data()
        h = comm.allreduce(float(np.max(d["depth"], initial=0.0)), op=MPI.MAX)
        # rigid cap: h² ∝ s, so sliding V Δt more adds rigid_cap_depth(V Δt)² to h²
        dh2 = float(rigid_cap_depth(v["k"], v["F"], v["R"], v["V"] * dt)) ** 2
        return self.delta + math.sqrt(h * h + dh2) - h

    def step(self, dt, verbose=False):
        """One wear step Δt at the prescribed force; returns the Newton reports.

        The secant on δ starts from :meth:`predicted_position` and runs inside
        :meth:`WearProblem.step` (after the explicit shape update), so a failed
        step restores the flat together with the rest of the state at entry.
        """
        start = self.predicted_position(dt)
        return self.prob.step(dt, verbose=verbose,
                              solve=lambda vb: self.solve(vb, start=start))

    def solve(self, verbose=False, start=None):
        """Outer secant iteration on δ from ``start`` (default: the current δ); Newton reports."""
        prob = self.prob
        reports, trials = [], []
        slope = self._slope()
        d = self.delta if start is None else start
        for _ in range(self.max_trials):
            prob.obstacle.offset.value[2] = d
            reports.append(prob.solver.solve(verbose=verbose))
            f = float(prob.contact_force()[2])
            trials.append((d, f))
            if abs(f - self.target) <= self.rtol * self.target:
                self.trials.append(len(trials))
                return reports
            if len(trials) >= 2 and trials[-1][1] != trials[-2][1]:
                s = (trials[-1][1] - trials[-2][1]) / (trials[-1][0] - trials[-2][0])
                slope = s if s > 0 else self._slope()
            d = d + (self.target - f) / slope
        raise NewtonDivergence(f"force control: F/2 = {self.target:g} N not reached in "
                               f"{self.max_trials} trials (last {trials[-1][1]:.6g} N)")

    def initial(self, verbose=False, max_ramp=4):
        """Unworn contact under F from the Hertz approach a_H²/R; returns the Newton iterations.

        If the full approach fails, the flat is brought up in 2, 4, … steps first.
        """
        v = self.v
        delta = hertz(v["F"], v["R"], v["E"], v["nu"]).delta
        saved = self.prob.state()
        for level in range(max_ramp):
            self.prob.restore(saved)
            n = 2**level
            its = 0
            try:
                for i in range(1, n):
                    self.prob.obstacle.offset.value[2] = delta * i / n
                    its += self.prob.solver.solve(verbose=verbose).iterations
                self.prob.obstacle.offset.value[2] = delta
                its += sum(r.iterations for r in self.solve(verbose))
            except NewtonDivergence:
                continue
            self.prob.commit()
            return its
        raise NewtonDivergence("initial contact solve failed")


class WearBallCase:
    """Case ``wear-ball-flat``; see the module docstring."""

    name = "wear-ball-flat"
    doc = "elastic ball worn by a sliding rigid flat, quasi-steady state, quarter model (§5.2)"
    params = (
        Param("scheme", str, "implicit", "-", "θ-scheme: explicit (θ=0) or implicit (θ=1)",
              choices=("explicit", "implicit")),
        Param("dt", float, 100.0, "s", "time step Δt", lower=0.0),
        Param("T", float, 1000.0, "s", "end time", lower=0.0),
        Param("k", float, 1e-8, "mm^3/(N*mm)", "Archard coefficient (rate = k p V)",
              lower=0.0, closed=True),
        Param("V", float, 10.0, "mm/s", "sliding speed of the rigid flat", lower=0.0),
        Param("E", float, 1e5, "MPa", "Young's modulus of the ball", lower=0.0),
        Param("nu", float, 0.3, "-", "Poisson's ratio", lower=-1.0, upper=0.5),
        Param("R", float, 5.0, "mm", "ball radius", lower=0.0),
        Param("F", float, 100.0, "N", "normal force on the full ball", lower=0.0),
        Param("friction", float, 0.4, "-", "Coulomb coefficient μ (K = k/μ)", lower=0.0),
        Param("mesh", int, 0, "-",
              "refinement level: contact-zone element size a_H/(2·2^mesh)", lower=0, upper=3,
              closed=True),
        Param("max_cuts", int, 8, "-", "step halvings allowed per step", lower=0, upper=20,
              closed=True),
    )

    @staticmethod
    def validate(v):
        """Check cross-parameter consistency."""
        if v["dt"] > v["T"]:
            raise InputError(f"time step {v['dt']} s exceeds T = {v['T']} s")
        aH = hertz(v["F"], v["R"], v["E"], v["nu"]).a
        if aH > 0.2 * v["R"]:
            raise InputError(f"load too large for small strains: a_H/R = {aH / v['R']:.2f}")
        aT = WearBallCase.mesh_sizes(v)[2] / 1.25
        if aT > 0.6 * v["R"]:
            raise InputError(f"scar radius at T ({aT:.3g} mm) beyond 0.6 R: reduce k, V or T")

    @staticmethod
    def mesh_sizes(v):
        """(h_fine, h_coarse, r_fine) in mm; see the module docstring."""
        aH = hertz(v["F"], v["R"], v["E"], v["nu"]).a
        aT = max(float(rigid_cap_radius(v["k"], v["F"], v["R"], v["V"] * v["T"])), 2 * aH)
        return aH / (2 * 2 ** v["mesh"]), v["R"] / 4, 1.25 * aT

    @staticmethod
    def settings(v, h):
        """Steady (Eulerian) Coulomb sliding: the ball is at rest, the flat moves at V e_x."""
        return ContactSettings(rho_n=v["E"] / h, friction=v["friction"], slip="eulerian",
                               V=(0.0, 0.0, 0.0), V_master=(v["V"], 0.0, 0.0), dtau=1.0)

    @classmethod
    def build(cls, v, comm=MPI.COMM_WORLD, newton_kw=None):
        """Mesh and :class:`WearProblem` of the case (not yet loaded); returns the problem."""
        h_fine, h_coarse, r_fine = cls.mesh_sizes(v)
        msh, ft = quarter_ball(v["R"], h_fine, h_coarse, r_fine, comm)
        mu, lmbda = lame_parameters(v["E"], v["nu"])

        def factory(m, Vs):
            return AnalyticObstacle(Vs.mesh, "plane", np.zeros(3), normal=np.array([0.0, 0, 1]))

        prob = WearProblem(msh, ft, CONTACT, "3d", "neo-hookean", {"mu": mu, "lmbda": lmbda},
                           factory, cls.settings(v, h_fine), k=v["k"], slip_speed=v["V"],
                           scheme=v["scheme"], aux_E=v["E"])
        # the mid-plane is the rigid holder: clamped in the ball frame, the flat moves
        prob.add_dirichlet(LOADED, np.zeros(3))
        prob.add_dirichlet(SYMMETRY_Y, 0.0, component=1)
        prob.add_shape_dirichlet(SYMMETRY_Y, 1)
        prob.add_shape_dirichlet(LOADED, 2)
        prob.finalize(**(newton_kw or {}))
        prob.h_fine = h_fine
        return prob

    @staticmethod
    def measures(prob, v):
        """Contact radius, flat-scar radius, pressure ratio, max depth, full-ball worn volume."""
        comm = prob.mesh.comm
        d = prob.nodal_shape_data()
        area = comm.allreduce(float(np.sum(d["weight"][d["active"]])), op=MPI.SUM)
        a_c = math.sqrt(2 * area / math.pi)
        h = comm.allreduce(float(np.max(d["depth"], initial=0.0)), op=MPI.MAX)
        a_s = math.sqrt(max(2 * v["R"] * h - h * h, 0.0))
        r = np.linalg.norm(d["x"][:, :2], axis=1)
        inner = d["active"] & (r < 0.7 * a_c)
        pmax = comm.allreduce(float(np.max(d["p"][inner], initial=0.0)), op=MPI.MAX)
        pmin = comm.allreduce(float(np.min(d["p"][inner], initial=np.inf)), op=MPI.MIN)
        return {"contact_radius": a_c, "scar_radius": a_s, "max_wear_depth": h,
                "pressure_ratio": pmax / pmin if pmin > 0 else math.inf,
                "wear_volume": prob.worn_volume() / MODEL_FRACTION,
                "wear_rate_integral": prob.wear_rate_integral() / MODEL_FRACTION}

    @staticmethod
    def symmetry_line(prob, v):
        """Worn and deformed contact boundary along y = 0 near the contact, on rank 0 (else None).

        Returns a dict of arrays sorted by X̂_x: X_worn, x (deformed), p (pressure).
        """
        d = prob.gather_shape()
        if prob.mesh.comm.rank != 0:
            return None
        r_fine = WearBallCase.mesh_sizes(v)[2]
        sel = (np.abs(d["X_hat"][:, 1]) < 1e-9 * v["R"]) & (d["X_hat"][:, 2] < 0.5 * v["R"]) \
            & (np.abs(d["X_hat"][:, 0]) <= 2 * r_fine)
        return {"X_worn": d["X_worn"][sel], "x": d["x"][sel], "p": d["p"][sel]}

    @staticmethod
    def contact_plane(prob):
        """(x, y, p) of all contact-surface nodes within the active zone, on rank 0 (else None)."""
        d = prob.gather_shape()
        if prob.mesh.comm.rank != 0:
            return None
        a = d["active"]
        return np.column_stack([d["x"][a, 0], d["x"][a, 1], d["p"][a]])

    @classmethod
    def run(cls, v, record, progress=None, verbose=False, newton_kw=None, on_step=None,
            comm=MPI.COMM_WORLD, t_stop=None):
        """Integrate the wear of the ball from t = 0 to T; record per-step histories.

        ``on_step(prob, t, reports)``, if given, is called after every accepted step;
        ``t_stop`` < T ends the run early (on the mesh built for T).
        """
        t_wall = time.perf_counter()
        prob = cls.build(v, comm=comm, newton_kw=newton_kw)
        ctrl = ForceControl(prob, v)
        record.data["num_dofs"] = prob.solver.num_dofs
        if prob.shape_solver is not None:
            record.data["num_dofs_shape"] = prob.shape_solver.num_dofs
        record.result("shape_unknown_fraction", shape_unknown_fraction(prob), "-")
        record.problem = prob
        record.control = ctrl
        comm = prob.mesh.comm
        record.result("h_contact_zone", prob.h_fine, "mm")
        keys = ("time", "dt", "approach", "wear_volume", "max_wear_depth", "contact_radius",
                "scar_radius", "pressure_ratio", "newton_iterations", "wear_rate_integral")
        hist = {k: [] for k in keys}
        state = {"profiles": [], "initial_plane": None}

        def log(t, its, dt):
            m = cls.measures(prob, v)
            hist["time"].append(t)
            hist["dt"].append(dt)
            hist["newton_iterations"].append(its)
            hist["approach"].append(ctrl.delta)
            for k in m:
                hist[k].append(m[k])
            record.data["newton_iterations"].append(its)
            line = cls.symmetry_line(prob, v)
            if comm.rank == 0:
                state["profiles"].append((t, line["X_worn"][:, [0, 2]].tolist()))

        its0 = ctrl.initial(verbose)
        state["initial_plane"] = cls.contact_plane(prob)
        log(0.0, its0, 0.0)
        t, T, dt = 0.0, v["T"] if t_stop is None else min(t_stop, v["T"]), v["dt"]
        cuts = 0
        try:
            while t < T * (1 - 1e-12):
                h = min(dt / 2**cuts, T - t)
                try:
                    reports = ctrl.step(h, verbose=verbose)
                except NewtonDivergence:
                    cuts += 1
                    if cuts > v["max_cuts"]:
                        raise
                    continue
                t += h
                its = int(sum(r.iterations for r in reports))
                log(t, its, h)
                record.data.setdefault("newton_residuals", []).append(
                    [float(x) for x in reports[-1].residuals])
                record.data.setdefault("newton_residuals_all", []).append(
                    [[float(x) for x in r.residuals] for r in reports])
                if on_step is not None:
                    on_step(prob, t, reports)
                # substepping: double the step back once t is aligned with the coarser step
                while cuts > 0 and abs(t / (dt / 2 ** (cuts - 1))
                                       - round(t / (dt / 2 ** (cuts - 1)))) < 1e-9:
                    cuts -= 1
                if progress is not None:
                    progress.update(1)
        except NewtonDivergence as err:
            err.problem = prob
            raise
        finally:
            cls._report(prob, v, record, hist, state, time.perf_counter() - t_wall)
        return prob

    @staticmethod
    def late_time_exponent(time_s, radius, V, t_min):
        """Least-squares slope of log a against log s = V t over the steps with t ≥ t_min."""
        t = np.asarray(time_s, dtype=float)
        a = np.asarray(radius, dtype=float)
        sel = t >= t_min
        if np.count_nonzero(sel) < 2:
            return math.nan
        return float(np.polyfit(np.log(V * t[sel]), np.log(a[sel]), 1)[0])

    @classmethod
    def _report(cls, prob, v, record, hist, state, wall):
        units = {"time": "s", "dt": "s", "approach": "mm (flat position)",
                 "wear_volume": "mm^3 (full ball)",
                 "max_wear_depth": "mm", "contact_radius": "mm", "scar_radius": "mm",
                 "pressure_ratio": "-", "newton_iterations": "-",
                 "wear_rate_integral": "mm^3/s (full ball)"}
        for key, vals in hist.items():
            record.result(key, vals, units[key])
        comm = prob.mesh.comm
        record.result("wall_time", comm.allreduce(wall, op=MPI.MAX), "s")
        record.result("steps", len(hist["time"]) - 1, "-")
        s = v["V"] * np.asarray(hist["time"])
        record.result("rigid_cap_radius", rigid_cap_radius(v["k"], v["F"], v["R"], s).tolist(),
                      "mm")
        record.result("archard_volume", (v["k"] * v["F"] * s).tolist(), "mm^3 (k F V t)")
        t_late = 0.4 * v["T"]
        for key in ("contact_radius", "scar_radius"):
            record.result(f"{key}_exponent_late",
                          cls.late_time_exponent(hist["time"], hist[key], v["V"], t_late), "-")
        line = cls.symmetry_line(prob, v)
        plane = cls.contact_plane(prob)
        if comm.rank == 0:
            record.result("final_profile", line["X_worn"][:, [0, 2]].tolist(),
                          "mm ([x, z] of the worn boundary on y = 0)")
            record.result("final_profile_deformed", line["x"][:, [0, 2]].tolist(), "mm")
            record.result("final_pressure_symmetry_line", line["p"].tolist(), "MPa")
            record.profile = {**hist, "profiles": state["profiles"],
                              "initial_plane": state["initial_plane"], "final_plane": plane,
                              "scheme": v["scheme"], "dt": v["dt"], "R": v["R"], "k": v["k"],
                              "F": v["F"], "V": v["V"]}

    @staticmethod
    def vtx_fields(prob):
        """Fields for ParaView: displacement and shape change (bulk), contact multiplier."""
        return {"displacement": [prob.u, prob.w], "contact": [prob.lam_n]}

    @staticmethod
    def plot(profile, outdir):
        """Plot ``pressure.png``, ``profiles.png`` and ``scar.png``.

        Initial/final pressure on the contact plane, worn profile along y = 0 at
        every step, scar radius against the rigid-cap law.
        """
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, axes = plt.subplots(1, 2, figsize=(10, 4))
        for ax, key, title in zip(axes, ("initial_plane", "final_plane"),
                                  ("t = 0", f"t = {profile['time'][-1]:g} s")):
            pts = np.asarray(profile[key])
            if len(pts) >= 3:
                # mirror the half model about y = 0
                x = np.concatenate([pts[:, 0], pts[:, 0]])
                y = np.concatenate([pts[:, 1], -pts[:, 1]])
                p = np.concatenate([pts[:, 2], pts[:, 2]])
                sc = ax.tricontourf(x, y, p, levels=20, cmap="viridis")
                fig.colorbar(sc, ax=ax, label="contact pressure (MPa)")
                ax.plot(pts[:, 0], pts[:, 1], "k.", ms=2)
            ax.set_aspect("equal")
            ax.set_xlabel("x (mm, sliding direction)")
            ax.set_ylabel("y (mm)")
            ax.set_title(f"contact pressure, {title}")
        fig.tight_layout()
        fig.savefig(outdir / "pressure.png", dpi=120)
        plt.close(fig)

        fig, ax = plt.subplots(figsize=(7, 3.5))
        for t, pts in profile["profiles"]:
            p = np.asarray(pts)
            ax.plot(p[:, 0], p[:, 1] * 1e3, lw=1, label=f"t = {t:g} s")
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("worn z (µm)")
        ax.set_title(f"worn ball profile on y = 0, {profile['scheme']} scheme")
        if len(profile["profiles"]) <= 14:
            ax.legend(fontsize=6, ncol=2)
        fig.tight_layout()
        fig.savefig(outdir / "profiles.png", dpi=120)
        plt.close(fig)

        t = np.asarray(profile["time"])[1:]
        s = profile["V"] * t
        fig, ax = plt.subplots(figsize=(5, 4))
        ax.loglog(s, np.asarray(profile["contact_radius"])[1:], "o", label="contact radius")
        ax.loglog(s, np.asarray(profile["scar_radius"])[1:], "s", label="flat-scar radius")
        ax.loglog(s, rigid_cap_radius(profile["k"], profile["F"], profile["R"], s), "k-",
                  label="(4kFRs/π)^{1/4}")
        ax.set_xlabel("sliding distance s (mm)")
        ax.set_ylabel("radius (mm)")
        ax.legend()
        fig.tight_layout()
        fig.savefig(outdir / "scar.png", dpi=120)
        plt.close(fig)
