"""Soft-EHL: elastic ball sliding against a rigid plane (chapter §8.3, 3D quarter model).

A neo-Hookean ball (radius R, centre (0, 0, R)) is pressed with the load W
against the rigid plane and slides on it (ball-on-disc, pure sliding, curvature
of the track neglected).  Quarter model: lower hemisphere, half y ≥ 0, the
sliding direction x in the symmetry plane y = 0 (u_y = 0); the mid-plane z = R
moves as a rigid plane (here: held, and the plane z = z_p = −s moves, the same
rigid translation; s found by a secant iteration for each load).  Ball frame:
the ball material is at rest, the plane slides with V = 2U e_x, the mean
entrainment speed is v̄ = U e_x (U = V/2; the chapter's control parameter is μU).

Film (forms/ehl.py, chapter §6–7): lubrication surface S = P(γ_l) on the plane
(y = x − (x·e_z − z_p) e_z, ν = e_z, h = x_z − z_p, ∂P/∂x = I − e_z⊗e_z), steady
Reynolds (49) on S pulled back to the lubricated cap Γ_l (polar angle ≤ θ_l),
p = 0 on the cap's boundary circle, zero flux on y = 0, penalty cavitation,
SUPG.  Traction (46) on the ball: −p n − (μ/h)(0 − V) − (h/2) grad_S p
(``shear`` switches the two shear terms: "no friction stresses").  ``model=linear``
is classical EHL: geometry of the undeformed ball, h linear in u, small-strain
Hooke solid.  Unknowns u, u_s (trace), p, g = Grad_Γ p (vector DG0); one
monolithic Newton with the exact tangent (tribofx/ehl_ball_problem.py).

Default data (mm, N, s, MPa), in the spirit of Stupkiewicz et al. (2016,
Tribol. Int.; ball R = 12.7 mm, soft-EHL, W up to 40 N with a contact radius
≈ R/2, μU ≈ 0.01–10 N/m):

* R = 12.7 mm (1/2-inch ball); E = 1.19 MPa, ν = 0.45, so that
  E* = E/(1 − ν²) = 1.49 MPa ≈ 240/R² MPa and the Hertz radius
  a = (3WR/(4E*))^{1/3} ≈ R/2 at W = 40 N.  ν = 0.45 (not 0.49): P1 tetrahedra
  lock for ν → 0.5; the Hertz/Hamrock–Dowson references depend on E* only;
* μ = 1e-8 MPa·s (10 mPa·s), U = 1e4 mm/s: μU = 1e-4 N/mm (0.1 N/m, close to
  the 0.078 N/m of Fig. 26);
* W = 10 N in ``steps`` = 3 increments; cap θ_l = 40°; mesh: element size
  a/(4·2^mesh) within 1.6 a of the contact point (a at the final load),
  ``mesh`` = 1 (≈ 11k unknowns, ≈ 40 s for the default sweep on one core).

Load path: for a(W) ≤ R/3 (W ≲ 12 N) each load starts from the Hertz state and
the plane position is found by a secant in ln W.  Larger loads (a → R/2,
finite strain), where the coupled solve from a Hertz state does not converge,
use displacement control on a thick film: at ``start_speed``·U (default 30,
film ≈ 9× thicker) from the Hertz state at min(W/steps, W/4) the plane is
lowered step by step (each step from the last converged state, step cutting,
converged films with min h ≤ 0 rejected), the target load is hit by a secant
between the bracketing converged states, then U is continued down to U at
fixed load.  Penalty, SUPG and row scales follow the load and the speed.

Limits (measured): W = 40 N (a = 6.34 mm ≈ R/2, needs ``theta_l`` ≥ 49°, e.g. 55)
runs on mesh 0 (2.4k unknowns, ≈ 13 s) down to μU = 1 N/m (U = 1e5 mm/s with
the default μ); below that the side-lobe minimum film collapses (min h → 0,
the chapter's "severe conditions") on mesh 0; on mesh 1 at W = 20 N the same
happens near μU = 0.1 N/m.  Thinner films need finer meshes than levels 0–1;
W = 40 N on mesh 1 (three variants) did not finish within 7 min on one core.
P1 displacement shows the zig-zag oscillations of p and h the chapter
describes (§8.1) at level 1.

    tribofx run ehl-ball --set W=40 --set theta_l=55 --set U=3e5 --set mesh=0

``compare=all`` runs the load sweep for the full model, the model without
shear tractions and the geometrically linear model in one run (Fig. 26; results
prefixed ``full_``, ``no-shear_``, ``linear_``).  ``speeds`` (mm/s) continues every
variant at the final load in U and records the friction coefficient (friction
force / W) against μU (Fig. 27).

Results: h_central (film on the symmetry axis at x = 0), h_min (and where),
p_max, friction coefficient (x-force of the traction that loads the ball / W;
without shear tractions only its pressure part) and the Couette friction
coefficient (drag ∫ (μ/h) 2U ds / W, for every variant), the plane position,
per load step; Hertz and
Hamrock–Dowson (1978) references at the final load; plots ``film_map.png``
(h over the (x, y) projection), ``centerline.png`` (p, h on y = 0, every
variant), ``friction_vs_speed.png``; VTX of u (bulk) and p (cap).
"""

