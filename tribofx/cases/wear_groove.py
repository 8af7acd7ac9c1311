"""Rigid ball sliding against an elastic half-space: wear groove (chapter §5.3, Figs. 9–10).

Case ``wear-ball-halfspace``.  A rigid ball of radius R under the normal load F
slides at speed V over an elastic half-space (ball-on-disk test, curvature of
the track neglected).  The half-space is described in an Eulerian frame
attached to the ball (§4.3): its worn configuration moves rigidly at −V e_x,
the deformation is Lagrangian, the slip velocity is the tangential part of
v = F V (eqs. 26–27).  Contact is frictionless; Archard wear in the pressure
form Ẇ = k p ‖v_T‖ (eq. 14; ``law=spatial``: eqs. 15–16) is averaged along the
sliding path of length L per cycle (disk-track circumference), so the groove
depth rate at y is (1/L) ∫ Ẇ(x, y) dx.  The groove is uniform along x: the
shape mapping Ψ is a 2D field on the cross-section (y, z), coupled to the 3D
block by extrusion (see :mod:`tribofx.groove_problem` for the formulation,
the monolithic implicit and the explicit scheme).  Half model (y ≥ 0).

Material sets (``regime``; the chapter refers to Stupkiewicz 2013 for its
values, these are chosen in its spirit):

* ``small`` (default, Fig. 10): steel-like half-space E = 200 GPa, ν = 0.3,
  R = 5 mm, F = 10 N → Hertz a = 0.0555 mm, p₀ = 1.55 GPa (small strains);
  k = 1·10⁻⁷ mm³/(N·mm) (= 10⁻⁴ mm³/(N·m), severe dry sliding wear),
  V = 100 mm/s, L = 2π·10 mm (track radius 10 mm), T = 1000 s: final groove
  cross-section ≈ 1.6·10⁻³ mm² (half-width ≈ 0.23 mm, depth ≈ 5 µm).
* ``finite`` (Fig. 9): soft elastomer E = 10 MPa, ν = 0.3, same R, F → Hertz
  a = 1.5 mm (a/R = 0.3, finite strains); k = 1·10⁻⁴ mm³/(N·mm) (rubber
  abrasion, ~0.1 mm³/(N·m)).
* ``graded``: functionally graded layer (Fig. 10b) — E and k rise linearly
  towards the surface over the thickness ``grade_depth`` (default 0.01 mm in
  the small regime, about twice the final groove depth) to (1 + ``grade_alpha``)
  times the substrate values.

Mesh: block x ∈ [−27a, 27a], y ∈ [0, 27a], z ∈ [−27a, 0] (a the Hertz radius),
element size h = 0.45 a / 2^mesh in y and z in the contact region (y ≤ 5.4a,
depth ≤ 1.35a) and h/2 along x for |x| ≤ 1.8a (once the groove conforms to the
ball the contact is a narrow band, half-length ≈ 0.45a along x), geometric
coarsening outside; Q1 hexahedra.
Reported ``wear_volume`` is the full groove cross-section area (both halves),
i.e. the worn volume per unit groove length (mm³/mm); ``contact_radius`` is
the contact half-width across the groove (y), ``contact_half_length`` along x.
Runs in serial and under mpiexec (the cross-section is replicated, its
unknowns owned by rank 0 in the monolithic system).
"""

import math
import time
from pathlib import Path

import numpy as np
from mpi4py import MPI

from ..groove_problem import GrooveProblem
from ..meshes import halfspace as hs
from ..newton import NewtonDivergence
from ..params import InputError, Param
from ..references import hertz, rigid_groove_halfwidth

__all__ = ["WearBallHalfspaceCase", "hertz_sphere", "plot_groove", "plot_pressure_across"]

REGIMES = {"small": {"E": 2.0e5, "k": 1.0e-7, "grade_depth": 0.01},
           "finite": {"E": 10.0, "k": 1.0e-4, "grade_depth": 0.3}}


def hertz_sphere(E, nu, R, F):
    """Hertz contact of a rigid sphere on an elastic half-space: (a, p₀, δ) in mm, MPa, mm.

    Kept for existing callers; the formula is :func:`tribofx.references.hertz`.
    """
    return hertz(F, R, E, nu)[:3]


