"""Pin-on-flat finite wear (chapter §4.4, Figs. 2–4): case ``wear-pin``.

A neo-Hookean plane-strain pin of width W and height H with a rounded tip
(circular arc of radius R_tip through the lowest point) is pressed by a uniform
traction q on its top face onto a rigid plane y = 0 that slides at speed V.
Contact is frictionless; the lateral faces x = ±W/2 are constrained laterally
(u_x = 0) and free vertically.  Archard wear, nominal rate Ẇ = k p V (eq. 14
in pressure form), changes the shape of the tip; the shape evolution (28) is
integrated to t = T by the explicit (θ = 0) or implicit (θ = 1) scheme on the
initial mesh (see :mod:`tribofx.wear_problem`).

Default data (the chapter leaves them to Stupkiewicz 2013; chosen in its
spirit): W = H = 2 mm, R_tip = 4 mm (tip height 0.127 mm), q = 2 MPa
(4 N/mm), V = 10 mm/s, k = 5·10⁻⁶ mm³/(N·mm), T = 1000 s, so that the worn
area k q W V T = 0.2 mm² per mm (mean depth 0.1 mm) flattens most of the tip.
E = 640 MPa (small-deformation regime: initial Hertz half-width 0.17 mm) to
E = 10 MPa (finite deformation, full contact), ν = 0.3.  Options: ``law``
(nominal Ẇ = k p V, eq. 14, or spatial Ẇ = (k/J) p V, eqs. 15–16) and a wear
coefficient graded with the worn depth d, k(d) = k max(1 + k_grad d, 0).  The structured mesh
has n × n squares (split in triangles), n = 10·2^mesh.

Friction (``friction`` = μ > 0, eqs. 13–14): the wear rate is driven by the
frictional dissipation, Ẇ = (k/μ) T_T·v_T, which equals k p V in sliding.
``mode=steady``: steady sliding of the plane at V with the Eulerian slip
velocity (v = F V − V_plane, eqs. 26–27; the pin is at rest, so v_T = −V e_x).
``mode=cyclic`` (μ > 0 required): time-scale separation (§4.2, eqs. 21–23, the
reciprocating pin-on-flat test of §5.1): per slow step one fast reciprocating
cycle of the plane (peak-to-peak ``stroke`` 2A, ``fast_steps`` sub-steps, a
run-in stage from −A first, Lagrangian friction), wear increment accumulated
over the cycle and averaged, shape updated by the θ-scheme on the slow time (θ
= 0 ``explicit``, θ = 1 ``implicit`` by Picard iteration; see
:mod:`tribofx.time_scale`).  A slow step stands for ``cycles_per_step`` cycles,
Δt = cycles_per_step · 2 stroke / V (0: Δt = ``dt``).

``study=dt`` (Fig. 3 and Fig. 4 of the chapter): for the given E and each mesh
level of ``study_meshes`` (default: ``mesh``), the explicit and the implicit
scheme are run to T with every Δt of ``study_dts`` (default 200, 100, 50, 20,
10, 5 s), plus an implicit reference run with Δt = ``study_ref_dt`` (default
T/1280 = 0.78125 s, as in the chapter; ``study_ref=richardson``: 2 p(Δt_r) −
p(2 Δt_r) of two implicit runs instead).  The error of a run is the Euclidean
norm (as in the chapter) of the difference of the final worn nodal positions X̂ + w on
Γ̂_c from the reference (mm; the max nodal distance is also stored).  A run is
flagged unstable if it fails (Newton divergence or an inverted mesh at its
nominal Δt: explicit runs get no step cutting) or if its error is dominated by
the node-to-node alternating (checkerboard) mode, :func:`oscillation_ratio` of the
vertical error > ``OSCILLATION_TOL``, or (explicit) if Δt exceeds the critical
step Δt_cr of the mesh (:func:`explicit_critical_step`, also reported).  Writes ``error_vs_dt.png``,
``profiles.png`` and the ``study_*`` results in summary.json.
"""

import math
import time
from pathlib import Path

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from ..contact_problem import ContactSettings
from ..forms.hyperelastic import lame_parameters
from ..meshes.pin import CONTACT, SIDES, TOP, pin_body, tip_height
from ..newton import NewtonDivergence
from ..obstacles import AnalyticObstacle
from ..params import InputError, Param
from ..references import hertz
from ..time_scale import ReciprocatingCycle, TimeScaleDriver
from ..wear_problem import WearProblem

__all__ = ["WearPinCase", "checkerboard_amplitude", "explicit_critical_step",
           "oscillation_ratio", "run_dt_study", "solve_initial_contact"]

