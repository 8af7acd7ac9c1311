"""Soft-EHL: rigid cylinder sliding against a coated elastic layer (chapter §8.2, plane strain).

A rigid cylinder of radius R slides at speed U over an elastic layer of
thickness H bonded to a rigid substrate; the top t_c of the layer is a stiffer
coating.  The lubricant film between them carries the load W per unit length.
The problem is steady in the frame of the cylinder: the layer material flows
through the deformed mesh with v = F V, V = (U, 0) (eq. 26), the cylinder is
at rest.  The lubrication surface is S = P(γ_l), the projection of the deformed
layer surface onto the cylinder (§7.2); the film thickness h, the mean velocity
v̄ = ½(I − ν⊗ν)FV and the surface operators of S follow the deformation and
enter the exact Newton tangent (forms/ehl.py).  Cavitation: ``penalty`` on
p < 0 (Swift–Stieber/Reynolds conditions in the limit) or ``jfo`` (mass
conserving, §6.5: void fraction λ, weak form (57) on S, nodal complementarity,
flooded inlet).  ``alpha`` moves the lubrication surface to
S_α = (1 − α) P(γ_l) + α γ_l (Fig. 23).  The fluid traction (46) (pressure,
optionally the Couette and Poiseuille shear) loads the layer.  ``speeds``
continues the solution at the final load in the sliding speed (step cutting in
log U) and records friction coefficient, h_min, p_max against μU
(``speed_*`` results, ``friction_vs_speed.png``); the other results are those of
the load sweep at ``U``.

Default data (in the spirit of the chapter; mm, N, s, MPa):

* cylinder R = 10 mm;  layer H = 5 mm, E = 10 MPa;  coating t_c = 0.1 mm,
  E_c = 100 MPa;  ν = 0.45 both, compressible neo-Hookean;
* viscosity μ = 1e-7 MPa·s (0.1 Pa·s), U = 1000 mm/s, so μU = 1e-4 N/mm
  (= 0.1 N/m, Fig. 22 of the chapter);
* load W from W/steps to W = 1 N/mm in ``steps`` = 10 increments;
* lubricated zone |X| ≤ x_l = 3 mm of a layer of half width 3H.

``model=linear`` is the classical (geometrically linear) EHL model for
comparison (dashed lines of Fig. 22).  The load is controlled by the vertical
position of the cylinder, found by a secant iteration per load step.

``compare=linear`` runs the load sweep for both models in one run and
``compare=alpha`` for α = 0, 0.5, 1 (finite model); the results of each variant
carry its name as prefix (``finite_``, ``linear_``, ``alpha0_``, ``alpha0.5_``,
``alpha1_``; listed in ``variants``), the profiles of all variants at every load
share one plot (``profiles_finite_vs_linear.png``, ``profiles_alpha.png``, as
the chapter's Figs. 22–23).  :func:`mesh_convergence` gives h_min, p_max on
mesh levels 0, 1, 2 at one load.

Results: minimum film h_min, central film h_central (below the cylinder axis),
peak pressure p_max, friction coefficient (tangential film force on the layer /
W), per load step; profiles p(x), h(x) (``profiles.png``); VTX of u and p.
"""

import math

import numpy as np
from mpi4py import MPI

from ..ehl_problem import EHLProblem, LoadControl
from ..forms.hyperelastic import lame_parameters
from ..meshes.layer import BOTTOM, COATING, LAYER, LUBRICATED, coated_layer
from ..newton import NewtonDivergence
from ..params import InputError, Param
from ..references import rigid_clearance

__all__ = ["EHLCylinderLayerCase", "cylinder_arc", "mesh_convergence"]


def cylinder_arc(R, n, alpha):
    """Lower arc θ ∈ [−π/2 − α, −π/2 + α] of the circle of radius R about 0 (mm).

    ``n`` interval3 facets (v0, v1, midpoint, nodes on the circle), numbered
    counter-clockwise so that the facet normal (t_y, −t_x) points out of the
    cylinder, into the film.  Returns (nodes, facets, "interval3").
    """
    th = np.linspace(-0.5 * math.pi - alpha, -0.5 * math.pi + alpha, 2 * n + 1)
    nodes = R * np.c_[np.cos(th), np.sin(th)]
    k = 2 * np.arange(n)
    return nodes, np.c_[k, k + 2, k + 1].astype(np.int32), "interval3"


