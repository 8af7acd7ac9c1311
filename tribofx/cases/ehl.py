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

Results: minimum film h_min, central film h_central (below the cylinder axis),
peak pressure p_max, friction coefficient (tangential film force on the layer /
W), per load step; profiles p(x), h(x) (``profiles.png``); VTX of u and p.
"""

import math

import numpy as np
from mpi4py import MPI

from ..ehl_problem import EHLProblem, LoadControl, rigid_clearance
from ..forms.hyperelastic import lame_parameters
from ..meshes.layer import BOTTOM, COATING, LAYER, LUBRICATED, coated_layer
from ..newton import NewtonDivergence
from ..params import InputError, Param

__all__ = ["EHLCylinderLayerCase", "cylinder_arc"]


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
    )

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
        """Load sweep W/steps … W; records the per-step film measures."""
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

    @staticmethod
    def _report(prob, steps, profiles, v, record):
        if steps["W"]:
            for k, unit in (("h_min", "mm"), ("h_central", "mm"), ("p_max", "MPa"),
                            ("friction_coefficient", "-")):
                record.result(k, steps[k][-1], unit)
            record.result("W_reached", steps["W"][-1], "N/mm")
        units = {"W": "N/mm", "h_min": "mm", "h_central": "mm", "p_max": "MPa",
                 "friction_coefficient": "-", "clearance": "mm"}
        for k, vals in steps.items():
            record.result(f"steps_{k}", list(vals), units[k])
        record.result("mu_U", v["mu"] * v["U"], "N/mm")
        if prob.mesh.comm.rank == 0 and profiles:
            record.profile = {"model": v["model"], "steps": profiles}

    @staticmethod
    def vtx_fields(prob):
        """Displacement (bulk) and film pressure (Γ_l submesh)."""
        return {"displacement": [prob.u], "pressure": [prob.p]}

    @staticmethod
    def plot(profile, outdir):
        """Pressure and film-thickness profiles at every load step (``profiles.png``)."""
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

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