OSCILLATION_TOL = 0.7  # unstable: node-to-node oscillating part of the error > 70 %


def oscillation_ratio(err):
    """Share of the node-to-node alternating mode in a nodal error e_i (nodes sorted by X̂).

    ‖(e_{i−1} − 2 e_i + e_{i+1})/4‖ / ‖e_i‖ over the interior nodes: ≈ 1 for an
    alternating (checkerboard) error, O((h/L)²) for a smooth one.
    """
    err = np.asarray(err, dtype=float)
    hp = (err[:-2] - 2 * err[1:-1] + err[2:]) / 4
    den = np.linalg.norm(err[1:-1])
    return float(np.linalg.norm(hp) / den) if den > 0 else 0.0


def solve_initial_contact(prob, load, q, E, W, R, H, verbose=False, max_ramp=5):
    """First (unworn) contact solve under the full traction; ramps the load on failure.

    The initial guess translates the pin down by δ₀ ≈ a²/(2R) + qH/E (a the
    2D Hertz half-width, capped at W/2) so that the tip nodes start active.
    Returns the Newton iterations spent.
    """
    # 2D Hertz half-width of the tip (ν = 0.3 for the guess only), at most the pin width
    a = min(hertz(q * W, R, E, 0.3, line=True).a, W / 2) if R and not math.isinf(R) else 0
    delta0 = (a * a / (2 * R) if a else 0.0) + q * H / E
    saved = prob.state()
    its = 0
    for level in range(max_ramp):
        n = 2**level
        prob.restore(saved)
        prob.u.x.array.reshape(-1, 2)[:, 1] = -delta0 / n
        try:
            for i in range(1, n + 1):
                load.value = i / n
                if i > 1:
                    prob.u.x.array.reshape(-1, 2)[:, 1] -= delta0 / n
                its += prob.solve(verbose=verbose).iterations
            prob.commit()
            return its
        except NewtonDivergence:
            continue
    raise NewtonDivergence("initial contact solve failed after load ramping")


def _seed_checkerboard(prob, W, n, eps):
    """Add a wear-depth perturbation ε(−1)^i to the contact nodes x_i = −W/2 + i h of a flat pin."""
    X = prob.Vw.tabulate_dof_coordinates()
    on = np.isclose(X[:, 1], 0.0, atol=1e-9 * W)
    i = np.rint((X[on, 0] + W / 2) / (W / n)).astype(int)
    prob.w.x.array.reshape(-1, 2)[on, 1] += eps * (-1.0) ** i
    prob.w.x.scatter_forward()


def checkerboard_amplitude(prob):
    """Amplitude of the node-to-node alternating mode of the wear depth on Γ̂_c (mm).

    Projection of d_i − mean(d) onto (−1)^i − mean((−1)^i), nodes sorted by X̂;
    the same value on every rank.
    """
    d = prob.mesh.comm.bcast(prob.gather_shape(), root=0)
    depth = d["depth"] - np.mean(d["depth"])
    s = (-1.0) ** np.arange(len(depth))
    s -= s.mean()
    return float(depth @ s / (s @ s))


def explicit_critical_step(v, n, lo, hi, steps=3, iters=12, eps=1e-6):
    """Largest stable Δt (s) of the explicit scheme on an n × n flat-ended pin (eq. 31).

    The stability probe: the flat pin in the homogeneous state (parameters ``v``
    of ``wear-pin``, R_tip forced to 0) gets a node-to-node alternating wear-depth
    perturbation of amplitude ε (the highest mode the mesh carries, i.e. the
    first to go unstable), the contact problem is re-solved, and ``steps``
    explicit steps are taken.  Forward Euler multiplies that mode by g = 1 − Δt kV S
    per step (S: pressure per unit depth of the mode, ∝ E/h), so Δt is stable iff
    the amplitude does not grow, |a_steps| ≤ |a_0|; a Newton failure or inverted
    mesh also counts as unstable.  Bisection on log Δt in [lo, hi] (lo stable, hi
    unstable, both checked).  Returns ``(dt_cr, probe)`` with ``probe`` the list of
    (Δt, a_steps/a_0) evaluated.
    """
    v = {**v, "scheme": "explicit", "R_tip": 0.0}
    prob, load = WearPinCase.build(v, n=n)
    solve_initial_contact(prob, load, v["q"], v["E"], v["W"], math.inf, v["H"])
    _seed_checkerboard(prob, v["W"], n, eps)
    prob.solver.solve()
    prob.commit()
    start = prob.state()
    a0 = checkerboard_amplitude(prob)
    probe = []

    def growth(dt):
        prob.restore(start)
        try:
            for _ in range(steps):
                prob.step(dt)
        except NewtonDivergence:
            probe.append((dt, math.inf))
            return math.inf
        g = checkerboard_amplitude(prob) / a0
        probe.append((dt, g))
        return abs(g)

    dt_cr = bisect_critical_step(growth, lo, hi, iters, probe=probe)
    prob.restore(start)
    return dt_cr, probe