class WearBallHalfspaceCase:
    """Case ``wear-ball-halfspace``; see the module docstring."""

    name = "wear-ball-halfspace"
    doc = "rigid ball sliding on an elastic half-space: quasi-steady wear groove (§5.3)"
    params = (
        Param("scheme", str, "implicit", "-", "θ-scheme: explicit (θ=0) or implicit (θ=1)",
              choices=("explicit", "implicit")),
        Param("dt", float, 100.0, "s", "time step Δt", lower=0.0),
        Param("T", float, 1000.0, "s", "end time", lower=0.0),
        Param("regime", str, "small", "-", "material set: small (E=200 GPa) or finite (E=10 MPa)",
              choices=("small", "finite")),
        Param("k", float, None, "mm^3/(N*mm)", "Archard coefficient of the substrate "
              "(default: 1e-7 small, 1e-4 finite)", lower=0.0, closed=True),
        Param("V", float, 100.0, "mm/s", "sliding speed", lower=0.0),
        Param("E", float, None, "MPa", "Young's modulus of the substrate "
              "(default: 2e5 small, 10 finite)", lower=0.0),
        Param("nu", float, 0.3, "-", "Poisson's ratio", lower=-1.0, upper=0.5),
        Param("R", float, 5.0, "mm", "ball radius", lower=0.0),
        Param("F", float, 10.0, "N", "normal load on the ball", lower=0.0),
        Param("L", float, 2 * math.pi * 10.0, "mm", "sliding length per cycle (track length)",
              lower=0.0),
        Param("mesh", int, 0, "-", "refinement level: h = 0.45 a / 2^mesh at the contact",
              lower=0, upper=2, closed=True),
        Param("law", str, "nominal", "-", "Archard law: nominal (eq. 14) or spatial (eqs. 15-16)",
              choices=("nominal", "spatial")),
        Param("graded", bool, False, "-", "functionally graded surface layer (Fig. 10b)"),
        Param("grade_alpha", float, 1.0, "-", "FGM: E and k at the surface = (1 + α) × substrate",
              lower=0.0, closed=True),
        Param("grade_depth", float, None, "mm", "FGM layer thickness (default: 0.01 small, "
              "0.3 finite)", lower=0.0),
        Param("max_cuts", int, 6, "-", "step halvings allowed per step", lower=0, upper=20,
              closed=True),
    )

    @staticmethod
    def resolved(v):
        """Parameters with the regime defaults filled in."""
        v = dict(v)
        for key, val in REGIMES[v["regime"]].items():
            if v.get(key) is None:
                v[key] = val
        return v

    @classmethod
    def validate(cls, v):
        """Check cross-parameter consistency."""
        v = cls.resolved(v)
        if v["dt"] > v["T"]:
            raise InputError(f"dt = {v['dt']} s exceeds T = {v['T']} s")
        a = hertz(v["F"], v["R"], v["E"], v["nu"]).a
        if a > 0.5 * v["R"]:
            raise InputError(f"Hertz radius a = {a:.3g} mm > R/2: load too high for the ball")
        if v["L"] < 4 * a:
            raise InputError(f"L = {v['L']:g} mm is shorter than the contact (4a = {4 * a:.3g} mm):"
                             " one pass per cycle is assumed")
        # final groove half-width if it follows the ball
        b = float(rigid_groove_halfwidth(v["k"], v["F"], v["R"], v["V"] * v["T"], v["L"]))
        if b > 5.4 * a:
            raise InputError(f"final groove half-width ≈ {b:.3g} mm exceeds the refined zone "
                             f"(5.4a = {5.4 * a:.3g} mm): reduce k, V or T, or increase L")

    @classmethod
    def build(cls, v, comm=MPI.COMM_WORLD):
        """Mesh and :class:`GrooveProblem`; returns ``(problem, info)``."""
        v = cls.resolved(v)
        a, p0, delta = hertz(v["F"], v["R"], v["E"], v["nu"])[:3]
        h = 0.45 * a / 2 ** v["mesh"]
        Lb = 27 * a
        gx, gy, gz = hs.grids(Lb, Lb, Lb, h, 1.8 * a, 5.4 * a, 1.35 * a, (4, 5, 6), hx=h / 2)
        msh, ft = hs.halfspace_block(comm, gx, gy, gz)
        sec, sft = hs.cross_section(MPI.COMM_SELF, gy, gz)  # replicated on every rank
        graded = (v["grade_alpha"], v["grade_depth"]) if v["graded"] else None
        prob = GrooveProblem(msh, ft, sec, sft, v["E"], v["nu"], v["R"], v["F"], v["V"], v["L"],
                             v["k"], h, scheme=v["scheme"], graded=graded, law=v["law"])
        return prob, {"a": a, "p0": p0, "delta": delta, "h": h}

    @staticmethod
    def initial_contact(prob, info, verbose=False):
        """Unworn contact: the block starts lifted by the Hertz approach δ = a²/R.

        The stiffness of the whole block adds a uniform compression F/(2A)·H/E,
        negligible here.  Returns the Newton report.
        """
        prob.u.x.array.reshape(-1, 3)[:, 2] = info["delta"]
        return prob.solve_contact(verbose)

    @staticmethod
    def vtx_fields(prob):
        """Displacement and 3D shape change (block), contact multiplier."""
        return {"displacement": [prob.u, prob.w3], "contact": [prob.lam_n]}

    @classmethod
    def run(cls, v, record, progress=None, verbose=False):
        """Integrate the groove from t = 0 to T; record per-step histories."""
        v = cls.resolved(v)
        for key in REGIMES[v["regime"]]:  # record the regime defaults actually used
            if key in record.data["parameters"]:
                record.data["parameters"][key]["value"] = v[key]
        t_start = time.perf_counter()
        prob, info = cls.build(v)
        sizes = prob.global_sizes()
        n_u, n_l, n_w, n_z = (sizes[b] for b in ("u", "l", "w", "z"))
        total = n_u + n_l + n_w + n_z
        record.data["num_dofs"] = total
        record.result("dofs", {"u": n_u, "lambda": n_l, "psi": n_w, "zeta": n_z}, "-")
        record.result("psi_fraction", (n_w + n_z) / total, "- (share of Ψ and its multiplier)")
        record.result("hertz", info, "mm, MPa")
        hist = {k: [] for k in ("time", "wear_volume", "max_wear_depth", "contact_radius",
                                "contact_half_length", "newton_iterations", "averaged_rate",
                                "max_pressure", "dt")}
        prof = {"times": [], "profiles": [], "maps": []}

        def log(t, its, dt):
            lp = prob.line_profile()
            d = prob.surface_data()
            ax, ay = prob.contact_extent()
            hist["time"].append(t)
            hist["dt"].append(dt)
            hist["wear_volume"].append(2 * prob.groove_area())
            hist["max_wear_depth"].append(float(lp["depth"].max()))
            hist["contact_radius"].append(ay)
            hist["contact_half_length"].append(ax)
            hist["newton_iterations"].append(its)
            hist["averaged_rate"].append(2 * prob.averaged_rate_integral())
            hist["max_pressure"].append(float(d["p"].max()))
            record.data["newton_iterations"].append(its)
            prof["times"].append(t)
            prof["profiles"].append(lp["worn"].tolist())
            prof["maps"].append(np.column_stack([d["X"], d["p"]]).tolist())

        rep = cls.initial_contact(prob, info, verbose)
        log(0.0, rep.iterations, 0.0)
        t, T, dt, cuts = 0.0, v["T"], v["dt"], 0
        try:
            while t < T * (1 - 1e-12):
                h = min(dt / 2**cuts, T - t)
                try:
                    reports = prob.step(h, verbose=verbose)
                except NewtonDivergence:
                    cuts += 1
                    if cuts > v["max_cuts"]:
                        raise
                    continue
                t += h
                log(t, int(sum(r.iterations for r in reports)), h)
                record.data.setdefault("newton_residuals", []).append(
                    [float(x) for x in reports[0].residuals])
                cuts = max(cuts - 1, 0)
                if progress is not None:
                    progress.update(1)
        except NewtonDivergence as err:
            err.problem = prob
            raise
        finally:
            cls._report(prob, v, record, hist, prof, time.perf_counter() - t_start)
        return prob

    @staticmethod
    def _report(prob, v, record, hist, prof, wall):
        units = {"time": "s", "wear_volume": "mm^3/mm (full groove cross-section area)",
                 "max_wear_depth": "mm", "contact_radius": "mm (half-width across the groove)",
                 "contact_half_length": "mm (along the sliding direction)",
                 "newton_iterations": "-", "averaged_rate": "mm^3/(mm*s) ((2/L) ∫ k p v dA)",
                 "max_pressure": "MPa (nominal)", "dt": "s"}
        for key, vals in hist.items():
            record.result(key, vals, units[key])
        lp = prob.line_profile()
        w = lp["worn"]
        full = np.vstack([w[::-1] * [-1, 1], w[1:]])
        record.result("final_profile", full.tolist(), "mm (worn cross-section (y, z), both halves)")
        y, pint = prob.averaged_pressure()
        d = prob.surface_data()
        on = np.abs(d["X"][:, 0]) < 1e-9
        o = np.argsort(d["X"][on, 1])
        record.result("final_pressure_x0", np.column_stack([d["X"][on, 1][o], d["p"][on][o]])
                      .tolist(), "mm, MPa (y, p at x = 0)")
        record.result("final_pressure_integral", np.column_stack([y, pint]).tolist(),
                      "mm, N/mm (y, ∫ p dx)")
        record.result("wall_time_solve", wall, "s")
        record.profile = {**hist, **prof, "scheme": v["scheme"], "graded": v["graded"],
                          "R": v["R"], "pressure_x0": record.data["results"]["final_pressure_x0"]
                          ["value"], "pressure_integral": np.column_stack([y, pint]).tolist()}

    @staticmethod
    def plot(profile, outdir):
        """Groove profiles, pressure maps at t = 0 and final, pressure across the groove."""
        plot_groove(profile, outdir)