class EHLCylinderLayerCase:
    """Case ``ehl-cylinder-layer``; see the module docstring."""

    name = "ehl-cylinder-layer"
    doc = "soft-EHL: rigid cylinder sliding on a coated elastic layer (finite or linear)"
    params = (
        Param("W", float, 1.0, "N/mm", "final load per unit length", lower=0.0),
        Param("steps", int, 10, "-", "load increments (W/steps, 2W/steps, …, W)", lower=1,
              upper=1000, closed=True),
        Param("mu", float, 1e-7, "MPa·s", "viscosity (1e-7 MPa·s = 0.1 Pa·s)", lower=0.0),
        Param("U", float, 1000.0, "mm/s", "sliding speed of the cylinder", lower=0.0),
        Param("R", float, 10.0, "mm", "cylinder radius", lower=0.0),
        Param("H", float, 5.0, "mm", "layer thickness (coating included)", lower=0.0),
        Param("E", float, 10.0, "MPa", "Young's modulus of the layer", lower=0.0),
        Param("t_c", float, 0.1, "mm", "coating thickness (0: no coating)", lower=0.0,
              closed=True),
        Param("E_c", float, 100.0, "MPa", "Young's modulus of the coating", lower=0.0),
        Param("nu", float, 0.45, "-", "Poisson's ratio (layer and coating)", lower=-1.0,
              upper=0.5),
        Param("x_l", float, 3.0, "mm", "half length of the lubricated zone (p = 0 at ±x_l)",
              lower=0.0),
        Param("model", str, "finite", "-", "finite deformation or geometrically linear (EHL)",
              choices=("finite", "linear")),
        Param("shear", bool, True, "-", "Couette and Poiseuille shear tractions on the layer"),
        Param("supg", bool, True, "-", "SUPG stabilisation of the Reynolds equation"),
        Param("penalty", float, 1e-6, "-",
              "relative cavitation penalty ε/ε_ref, ε_ref = 24 μ R/h_r², h_r = rigid film at W",
              lower=0.0),
        Param("mesh", int, 1, "-", "refinement: element size 0.04/2^mesh mm along Γ_l",
              lower=0, upper=6, closed=True),
        Param("degree", int, 2, "-", "Lagrange degree of the displacement", choices=(1, 2)),
        Param("countersurface", str, "analytic", "-",
              "cylinder in closed form, or meshed (interval3 arc, C++ projection kernel)",
              choices=("analytic", "mesh")),
        Param("cs_facets", int, 400, "-", "interval3 facets of the meshed cylinder arc", lower=1,
              upper=100000, closed=True),
        Param("cavitation", str, "penalty", "-",
              "penalty (Swift–Stieber limit) or jfo (mass-conserving, void fraction λ)",
              choices=("penalty", "jfo")),
        Param("alpha", float, 0.0, "-",
              "lubrication surface S_α = (1 − α) P(γ_l) + α γ_l (0: S = P(γ_l), 1: S = γ_l)",
              lower=0.0, upper=1.0, closed=True),
        Param("speeds", str, "", "mm/s",
              "comma-separated sliding speeds for continuation in U at the final load W "
              "(empty: none); records the friction coefficient vs μU"),
        Param("compare", str, "none", "-",
              "one load sweep per variant in the same run: linear (model = finite and "
              "linear, Fig. 22) or alpha (α = 0, 0.5, 1, Fig. 23); results prefixed by "
              "the variant", choices=("none", "linear", "alpha")),
    )

    #: variants of ``compare``: (summary key prefix, plot label, parameter overrides)
    COMPARE = {
        "linear": (("finite", "finite deformation", {"model": "finite"}),
                   ("linear", "geometrically linear", {"model": "linear"})),
        "alpha": (("alpha0", "α = 0 (S = P(γ_l))", {"alpha": 0.0}),
                  ("alpha0.5", "α = 0.5", {"alpha": 0.5}),
                  ("alpha1", "α = 1 (S = γ_l)", {"alpha": 1.0})),
    }
    #: plot file of each ``compare`` option
    COMPARE_PLOT = {"linear": "profiles_finite_vs_linear.png", "alpha": "profiles_alpha.png"}

    @staticmethod
    def validate(v):
        """Geometric consistency of the layer and the lubricated zone."""
        if v["t_c"] >= v["H"]:
            raise InputError(f"coating t_c = {v['t_c']} mm must be thinner than H = {v['H']} mm")
        if v["x_l"] >= 3 * v["H"]:
            raise InputError(f"x_l = {v['x_l']} mm must be < 3H = {3 * v['H']} mm")
        if v["x_l"] > 0.8 * v["R"]:
            raise InputError(f"x_l = {v['x_l']} mm must be < 0.8 R (film beyond the cylinder)")
        try:
            speeds = EHLCylinderLayerCase.speed_list(v)
        except ValueError as err:
            raise InputError(f"speeds = {v['speeds']!r}: {err}") from None
        if any(not U > 0 for U in speeds):
            raise InputError("speeds must be positive (mm/s)")
        if v["cavitation"] == "jfo" and not v["U"] > 0:
            raise InputError("cavitation=jfo needs U > 0")
        if v["compare"] != "none" and speeds:
            raise InputError("speeds (continuation in U) is not available with compare")
        if v["compare"] == "alpha" and v["model"] != "finite":
            raise InputError("compare=alpha is a study of the finite-deformation model")

    @staticmethod
    def speed_list(v):
        """Return the continuation speeds (mm/s) of ``speeds``."""
        return [float(t) for t in v["speeds"].replace(";", ",").split(",") if t.strip()]

    @staticmethod
    def scales(v, W=None):
        """Rigid film h_r (mm), pressure scale (MPa) and penalty ε (MPa·s/mm) at load W."""
        W = v["W"] if W is None else W
        h_r = rigid_clearance(W, v["mu"], v["U"], v["R"])
        ell = math.sqrt(2 * v["R"] * h_r)
        p_s = 6 * v["mu"] * v["U"] * ell / h_r**2
        eps = v["penalty"] * 12 * v["mu"] * ell**2 / h_r**3
        return h_r, p_s, eps

    @classmethod
    def build(cls, v, comm=MPI.COMM_WORLD, intermediate=False):
        """Mesh and :class:`EHLProblem` (unloaded; the cylinder at the rigid clearance).

        ``alpha = 0`` uses the closed-form S = P(γ_l) unless ``intermediate`` (then
        the general S_α kinematics with α = 0, for checking that they coincide).
        """
        h_fine = 0.04 / 2 ** v["mesh"]
        H = v["H"]
        msh, ct, ft = coated_layer(3 * H, H, v["t_c"], v["x_l"], h_fine, H / 5, comm)

        def mat(E):
            mu, lm = lame_parameters(E, v["nu"])
            return ("neo-hookean", {"mu": mu, "lmbda": lm})

        materials = {LAYER: mat(v["E"])}
        if v["t_c"] > 0:
            materials[COATING] = mat(v["E_c"])
        cs = None
        if v["countersurface"] == "mesh":
            cs = cylinder_arc(v["R"], v["cs_facets"], cls.arc_half_angle(v))
        W1 = v["W"] / v["steps"]
        h_r, p_s, eps = cls.scales(v, W1)
        prob = EHLProblem(msh, ct, ft, materials, LUBRICATED, BOTTOM, v["R"], v["U"], v["mu"],
                          model=v["model"], shear=v["shear"], supg=v["supg"],
                          eps=eps if v["penalty"] > 0 else None, p_c=p_s, h_ref=h_r,
                          degree=v["degree"], s0=h_r, countersurface=cs,
                          cavitation=v["cavitation"],
                          alpha=v["alpha"] if (v["alpha"] > 0 or intermediate) else None)
        if v["cavitation"] == "jfo":
            prob.jfo_initial_guess()
        return prob

    @staticmethod
    def arc_half_angle(v):
        """Half angle (rad) of the meshed arc: covers the film zone |x| ≤ x_l with 25 % margin."""
        return math.asin(min(0.95, 1.25 * v["x_l"] / v["R"]))

    @classmethod
    def run(cls, v, record, progress=None, verbose=False):
        """Load sweep W/steps … W (per variant of ``compare``); records the film measures."""
        if v["compare"] != "none":
            return cls._run_compare(v, record, progress, verbose)
        return cls._run_single(v, record, progress, verbose)

    @classmethod
    def _run_compare(cls, v, record, progress, verbose):
        """One load sweep per variant of ``compare``, results prefixed ``<variant>_``.

        All variants share the mesh parameters and the loads; the profiles of
        every variant go to one plot (:attr:`COMPARE_PLOT`).  The problem of the
        first variant is returned (VTX output); a variant that fails ends the run
        after recording what has converged.
        """
        targets = [v["W"] * (k + 1) / v["steps"] for k in range(v["steps"])]
        variants, first = {}, None
        record.result("mu_U", v["mu"] * v["U"], "N/mm")
        record.result("variants", [name for name, _, _ in cls.COMPARE[v["compare"]]])
        record.data["variant_newton_iterations"] = {}
        for name, label, over in cls.COMPARE[v["compare"]]:
            vv = dict(v, **over)
            prob = cls.build(vv)
            if first is None:
                first = prob
                record.data["num_dofs"] = prob.solver.num_dofs
            steps = {k: [] for k in cls.STEP_KEYS}
            profiles, its_all = [], []
            record.data["variant_newton_iterations"][name] = its_all

            def on_step(W, its, final, prob=prob, vv=vv, steps=steps, profiles=profiles,
                        its_all=its_all):
                its_all.append(its)
                record.data["newton_iterations"].append(its)
                if not final:
                    return
                m = prob.measures()
                for k in steps:
                    steps[k].append(m[k])
                prof = prob.profile()
                if prob.mesh.comm.rank == 0:
                    xx = prof["y"][:, 0] if vv["model"] == "finite" else prof["X"]
                    profiles.append({"W": W, "x": xx, "p": prof["p"], "h": prof["h"]})
                if progress is not None:
                    progress.update(1)

            try:
                LoadControl(prob, verbose=verbose).sweep(targets, on_step)
            except NewtonDivergence as err:
                err.problem = prob
                raise
            finally:
                cls._report_steps(steps, record, prefix=f"{name}_")
                variants[name] = {"label": label, "model": vv["model"], "alpha": vv["alpha"],
                                  "steps": profiles}
                if prob.mesh.comm.rank == 0:
                    record.profile = {"compare": v["compare"], "variants": variants}
        return first

    STEP_KEYS = ("W", "h_min", "h_central", "p_max", "friction_coefficient", "clearance")
    STEP_UNITS = {"W": "N/mm", "h_min": "mm", "h_central": "mm", "p_max": "MPa",
                  "friction_coefficient": "-", "clearance": "mm"}

    @classmethod
    def _report_steps(cls, steps, record, prefix=""):
        """Final-load values and per-step lists ``<prefix>steps_<key>`` of a load sweep."""
        if steps["W"]:
            for k in ("h_min", "h_central", "p_max", "friction_coefficient"):
                record.result(prefix + k, steps[k][-1], cls.STEP_UNITS[k])
            record.result(prefix + "W_reached", steps["W"][-1], "N/mm")
        for k, vals in steps.items():
            record.result(f"{prefix}steps_{k}", list(vals), cls.STEP_UNITS[k])

    @classmethod
    def _run_single(cls, v, record, progress=None, verbose=False):
        """Load sweep of one model (``compare=none``), optionally continued in speed."""
        prob = cls.build(v)
        record.data["num_dofs"] = prob.solver.num_dofs
        control = LoadControl(prob, verbose=verbose)
        steps = {k: [] for k in ("W", "h_min", "h_central", "p_max", "friction_coefficient",
                                 "clearance")}
        profiles = []

        def on_step(W, its, final):
            m = prob.measures()
            for k in steps:
                steps[k].append(m[k])
            record.data["newton_iterations"].append(its)
            if final:
                prof = prob.profile()
                if prob.mesh.comm.rank == 0:
                    xx = prof["y"][:, 0] if v["model"] == "finite" else prof["X"]
                    profiles.append({"W": W, "x": xx, "p": prof["p"], "h": prof["h"]})
                if progress is not None:
                    progress.update(1)

        targets = [v["W"] * (k + 1) / v["steps"] for k in range(v["steps"])]
        speed = {k: [] for k in ("U", "mu_U", "friction_coefficient", "h_min", "p_max",
                                 "clearance")}

        def on_speed(U, its, final):
            record.data["newton_iterations"].append(its)
            if final:
                m = prob.measures()
                speed["U"].append(U)
                speed["mu_U"].append(v["mu"] * U)
                for k in ("friction_coefficient", "h_min", "p_max", "clearance"):
                    speed[k].append(m[k])
                if progress is not None:
                    progress.update(1)

        try:
            control.sweep(targets, on_step)
            speeds = cls.speed_list(v)
            if speeds:
                for k in ("friction_coefficient", "h_min", "p_max", "clearance"):
                    speed[k].append(steps[k][-1])
                speed["U"].append(v["U"])
                speed["mu_U"].append(v["mu"] * v["U"])
                control.speed_sweep(speeds, lambda U: cls.speed_scales(v, U), on_speed)
        except NewtonDivergence as err:
            err.problem = prob  # restored to the last converged load (or speed) step
            raise
        finally:
            cls._report(prob, steps, profiles, v, record)
            if len(speed["U"]) > 1:
                units = {"U": "mm/s", "mu_U": "N/mm", "friction_coefficient": "-",
                         "h_min": "mm", "p_max": "MPa", "clearance": "mm"}
                for k, vals in speed.items():
                    record.result(f"speed_{k}", list(vals), units[k])
                if prob.mesh.comm.rank == 0 and record.profile is not None:
                    record.profile["speed"] = {k: list(vals) for k, vals in speed.items()}
        return prob

    @classmethod
    def speed_scales(cls, v, U):
        """(p_c, ε, h_ref) of the problem at the final load W and speed U."""
        h_r, p_s, eps = cls.scales(dict(v, U=U), v["W"])
        return p_s, eps, h_r

    @classmethod
    def _report(cls, prob, steps, profiles, v, record):
        cls._report_steps(steps, record)
        record.result("mu_U", v["mu"] * v["U"], "N/mm")
        if prob.mesh.comm.rank == 0 and profiles:
            record.profile = {"model": v["model"], "steps": profiles}

    @staticmethod
    def vtx_fields(prob):
        """Displacement (bulk) and film pressure (Γ_l submesh)."""
        return {"displacement": [prob.u], "pressure": [prob.p]}

    @classmethod
    def plot(cls, profile, outdir):
        """Pressure and film-thickness profiles at every load step (``profiles.png``).

        With ``compare``: all variants on the same axes (:attr:`COMPARE_PLOT`).
        """
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        if "variants" in profile:
            cls._plot_compare(profile, outdir, plt)
            return

        fig, (a1, a2) = plt.subplots(2, 1, figsize=(6.5, 6.5), sharex=True)
        for k, st in enumerate(profile["steps"]):
            c = plt.cm.viridis(k / max(1, len(profile["steps"]) - 1))
            a1.plot(st["x"], st["p"], color=c, lw=1, label=f"W = {st['W']:.3g} N/mm")
            a2.plot(st["x"], 1e3 * np.asarray(st["h"]), color=c, lw=1)
        a1.set_ylabel("pressure p (MPa)")
        a1.legend(fontsize=7, ncol=2)
        a1.grid(alpha=0.3)
        a1.set_title(f"coated layer, model = {profile['model']}")
        a2.set_ylabel("film thickness h (µm)")
        a2.set_yscale("log")
        a2.set_xlabel("x (mm, cylinder frame)")
        a2.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(outdir / "profiles.png", dpi=120)
        plt.close(fig)
        if "speed" in profile:
            sp = profile["speed"]
            fig, ax = plt.subplots(figsize=(5, 4))
            ax.loglog(1e3 * np.asarray(sp["mu_U"]), sp["friction_coefficient"], "o-")
            ax.set_xlabel("μU (N/m)")
            ax.set_ylabel("friction coefficient")
            ax.grid(alpha=0.3, which="both")
            fig.tight_layout()
            fig.savefig(outdir / "friction_vs_speed.png", dpi=120)
            plt.close(fig)

    @classmethod
    def _plot_compare(cls, profile, outdir, plt):
        """Figs. 22–23 of the chapter: p(x) and h(x) per load (colour) and variant (line)."""
        from matplotlib.lines import Line2D

        styles = ("-", "--", ":", "-.")
        fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 7), sharex=True)
        handles = []
        for j, var in enumerate(profile["variants"].values()):
            ls = styles[j % len(styles)]
            n = len(var["steps"])
            for k, st in enumerate(var["steps"]):
                c = plt.cm.viridis(k / max(1, n - 1))
                lab = f"W = {st['W']:.3g} N/mm" if j == 0 else None
                a1.plot(st["x"], st["p"], color=c, ls=ls, lw=1, label=lab)
                a2.plot(st["x"], 1e3 * np.asarray(st["h"]), color=c, ls=ls, lw=1)
            handles.append(Line2D([], [], color="k", ls=ls, lw=1, label=var["label"]))
        a1.set_ylabel("pressure p (MPa)")
        a1.legend(fontsize=7, ncol=2)
        a1.grid(alpha=0.3)
        a1.set_title("coated layer: " + ("finite deformation vs geometrically linear"
                                         if profile["compare"] == "linear"
                                         else "lubrication surface S_α"))
        a2.legend(handles=handles, fontsize=7)
        a2.set_ylabel("film thickness h (µm)")
        a2.set_yscale("log")
        a2.set_xlabel("x (mm, cylinder frame)")
        a2.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(outdir / cls.COMPARE_PLOT[profile["compare"]], dpi=120)
        plt.close(fig)