def bisect_critical_step(growth, lo, hi, iters, tol=1.0, probe=()):
    """Critical step by bisection on log Δt: ``growth(Δt) <= tol`` is stable.

    ``lo`` must be stable and ``hi`` unstable (both checked; ``probe``, the
    evaluations so far, goes into the error message).  Returns √(lo·hi) after
    ``iters`` halvings of the log-bracket.
    """
    if not growth(lo) <= tol or not growth(hi) > tol:
        raise ValueError(f"[{lo}, {hi}] s does not bracket the critical step: {list(probe)}")
    for _ in range(iters):
        mid = math.sqrt(lo * hi)
        if growth(mid) <= tol:
            lo = mid
        else:
            hi = mid
    return math.sqrt(lo * hi)


class WearPinCase:
    """Case ``wear-pin``; see the module docstring."""

    name = "wear-pin"
    doc = "plane-strain pin with rounded tip worn on a sliding rigid flat (§4.4)"
    params = (
        Param("scheme", str, "implicit", "-", "θ-scheme: explicit (θ=0) or implicit (θ=1)",
              choices=("explicit", "implicit")),
        Param("dt", float, 200.0, "s", "time step Δt", lower=0.0),
        Param("T", float, 1000.0, "s", "end time", lower=0.0),
        Param("k", float, 5e-6, "mm^3/(N*mm)", "Archard coefficient (rate = k p V)",
              lower=0.0, closed=True),
        Param("V", float, 10.0, "mm/s", "sliding speed of the rigid plane", lower=0.0,
              closed=True),
        Param("E", float, 640.0, "MPa", "Young's modulus", lower=0.0),
        Param("nu", float, 0.3, "-", "Poisson's ratio", lower=-1.0, upper=0.5),
        Param("mesh", int, 1, "-", "refinement level: n × n structured mesh, n = 10·2^mesh",
              lower=0, upper=4, closed=True),
        Param("q", float, 2.0, "MPa", "uniform traction on the top face", lower=0.0),
        Param("W", float, 2.0, "mm", "pin width", lower=0.0),
        Param("H", float, 2.0, "mm", "pin height", lower=0.0),
        Param("R_tip", float, 4.0, "mm", "tip radius (0: flat-ended punch)", lower=0.0,
              closed=True),
        Param("law", str, "nominal", "-", "Archard law: nominal (eq. 14) or spatial (eqs. 15-16)",
              choices=("nominal", "spatial")),
        Param("k_grad", float, 0.0, "1/mm",
              "depth gradient g of the wear coefficient, k(d) = k max(1 + g d, 0)"),
        Param("friction", float, 0.0, "-",
              "Coulomb coefficient μ (> 0: dissipation-driven wear, K = k/μ)",
              lower=0.0, closed=True),
        Param("mode", str, "steady", "-",
              "steady sliding (Eulerian slip) or cyclic (reciprocating, time-scale separation)",
              choices=("steady", "cyclic")),
        Param("stroke", float, 1.0, "mm", "cyclic: peak-to-peak stroke 2A of the flat",
              lower=0.0),
        Param("fast_steps", int, 8, "-", "cyclic: fast sub-steps per cycle (multiple of 4)",
              lower=4, upper=100000, closed=True),
        Param("cycles_per_step", float, 0.0, "-",
              "cyclic: cycles per slow step (0: Δt = dt)", lower=0.0, closed=True),
        Param("max_cuts", int, 6, "-", "step halvings allowed per step", lower=0, upper=20,
              closed=True),
        Param("study", str, "none", "-",
              "none: one run; dt: explicit and implicit error versus Δt study (Figs. 3-4)",
              choices=("none", "dt")),
        Param("study_dts", str, "200,100,50,20,10,5", "s",
              "study=dt: comma-separated time steps"),
        Param("study_meshes", str, "", "-",
              "study=dt: comma-separated mesh levels (n = 10·2^level; empty: mesh)"),
        Param("study_ref_dt", float, 0.78125, "s",
              "study=dt: time step of the implicit reference run", lower=0.0),
        Param("study_ref", str, "fine", "-",
              "study=dt: reference = implicit run at study_ref_dt (fine) or Richardson "
              "2 p(study_ref_dt) - p(2 study_ref_dt)", choices=("fine", "richardson")),
        Param("study_critical", bool, True, "-",
              "study=dt: also compute the explicit critical step of each mesh"),
    )

    @staticmethod
    def study_lists(v):
        """``(dts, mesh levels)`` of ``study=dt`` parsed from the comma-separated strings."""
        def split(text):
            return [t for t in text.replace(";", ",").split(",") if t.strip()]
        try:
            dts = [float(t) for t in split(v["study_dts"])]
            levels = [int(t) for t in split(v["study_meshes"])] or [v["mesh"]]
        except ValueError as err:
            raise InputError(f"study lists: {err}") from None
        return dts, levels

    @staticmethod
    def validate(v):
        """Check cross-parameter consistency."""
        R = v["R_tip"]
        if R and R < v["W"] / 2:
            raise InputError(f"R_tip = {R} mm must be 0 (flat) or >= W/2 = {v['W'] / 2} mm")
        if tip_height(v["W"] / 2, R) >= 0.5 * v["H"]:
            raise InputError("the rounded tip must be lower than half the pin height")
        if v["mode"] == "cyclic":
            if v["friction"] <= 0:
                raise InputError("mode=cyclic needs friction > 0 (Lagrangian Coulomb friction)")
            if v["fast_steps"] % 4:
                raise InputError(f"fast_steps = {v['fast_steps']} must be a multiple of 4")
            if v["V"] <= 0:
                raise InputError("mode=cyclic needs V > 0")
        if WearPinCase.slow_step(v) > v["T"]:
            raise InputError(f"time step {WearPinCase.slow_step(v)} s exceeds T = {v['T']} s")
        if v["study"] == "dt":
            dts, levels = WearPinCase.study_lists(v)
            if not dts or any(d <= 0 or d > v["T"] for d in dts):
                raise InputError(f"study_dts = {v['study_dts']!r}: need 0 < Δt <= T")
            if any(not 0 <= m <= 4 for m in levels):
                raise InputError(f"study_meshes = {v['study_meshes']!r}: levels 0..4")
            if v["mode"] != "steady":
                raise InputError("study=dt supports mode=steady only")
            r = v["study_ref_dt"] * (2 if v["study_ref"] == "richardson" else 1)
            if r > v["T"] or r >= min(dts):
                raise InputError("study_ref_dt must be below the study time steps")

    @staticmethod
    def slow_step(v):
        """Slow time step Δt (s): ``dt``, or cycles_per_step · 2 stroke / V in cyclic mode."""
        if v["mode"] == "cyclic" and v["cycles_per_step"] > 0:
            return v["cycles_per_step"] * 2 * v["stroke"] / v["V"]
        return v["dt"]

    @staticmethod
    def n_elements(v):
        """Elements per side of the structured mesh."""
        return 10 * 2 ** v["mesh"]

    @classmethod
    def build(cls, v, comm=MPI.COMM_WORLD, n=None, setup=None):
        """Mesh and :class:`WearProblem` of the case; returns ``(problem, load_factor)``.

        ``setup(prob)``, if given, is called before the forms are compiled (extra
        boundary conditions, e.g. in tests).
        """
        n = cls.n_elements(v) if n is None else n
        W, H = v["W"], v["H"]
        R = v["R_tip"] if v["R_tip"] > 0 else math.inf
        msh, ft = pin_body(W, H, R, n, comm)
        h = W / n
        mu, lmbda = lame_parameters(v["E"], v["nu"])

        def factory(m, Vs):
            return AnalyticObstacle(Vs.mesh, "plane", np.zeros(2), normal=np.array([0.0, 1.0]))

        prob = WearProblem(msh, ft, CONTACT, "plane_strain", "neo-hookean",
                           {"mu": mu, "lmbda": lmbda}, factory, cls.settings(v, h),
                           k=v["k"], slip_speed=v["V"], scheme=v["scheme"], aux_E=v["E"],
                           law=v["law"], k_grad=v["k_grad"], averaged=v["mode"] == "cyclic")
        load = fem.Constant(msh, 1.0)
        prob.add_traction(TOP, load * ufl.as_vector([0.0, -v["q"]]))
        prob.add_dirichlet(SIDES, 0.0, component=0)
        prob.add_shape_dirichlet(SIDES, 0)
        prob.add_shape_dirichlet(TOP, 1)
        if setup is not None:
            setup(prob)
        prob.finalize()
        return prob, load

    @staticmethod
    def settings(v, h):
        """Contact settings: frictionless, steady (Eulerian) or cyclic (Lagrangian) friction."""
        mu = v["friction"]
        if mu == 0:
            return ContactSettings(rho_n=v["E"] / h)
        if v["mode"] == "cyclic":
            return ContactSettings(rho_n=v["E"] / h, friction=mu, slip="lagrangian")
        # the pin is at rest (V = 0), the plane slides at V e_x: v_T = −V e_x, eq. 26
        return ContactSettings(rho_n=v["E"] / h, friction=mu, slip="eulerian", V=(0.0, 0.0),
                               V_master=(v["V"], 0.0), dtau=1.0)

    @classmethod
    def stepper(cls, prob, v):
        """Callable(Δt, verbose) advancing one slow step; returns the Newton iterations."""
        if v["mode"] == "cyclic":
            cycle = ReciprocatingCycle(v["stroke"], v["fast_steps"], v["V"])
            theta = 1.0 if v["scheme"] == "implicit" else 0.0
            return TimeScaleDriver(prob, cycle, theta=theta).step

        def step(dt, verbose=False):
            reports = prob.step(dt, verbose=verbose)
            step.last = reports
            return int(sum(r.iterations for r in reports))
        step.last = None
        return step

    @staticmethod
    def vtx_fields(prob):
        """Fields for ParaView: displacement and shape change (bulk), contact multiplier."""
        return {"displacement": [prob.u, prob.w], "contact": [prob.lam_n]}

    @staticmethod
    def plot(profile, outdir):
        """Worn profiles at every step (``profiles.png``) and wear history (``wear.png``).

        ``study=dt``: ``error_vs_dt.png`` and ``profiles.png`` (see :func:`plot_dt_study`).
        """
        if profile.get("study") == "dt":
            return plot_dt_study(profile, outdir)
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(6, 3.5))
        for t, pts in zip(profile["times"], profile["profiles"]):
            p = np.asarray(pts)
            ax.plot(p[:, 0], p[:, 1], lw=1, label=f"t = {t:g} s")
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        ax.set_title(f"worn tip, {profile['scheme']} scheme, Δt = {profile['dt']:g} s")
        if len(profile["times"]) <= 12:
            ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(outdir / "profiles.png", dpi=120)
        plt.close(fig)
        fig, ax = plt.subplots(figsize=(5, 3.5))
        ax.plot(profile["time"], profile["wear_volume"], "o-", label="worn area (mm²/mm)")
        ax.plot(profile["time"], profile["max_wear_depth"], "s-", label="max depth (mm)")
        ax.set_xlabel("t (s)")
        ax.legend()
        fig.tight_layout()
        fig.savefig(outdir / "wear.png", dpi=120)
        plt.close(fig)

    @classmethod
    def run(cls, v, record, progress=None, verbose=False, n=None):
        """Integrate the wear of the pin from t = 0 to T; record per-step histories."""
        if v["study"] == "dt":
            dts, levels = cls.study_lists(v)
            ns = [10 * 2**m for m in levels] if n is None else [n]
            return run_dt_study(v, record, ns, dts, progress=progress, verbose=verbose)
        prob, load = cls.build(v, n=n)
        R = v["R_tip"] if v["R_tip"] > 0 else math.inf
        record.data["num_dofs"] = prob.solver.num_dofs
        if prob.shape_solver is not None:
            record.data["num_dofs_shape"] = prob.shape_solver.num_dofs
        hist = {k: [] for k in ("time", "wear_volume", "max_wear_depth", "contact_radius",
                                "newton_iterations", "wear_rate_integral", "dt")}
        profiles, ptimes = [], []

        def log(t, its, dt):
            area, _ = prob.contact_measures()
            d = prob.nodal_shape_data()
            comm = prob.mesh.comm
            hist["time"].append(t)
            hist["dt"].append(dt)
            hist["wear_volume"].append(prob.worn_volume())
            hist["max_wear_depth"].append(
                comm.allreduce(float(np.max(d["depth"], initial=0.0)), op=MPI.MAX))
            hist["contact_radius"].append(area / 2)
            hist["newton_iterations"].append(its)
            hist["wear_rate_integral"].append(prob.wear_rate_integral())
            record.data["newton_iterations"].append(its)
            s = prob.gather_shape()
            if comm.rank == 0:
                profiles.append(s["X_worn"].tolist())
                ptimes.append(t)

        its0 = solve_initial_contact(prob, load, v["q"], v["E"], v["W"], R, v["H"], verbose)
        advance = cls.stepper(prob, v)
        if v["mode"] == "cyclic":
            its0 += advance.__self__.restart(verbose)  # contact at the centre, sliding
        log(0.0, its0, 0.0)
        t, T, dt = 0.0, v["T"], cls.slow_step(v)
        cuts = 0
        try:
            while t < T * (1 - 1e-12):
                h = min(dt / 2**cuts, T - t)
                try:
                    its = advance(h, verbose=verbose)
                except NewtonDivergence:
                    cuts += 1
                    if cuts > v["max_cuts"]:
                        raise
                    continue
                t += h
                log(t, its, h)
                reports = getattr(advance, "last", None)
                if reports:
                    record.data.setdefault("newton_residuals", []).append(
                        [float(x) for x in reports[-1].residuals])
                cuts = 0 if abs(t / dt - round(t / dt)) < 1e-9 else cuts
                if progress is not None:
                    progress.update(1)
        except NewtonDivergence as err:
            err.problem = prob
            raise
        finally:
            cls._report(prob, v, record, hist, profiles, ptimes)
        return prob

    @staticmethod
    def _report(prob, v, record, hist, profiles, ptimes):
        units = {"time": "s", "wear_volume": "mm^3/mm", "max_wear_depth": "mm",
                 "contact_radius": "mm (half-width)", "newton_iterations": "-",
                 "wear_rate_integral": "mm^3/(mm*s)", "dt": "s"}
        for key, vals in hist.items():
            record.result(key, vals, units[key])
        d = prob.gather_shape()
        if prob.mesh.comm.rank == 0:
            record.result("final_profile", d["X_worn"].tolist(), "mm (worn configuration)")
            record.result("final_profile_deformed", d["x"].tolist(), "mm (current)")
            record.result("final_pressure", d["p"].tolist(), "MPa")
            record.profile = {**hist, "profiles": profiles, "times": ptimes,
                              "scheme": v["scheme"], "dt": WearPinCase.slow_step(v)}