def plot_groove(profile, outdir, compare=None):
    """``groove_profiles.png``, ``pressure_maps.png``, ``pressure_across.png``.

    ``compare``: a second profile (e.g. the graded layer) overlaid on the
    pressure-across plot (Fig. 10 bottom, homogeneous vs graded).
    """
    import matplotlib

    matplotlib.use("Agg")

    import matplotlib.pyplot as plt

    outdir = Path(outdir)
    fig, ax = plt.subplots(figsize=(6, 3.5))
    colors = plt.cm.viridis(np.linspace(0, 0.9, len(profile["times"])))
    for t, pts, c in zip(profile["times"], profile["profiles"], colors):
        p = np.asarray(pts)
        p = np.vstack([p[::-1] * [-1, 1], p[1:]])
        ax.plot(p[:, 0], 1e3 * p[:, 1], lw=1, color=c, label=f"t = {t:g} s")
    ax.set_xlim(-1.5 * max(profile["contact_radius"]), 1.5 * max(profile["contact_radius"]))
    ax.set_xlabel("y (mm)")
    ax.set_ylabel("worn surface z (µm)")
    ax.set_title(f"wear groove, {profile['scheme']} scheme")
    if len(profile["times"]) <= 12:
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(outdir / "groove_profiles.png", dpi=120)
    plt.close(fig)

    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    lim = 1.5 * max(max(profile["contact_radius"]), max(profile["contact_half_length"]))
    for ax, i in zip(axes, (0, -1)):
        m = np.asarray(profile["maps"][i])
        m = np.vstack([m, m * [1, -1, 1]])
        sel = (np.abs(m[:, 0]) < lim) & (np.abs(m[:, 1]) < lim)
        sc = ax.tricontourf(m[sel, 0], m[sel, 1], m[sel, 2], levels=20, cmap="viridis")
        fig.colorbar(sc, ax=ax, label="p (MPa)")
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm, sliding)")
        ax.set_ylabel("y (mm)")
        ax.set_title(f"contact pressure, t = {profile['times'][i]:g} s")
    fig.tight_layout()
    fig.savefig(outdir / "pressure_maps.png", dpi=120)
    plt.close(fig)

    entries = [("graded" if prof["graded"] else "homogeneous", prof["pressure_x0"],
                prof["pressure_integral"]) for prof in (profile, compare) if prof is not None]
    plot_pressure_across(entries, outdir / "pressure_across.png", profile["times"][-1],
                         1.5 * max(profile["contact_radius"]))


def plot_pressure_across(entries, path, t, ymax):
    """Pressure across the groove at x = 0 and ∫ p dx versus y (Fig. 10 bottom).

    ``entries``: list of (label, [(y, p)], [(y, ∫p dx)]), e.g. homogeneous and graded.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 3.5))
    for (label, px0, pint), style in zip(entries, ("-o", "--s", ":^")):
        p = np.asarray(px0)
        axes[0].plot(p[:, 0], p[:, 1], style, ms=3, label=label)
        q = np.asarray(pint)
        axes[1].plot(q[:, 0], q[:, 1], style, ms=3, label=label)
    axes[0].set_ylabel("p at x = 0 (MPa)")
    axes[1].set_ylabel("∫ p dx (N/mm)")
    for ax in axes:
        ax.set_xlabel("y (mm)")
        ax.set_xlim(0, ymax)
        ax.legend(fontsize=8)
    fig.suptitle(f"pressure across the groove at t = {t:g} s (Fig. 10 bottom)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