def mesh_convergence(v, levels=(0, 1, 2), W=None, steps=None, comm=MPI.COMM_WORLD):
    """Film measures at one load W for the mesh levels ``levels`` (all else as in ``v``).

    Each level is a separate problem (element size 0.04/2^level mm along Γ_l),
    loaded in ``steps`` increments (default ``v["steps"]``) to W (default
    ``v["W"]``).  Returns a list of dicts (level, h_fine, num_dofs, h_min,
    h_central, p_max, newton_iterations) and, from the second level on, the
    differences ``d_h_min``, ``d_p_max`` to the previous level (relative to the
    finer value).
    """
    W = v["W"] if W is None else W
    steps = v["steps"] if steps is None else steps
    rows = []
    for level in levels:
        vv = dict(v, mesh=int(level), W=W, steps=steps)
        prob = EHLCylinderLayerCase.build(vv, comm)
        control = LoadControl(prob)
        control.sweep([W * (k + 1) / steps for k in range(steps)])
        m = prob.measures()
        row = {"level": int(level), "h_fine": 0.04 / 2 ** int(level),
               "num_dofs": prob.solver.num_dofs, "h_min": m["h_min"],
               "h_central": m["h_central"], "p_max": m["p_max"],
               "newton_iterations": [list(t) for t in control.trials]}
        if rows:
            for k in ("h_min", "p_max"):
                row[f"d_{k}"] = abs(row[k] - rows[-1][k]) / abs(row[k])
        rows.append(row)
    return rows