# -- study=dt: error versus Δt of the explicit and implicit schemes (Figs. 3-4) -------

class _SubRecord:
    """Minimal stand-in for :class:`tribofx.output.RunRecord` for the runs of a study."""

    def __init__(self):
        self.data = {"newton_iterations": [], "results": {}}
        self.profile = None

    def result(self, key, value, unit="-"):
        self.data["results"][key] = {"value": value, "unit": unit}


def _study_run(v, n, scheme, dt, verbose=False):
    """One run of a study; returns (problem, dict with status, profiles, costs)."""
    over = {**v, "study": "none", "scheme": scheme, "dt": dt}
    if scheme == "explicit":
        over["max_cuts"] = 0  # at its nominal Δt: a failure is the instability
    sub = _SubRecord()
    t0 = time.perf_counter()
    status = "ok"
    try:
        prob = WearPinCase.run(over, sub, n=n, verbose=verbose)
    except NewtonDivergence as err:
        status = f"failed: {type(err).__name__}: {err}"[:200]
        prob = getattr(err, "problem", None)
    wall = time.perf_counter() - t0
    comm = MPI.COMM_WORLD if prob is None else prob.mesh.comm
    res = {k: r["value"] for k, r in sub.data["results"].items()}
    out = {"status": status, "wall_time_s": comm.allreduce(wall, op=MPI.MAX),
           "steps": len(res.get("time", [0.0])) - 1,
           "newton_iterations": int(sum(res.get("newton_iterations", [0])[1:])),
           "final_time": res["time"][-1] if res.get("time") else 0.0,
           "max_wear_depth": res["max_wear_depth"][-1] if res.get("max_wear_depth") else 0.0,
           "checkerboard": checkerboard_amplitude(prob) if prob is not None else math.nan}
    prof = sub.profile if comm.rank == 0 else None
    out["final_profile"] = comm.bcast(
        np.asarray(res["final_profile"]) if comm.rank == 0 and "final_profile" in res else None,
        root=0)
    out["profiles"] = comm.bcast(
        None if prof is None else {"times": prof["times"], "profiles": prof["profiles"]}, root=0)
    return prob, out