import math

import numpy as np
from mpi4py import MPI

from ..ehl_ball_problem import BallLoadControl, EHLBallProblem
from ..forms.hyperelastic import lame_parameters
from ..meshes.ball import LUBRICATED, MIDPLANE, SYMMETRY, cap_height, quarter_ball
from ..newton import NewtonDivergence
from ..params import InputError, Param
from ..references import composite_modulus, hamrock_dowson, hertz

__all__ = ["EHLBallCase"]


class EHLBallCase:
    """Case ``ehl-ball``; see the module docstring."""

    name = "ehl-ball"
    doc = "soft-EHL: elastic ball sliding on a rigid plane (3D, finite/no-shear/linear)"
    params = (
        Param("W", float, 10.0, "N", "final load on the whole ball", lower=0.0),
        Param("steps", int, 3, "-", "load increments (W/steps, …, W)", lower=1, upper=100,
              closed=True),
        Param("mu", float, 1e-8, "MPa·s", "viscosity (1e-8 MPa·s = 10 mPa·s)", lower=0.0),
        Param("U", float, 1e4, "mm/s", "entrainment speed U = V/2 (plane slides at 2U)",
              lower=0.0),
        Param("R", float, 12.7, "mm", "ball radius", lower=0.0),
        Param("E", float, 1.19, "MPa", "Young's modulus of the ball", lower=0.0),
        Param("nu", float, 0.45, "-", "Poisson's ratio of the ball", lower=-1.0, upper=0.5),
        Param("theta_l", float, 40.0, "deg", "polar angle of the lubricated cap", lower=5.0,
              upper=75.0, closed=True),
        Param("model", str, "finite", "-", "finite deformation or geometrically linear (EHL)",
              choices=("finite", "linear")),
        Param("shear", bool, True, "-", "Couette and Poiseuille shear tractions on the ball"),
        Param("supg", bool, True, "-", "SUPG stabilisation of the Reynolds equation"),
        Param("penalty", float, 1e-4, "-",
              "relative cavitation penalty ε/ε_ref, ε_ref = 12 μ a²/h_c³ (Hertz a, "
              "Hamrock–Dowson h_c at W)", lower=0.0),
        Param("mesh", int, 1, "-", "element size a/(4·2^mesh) near the contact", lower=0,
              upper=3, closed=True),
        Param("h_coarse", float, 4.0, "mm", "element size far from the contact", lower=0.0),
        Param("start_speed", float, 30.0, "-",
              "loads with Hertz a(W) > R/3: each load is reached at start_speed·U by "
              "displacement control (thick film), then U is continued down to U",
              lower=1.0, closed=True),
        Param("speeds", str, "", "mm/s",
              "comma-separated entrainment speeds for continuation in U at the final load "
              "(empty: none); records the friction coefficient vs μU"),
        Param("compare", str, "none", "-",
              "all: load sweep (and speeds) of the full model, without shear tractions and "
              "geometrically linear in one run", choices=("none", "all")),
    )

    #: variants of ``compare=all``: (prefix, label, overrides)
    VARIANTS = (("full", "finite deformation", {"model": "finite", "shear": True}),
                ("no-shear", "finite, no shear tractions", {"model": "finite", "shear": False}),
                ("linear", "geometrically linear", {"model": "linear", "shear": True}))
    STEP_UNITS = {"W": "N", "h_central": "mm", "h_min": "mm", "p_max": "MPa",
                  "friction_coefficient": "-", "couette_friction_coefficient": "-",
                  "clearance": "mm"}

    @staticmethod
    def e_star(v):
        """Plane-strain modulus E* = E/(1 − ν²) of the ball against the rigid plane (MPa)."""
        return composite_modulus(v["E"], v["nu"])

    @staticmethod
    def hertz_contact(v, W=None):
        """Hertz contact of the ball on the rigid plane at W (default ``v["W"]``, N)."""
        return hertz(v["W"] if W is None else W, v["R"], v["E"], v["nu"])

    @classmethod
    def validate(cls, v):
        """Check that the cap holds the contact and the inlet: R sin θ_l ≥ 1.5 a(W)."""
        a = cls.hertz_contact(v).a
        r_cap = v["R"] * math.sin(math.radians(v["theta_l"]))
        if r_cap < 1.5 * a:
            raise InputError(f"cap radius R sin θ_l = {r_cap:.3g} mm < 1.5 a = {1.5 * a:.3g} mm "
                             f"(Hertz a at W = {v['W']} N): increase theta_l")
        if not v["U"] > 0 or not v["mu"] > 0:
            raise InputError("U and mu must be positive (entrainment)")
        try:
            speeds = cls.speed_list(v)
        except ValueError as err:
            raise InputError(f"speeds = {v['speeds']!r}: {err}") from None
        if any(not U > 0 for U in speeds):
            raise InputError("speeds must be positive (mm/s)")

    @staticmethod
    def speed_list(v):
        """Return the continuation speeds (mm/s) of ``speeds``."""
        return [float(t) for t in v["speeds"].replace(";", ",").split(",") if t.strip()]

    @classmethod
    def scales(cls, v, W=None, U=None):
        """Hertz a (mm), p0 (MPa), Hamrock–Dowson h_c (mm) and penalty ε (MPa·s/mm)."""
        W = v["W"] if W is None else W
        U = v["U"] if U is None else U
        h = cls.hertz_contact(v, W)
        a, p0 = h.a, h.p0
        h_c = hamrock_dowson(W, v["mu"], U, v["R"], cls.e_star(v))[0]
        return a, p0, h_c, v["penalty"] * 12 * v["mu"] * a * a / h_c**3

    @classmethod
    def build(cls, v, comm=MPI.COMM_WORLD):
        """Mesh and :class:`EHLBallProblem` (unloaded)."""
        a = cls.hertz_contact(v).a
        th = math.radians(v["theta_l"])
        h_fine = a / (4 * 2 ** v["mesh"])
        msh, ct, ft = quarter_ball(v["R"], th, h_fine, max(v["h_coarse"], h_fine),
                                   1.6 * a, comm)
        mu, lm = lame_parameters(v["E"], v["nu"])
        W1 = v["W"] / v["steps"]
        _, p0, h_c, eps = cls.scales(v, W1)
        return EHLBallProblem(msh, ct, ft, "neo-hookean", {"mu": mu, "lmbda": lm}, LUBRICATED,
                              MIDPLANE, SYMMETRY, v["R"], cap_height(v["R"], th), v["U"],
                              v["mu"], model=v["model"], shear=v["shear"], supg=v["supg"],
                              eps=eps if v["penalty"] > 0 else None, p_c=p0, h_ref=h_c)

    @classmethod
    def large_load(cls, v):
        """Return True when the Hertz radius a(W) exceeds R/3 (W > 11.9 N, default ball)."""
        return cls.hertz_contact(v).a > v["R"] / 3

    @classmethod
    def load_sweep(cls, prob, v, on_step=None, verbose=False):
        """Reach the loads W/steps, …, W at the speed U; return the controller.

        a(W) ≤ R/3: Hertz start at each load, secant on the plane position;
        larger loads: the thick-film path (:meth:`thick_film_sweep`).
        """
        if cls.large_load(v):
            return cls.thick_film_sweep(prob, v, on_step, verbose)
        W1 = v["W"] / v["steps"]
        _, _, h_c, _ = cls.scales(v, W1)
        prob.hertz_start(W1, cls.e_star(v), h_c)
        its0 = prob.solve(verbose=verbose).iterations
        if not prob.min_film() > 0:
            raise NewtonDivergence(
                f"the first load W = {W1:g} N converged to a film with h <= 0 (contact under-"
                "resolved by the mesh): raise mesh or use fewer load steps")
        d = cls.hertz_contact(v).delta
        control = BallLoadControl(prob, ds0=0.1 * h_c, max_step=0.1 * d, verbose=verbose)
        targets = [v["W"] * (k + 1) / v["steps"] for k in range(v["steps"])]
        first = [True]

        def step(W, its, final):
            if first[0]:
                its = [its0, *its]
                first[0] = False
            if on_step is not None:
                on_step(W, its, final)

        if prob.load() > 0:
            control.points = [(float(prob.s.value), math.log(prob.load()))]
        control.sweep(targets, step, restart=lambda W: prob.hertz_start(
            W, cls.e_star(v), cls.scales(v, W)[2]))
        return control

    @classmethod
    def thick_film_sweep(cls, prob, v, on_step=None, verbose=False):
        """Reach each load by displacement control on a thick film, then continue down in U.

        At large loads (a → R/2, finite strain) the coupled solve from a Hertz
        state does not converge, so: (i) at the speed U_s = ``start_speed``·U
        (film ≈ start_speed^0.64 thicker) the Hertz state at W_0 = min(W/steps, W/4)
        (a_0 ≈ 0.63 a, resolved by the mesh made for a) is solved; (ii) the plane
        is lowered step by step (displacement control,
        :meth:`BallLoadControl.indent`, each step from the last converged state,
        step cutting, h ≤ 0 rejected) until the film carries the next target
        load, hit by the secant; (iii) from that state U is continued down to U
        at fixed load (:meth:`BallLoadControl.speed_sweep`, plane shifted by the
        Hamrock–Dowson film change, cut in log U on failure) and the load step
        is recorded; (iv) the next load continues from the state at U_s.  If the
        start solve fails, U_s ×0.3, ×3, ×0.1, ×10 are tried in turn.
        ``on_step(W, its, final)`` gets all Newton iterations of the load.
        """
        E_s, U = cls.e_star(v), v["U"]
        Us = v["start_speed"] * U
        W0 = min(v["W"] / v["steps"], 0.25 * v["W"])

        def scales_at(W, Uv):
            _, p0, h_c, eps = cls.scales(v, W, Uv)
            return p0, eps, h_c

        # the coupled solve from the Hertz state is not monotone in the start film on
        # coarse meshes: if it fails, try start speeds ×0.3, ×3, ×0.1, ×10 (never below U)
        for f in (1.0, 0.3, 3.0, 0.1, 10.0):
            Ut = max(U, f * Us)
            prob.set_speed(Ut, *scales_at(W0, Ut))
            prob.hertz_start(W0, E_s, cls.scales(v, W0, Ut)[2])
            try:
                its0 = prob.solve(verbose=verbose).iterations
            except NewtonDivergence:
                continue
            if prob.min_film() > 0:
                Us = Ut
                break
        else:
            raise NewtonDivergence(f"the start load W = {W0:g} N did not converge (speeds "
                                   f"{0.1 * Us:g}–{10 * Us:g} mm/s): change start_speed or mesh")
        d = cls.hertz_contact(v).delta
        control = BallLoadControl(prob, ds0=0.1 * cls.scales(v, W0, Us)[2], max_step=0.1 * d,
                                  verbose=verbose)
        its_pending = [its0]
        for k in range(v["steps"]):
            Wk = v["W"] * (k + 1) / v["steps"]
            its = its_pending + control.indent(Wk, 0.05 * d, lambda W: scales_at(W, Us))
            its_pending = []
            carrier = (prob.state(), list(control.points), control.ds0)
            if Us != U:
                control.speed_sweep([U], lambda Uv, Wk=Wk: scales_at(Wk, Uv),
                                    lambda Uv, i, final, its=its: its.extend(i), max_cuts=6)
            if on_step is not None:
                on_step(Wk, its, True)
            if k + 1 < v["steps"] and Us != U:
                prob.restore(carrier[0])
                control.points, control.ds0 = carrier[1], carrier[2]
                prob.set_speed(Us, *scales_at(Wk, Us))
        return control

    @classmethod
    def run(cls, v, record, progress=None, verbose=False):
        """Load sweep (and speed sweep) of each variant; results prefixed by the variant."""
        variants = (cls.VARIANTS if v["compare"] == "all"
                    else (("", v["model"], {}),))
        record.result("mu_U", v["mu"] * v["U"], "N/mm")
        a, p0, _, _ = cls.scales(v)
        hc, hm = hamrock_dowson(v["W"], v["mu"], v["U"], v["R"], cls.e_star(v))
        record.result("hertz_a", a, "mm")
        record.result("hertz_p0", p0, "MPa")
        record.result("hamrock_dowson_h_c", hc, "mm")
        record.result("hamrock_dowson_h_min", hm, "mm")
        record.data["variant_newton_iterations"] = {}
        profile = {"variants": {}, "W": v["W"]}
        first = None
        for name, label, over in variants:
            vv = dict(v, **over)
            prefix = f"{name}_" if name else ""
            prob = cls.build(vv)
            first = first or prob
            record.data["num_dofs"] = prob.solver.num_dofs
            steps = {k: [] for k in cls.STEP_UNITS}
            its_all = []
            record.data["variant_newton_iterations"][name or vv["model"]] = its_all
            speed = {k: [] for k in ("U", "mu_U", "friction_coefficient",
                                     "couette_friction_coefficient", "h_central", "h_min",
                                     "p_max")}
            var = {"label": label, "shear": vv["shear"]}
            profile["variants"][name or vv["model"]] = var

            def on_step(W, its, final, prob=prob, steps=steps, its_all=its_all):
                its_all.append(its)
                record.data["newton_iterations"].append(its)
                m = prob.measures()
                for k in steps:
                    steps[k].append(m[k])
                if progress is not None:
                    progress.update(1)

            def on_speed(U, its, final, prob=prob, speed=speed, its_all=its_all):
                its_all.append(its)
                record.data["newton_iterations"].append(its)
                if final:
                    m = prob.measures()
                    speed["U"].append(U)
                    speed["mu_U"].append(v["mu"] * U)
                    for k in ("friction_coefficient", "couette_friction_coefficient",
                              "h_central", "h_min", "p_max"):
                        speed[k].append(m[k])

            try:
                control = cls.load_sweep(prob, vv, on_step, verbose)
                cls._profile(prob, var)
                speeds = cls.speed_list(v)
                if speeds:
                    on_speed(v["U"], [], True)
                    control.speed_sweep(
                        speeds, lambda U, vv=vv: cls.speed_scales(vv, U), on_speed,
                        restart=None if cls.large_load(vv) else (
                            lambda U, vv=vv, prob=prob: prob.hertz_start(
                                vv["W"], cls.e_star(vv), cls.scales(vv, U=U)[2])))
            except NewtonDivergence as err:
                err.problem = prob
                raise
            finally:
                cls._report(steps, speed, record, prefix)
                if prob.mesh.comm.rank == 0:
                    var["speed"] = {k: list(x) for k, x in speed.items()}
                    record.profile = profile
        return first

    @classmethod
    def speed_scales(cls, v, U):
        """(p_c, ε, h_ref) at the final load and entrainment speed U."""
        _, p0, h_c, eps = cls.scales(v, U=U)
        return p0, eps, h_c

    @staticmethod
    def _profile(prob, var):
        prof = prob.profile()
        if prob.mesh.comm.rank == 0:
            xx, hh, pp = prob.centerline(prof)
            var.update({"xy": prof["xy"], "h": prof["h"], "p": prof["p"], "x_axis": xx,
                        "h_axis": hh, "p_axis": pp})

    @classmethod
    def _report(cls, steps, speed, record, prefix):
        if steps["W"]:
            for k in ("h_central", "h_min", "p_max", "friction_coefficient",
                      "couette_friction_coefficient", "clearance"):
                record.result(prefix + k, steps[k][-1], cls.STEP_UNITS[k])
            record.result(prefix + "W_reached", steps["W"][-1], "N")
        for k, vals in steps.items():
            record.result(f"{prefix}steps_{k}", list(vals), cls.STEP_UNITS[k])
        if len(speed["U"]) > 1:
            units = {"U": "mm/s", "mu_U": "N/mm", "friction_coefficient": "-",
                     "couette_friction_coefficient": "-", "h_central": "mm", "h_min": "mm",
                     "p_max": "MPa"}
            for k, vals in speed.items():
                record.result(f"{prefix}speed_{k}", list(vals), units[k])

    @staticmethod
    def vtx_fields(prob):
        """Displacement (bulk) and film pressure (cap submesh)."""
        return {"displacement": [prob.u], "pressure": [prob.p]}

    @staticmethod
    def plot(profile, outdir):
        """film_map.png, centerline.png and (with speeds) friction_vs_speed.png."""
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import matplotlib.tri as mtri

        variants = {k: var for k, var in profile["variants"].items() if "xy" in var}
        if not variants:
            return
        name, var = next(iter(variants.items()))
        xy = np.asarray(var["xy"])
        x = np.r_[xy[:, 0], xy[:, 0]]
        y = np.r_[xy[:, 1], -xy[:, 1]]
        h = 1e3 * np.r_[var["h"], var["h"]]
        tri = mtri.Triangulation(x, y)
        fig, ax = plt.subplots(figsize=(6, 5))
        hmax = 4 * float(np.min(h))
        cs = ax.tricontourf(tri, np.minimum(h, hmax), levels=30, cmap="viridis")
        fig.colorbar(cs, ax=ax, label="film thickness h (µm, clipped)")
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm, inlet on the left)")
        ax.set_ylabel("y (mm)")
        ax.set_title(f"{var['label']}: W = {profile['W']:g} N")
        fig.tight_layout()
        fig.savefig(outdir / "film_map.png", dpi=120)
        plt.close(fig)

        styles = ("-", "--", "-.")
        fig, (a1, a2) = plt.subplots(2, 1, figsize=(6.5, 6.5), sharex=True)
        for j, var in enumerate(variants.values()):
            a1.plot(var["x_axis"], var["p_axis"], ls=styles[j % 3], label=var["label"])
            a2.plot(var["x_axis"], 1e3 * np.asarray(var["h_axis"]), ls=styles[j % 3])
        a1.set_ylabel("pressure p (MPa)")
        a1.legend(fontsize=8)
        a1.grid(alpha=0.3)
        a1.set_title(f"symmetry line y = 0, W = {profile['W']:g} N")
        a2.set_ylabel("film thickness h (µm)")
        a2.set_yscale("log")
        a2.set_xlabel("x (mm)")
        a2.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(outdir / "centerline.png", dpi=120)
        plt.close(fig)

        sp = {k: var["speed"] for k, var in profile["variants"].items()
              if len(var.get("speed", {}).get("mu_U", [])) > 1}
        if sp:
            fig, ax = plt.subplots(figsize=(5, 4))
            for j, (k, s) in enumerate(sp.items()):
                order = np.argsort(s["mu_U"])
                var = profile["variants"][k]
                # without shear tractions the film force has no drag: plot the Couette drag
                key = ("friction_coefficient" if var.get("shear", True)
                       else "couette_friction_coefficient")
                lab = var["label"] + ("" if key == "friction_coefficient" else " (Couette drag)")
                ax.loglog(1e3 * np.asarray(s["mu_U"])[order], np.asarray(s[key])[order],
                          "o" + styles[j % 3], label=lab)
            ax.set_xlabel("μU (N/m)")
            ax.set_ylabel("friction coefficient")
            ax.legend(fontsize=8)
            ax.grid(alpha=0.3, which="both")
            fig.tight_layout()
            fig.savefig(outdir / "friction_vs_speed.png", dpi=120)
            plt.close(fig)