def run_dt_study(v, record, ns, dts, progress=None, verbose=False):
    """``study=dt`` of ``wear-pin`` on the n × n meshes ``ns`` for the time steps ``dts``.

    Records ``study_dt``, ``study_error_explicit`` and ``study_error_implicit``
    ({"n×n": [error per Δt, None if the run failed]}, mm, Euclidean norm of the
    final worn contact-node positions minus the reference), the max-norm
    counterparts ``study_maxerror_*``, ``study_unstable_*`` and ``study_status_*``
    flags, checkerboard amplitudes, costs and ``study_dt_cr`` (explicit critical
    step per mesh, None if not computed or not bracketed).  Returns the reference
    problem of the last mesh; ``record.profile`` holds what :func:`plot_dt_study` needs.
    """
    T = v["T"]
    ref_dt = v["study_ref_dt"]
    res = {key: {} for key in ("error_explicit", "error_implicit", "maxerror_explicit",
                               "maxerror_implicit", "unstable_explicit", "unstable_implicit",
                               "status_explicit", "status_implicit", "oscillation_explicit",
                               "oscillation_implicit", "checkerboard_explicit",
                               "checkerboard_implicit", "wall_time_explicit",
                               "wall_time_implicit", "newton_explicit", "newton_implicit",
                               "dt_cr", "reference_wall_time", "reference_correction",
                               "checkerboard_reference")}
    plots = {"study": "dt", "dts": list(dts), "E": v["E"], "T": T, "meshes": {}}
    prob_ref = None
    for n in ns:
        key = f"{n}x{n}"
        t0 = time.perf_counter()
        prob_ref, ref = _study_run(v, n, "implicit", ref_dt, verbose)
        if not ref["status"] == "ok":
            raise NewtonDivergence(f"study reference run ({key}, Δt = {ref_dt} s) "
                                   f"{ref['status']}")
        p_ref = ref["final_profile"]
        correction = 0.0
        if v["study_ref"] == "richardson":
            _, coarse = _study_run(v, n, "implicit", 2 * ref_dt, verbose)
            if not coarse["status"] == "ok":
                raise NewtonDivergence(f"study reference run ({key}, Δt = {2 * ref_dt} s) "
                                       f"{coarse['status']}")
            correction = float(np.linalg.norm(p_ref - coarse["final_profile"]))
            p_ref = 2 * p_ref - coarse["final_profile"]
        res["reference_wall_time"][key] = time.perf_counter() - t0
        res["reference_correction"][key] = correction
        res["checkerboard_reference"][key] = ref["checkerboard"]
        dt_cr = None
        if v["study_critical"]:
            try:
                dt_cr = explicit_critical_step(v, n, lo=0.01, hi=1e4)[0]
            except (ValueError, NewtonDivergence):
                dt_cr = None
        res["dt_cr"][key] = dt_cr
        runs = {"reference": {"dt": ref_dt, "profiles": ref["profiles"],
                              "final_profile": p_ref}}
        for scheme in ("explicit", "implicit"):
            for name in ("error", "maxerror", "unstable", "oscillation", "status", "checkerboard",
                         "wall_time", "newton"):
                res[f"{name}_{scheme}"][key] = []
            for dt in dts:
                _, r = _study_run(v, n, scheme, dt, verbose)
                ok = r["status"] == "ok"
                if ok:
                    diff = r["final_profile"] - p_ref
                    err = float(np.linalg.norm(diff))
                    maxerr = float(np.max(np.linalg.norm(diff, axis=1)))
                    osc = oscillation_ratio(diff[:, 1])
                else:
                    err = maxerr = osc = None
                res[f"error_{scheme}"][key].append(err)
                res[f"maxerror_{scheme}"][key].append(maxerr)
                res[f"unstable_{scheme}"][key].append(
                    bool(not ok or osc > OSCILLATION_TOL
                         or (scheme == "explicit" and dt_cr is not None and dt > dt_cr)))
                res[f"oscillation_{scheme}"][key].append(osc)
                res[f"status_{scheme}"][key].append(r["status"])
                res[f"checkerboard_{scheme}"][key].append(r["checkerboard"])
                res[f"wall_time_{scheme}"][key].append(r["wall_time_s"])
                res[f"newton_{scheme}"][key].append(r["newton_iterations"])
                runs[(scheme, dt)] = {"profiles": r["profiles"], "ok": ok}
                if progress is not None:
                    progress.update(1)
        plots["meshes"][key] = {"runs": runs, "dt_cr": dt_cr,
                                "error_explicit": res["error_explicit"][key],
                                "error_implicit": res["error_implicit"][key],
                                "unstable_explicit": res["unstable_explicit"][key],
                                "unstable_implicit": res["unstable_implicit"][key]}
    record.result("study_dt", list(dts), "s")
    units = {"error": "mm (Euclidean norm over the contact nodes)",
             "maxerror": "mm (max nodal distance)", "unstable": "-", "status": "-",
             "oscillation": "-",
             "checkerboard": "mm", "wall_time": "s", "newton": "-", "dt_cr": "s",
             "reference": "s", "checkerboard_reference": "mm"}
    for name, val in res.items():
        record.result(f"study_{name}", val, units.get(name.split("_")[0], units.get(name, "-")))
    ref_txt = (f"implicit, Δt = {ref_dt:g} s" if v["study_ref"] == "fine" else
               f"Richardson 2 p({ref_dt:g} s) − p({2 * ref_dt:g} s), implicit")
    record.result("study_reference", ref_txt, "-")
    record.result("study_unstable_criterion",
                  "failed at nominal Δt, or oscillation ratio of the error > "
                  f"{OSCILLATION_TOL:g}, or explicit with Δt > study_dt_cr", "-")
    plots["reference"] = ref_txt
    if prob_ref is not None and prob_ref.mesh.comm.rank == 0:
        record.profile = plots
    return prob_ref


def plot_dt_study(study, outdir):
    """Plot ``study=dt``: ``error_vs_dt.png`` and ``profiles.png``.

    ``error_vs_dt.png``: log-log, explicit and implicit panels, one curve per
    mesh, unstable runs as red crosses, Δt_cr dotted (like Fig. 4).
    ``profiles.png``: worn profiles every 200 s (the largest Δt) for Δt = 200 s
    and 5 s (or the largest and smallest Δt) against the reference, explicit
    left, implicit right, one row per mesh (like Fig. 3).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    dts = np.asarray(study["dts"])
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    for ax, scheme in zip(axes, ("explicit", "implicit")):
        for i, (key, m) in enumerate(study["meshes"].items()):
            color = f"C{i}"
            err = np.array([np.nan if e is None else e for e in m[f"error_{scheme}"]])
            bad = np.asarray(m[f"unstable_{scheme}"])
            ax.loglog(dts, err, "o-", color=color, label=f"{key}, {scheme}")
            if bad.any():
                top = np.nanmax(err) if np.isfinite(err).any() else 1.0
                ax.loglog(dts[bad], np.where(np.isfinite(err[bad]), err[bad], top), "x",
                          color="red", ms=10, mew=2)
            if scheme == "explicit" and m["dt_cr"]:
                ax.axvline(m["dt_cr"], color=color, ls=":", lw=1)
        ok = [e for m in study["meshes"].values() for e in m[f"error_{scheme}"] if e]
        if ok:  # slope-1 guide
            x = np.array([dts.min(), dts.max()])
            ax.loglog(x, min(ok) * x / dts.min(), "k--", lw=0.8, label="slope 1")
        ax.set_xlabel("Δt (s)")
        ax.set_title(f"{scheme}, E = {study['E']:g} MPa (× unstable, ⋮ Δt_cr)")
        ax.legend(fontsize=7)
    axes[0].set_ylabel("error of the worn contact profile (mm)")
    fig.suptitle(f"reference: {study['reference']}", fontsize=8)
    fig.tight_layout()
    fig.savefig(Path(outdir) / "error_vs_dt.png", dpi=120)
    plt.close(fig)

    big, small = max(dts), min(dts)
    if 5.0 in dts:
        small = 5.0
    if 200.0 in dts:
        big = 200.0
    meshes = study["meshes"]
    fig, axes = plt.subplots(len(meshes), 2, figsize=(10, 3.2 * len(meshes)), squeeze=False)
    for row, (key, m) in zip(axes, meshes.items()):
        ref = m["runs"]["reference"]["profiles"]
        marks = [t for t in ref["times"] if abs(t / big - round(t / big)) < 1e-9]
        ylim = None
        for ax, scheme in zip(row, ("explicit", "implicit")):
            for dt, style in ((big, "-"), (small, "--")):
                run = m["runs"].get((scheme, dt))
                if run is None or run["profiles"] is None:
                    continue
                for j, (t, p) in enumerate(zip(run["profiles"]["times"],
                                               run["profiles"]["profiles"])):
                    if any(abs(t - s) < 1e-6 for s in marks):
                        p = np.asarray(p)
                        ax.plot(p[:, 0], p[:, 1], style, color="C0" if dt == big else "C1",
                                lw=1, label=f"Δt = {dt:g} s" if j == 0 else None)
            for j, (t, p) in enumerate(zip(ref["times"], ref["profiles"])):
                if t in marks:
                    p = np.asarray(p)
                    ax.plot(p[:, 0], p[:, 1], ":", color="k", lw=1,
                            label=f"reference Δt = {m['runs']['reference']['dt']:g} s"
                            if j == 0 else None)
                    lo, hi = p[:, 1].min(), p[:, 1].max()
                    ylim = (min(lo, ylim[0]) if ylim else lo, max(hi, ylim[1]) if ylim else hi)
            if ylim:
                pad = 0.3 * (ylim[1] - ylim[0])
                ax.set_ylim(ylim[0] - pad, ylim[1] + pad)
            ax.set_title(f"{scheme}, {key}, E = {study['E']:g} MPa, t = {marks[0]:g}…"
                         f"{marks[-1]:g} s", fontsize=9)
            ax.set_xlabel("X (mm)")
            ax.set_ylabel("worn Y (mm)")
            ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(Path(outdir) / "profiles.png", dpi=120)
    plt.close(fig)
