"""Reciprocating O-ring seal: axisymmetric soft EHL (chapter §8.1, Figs. 15–19).

An elastomeric O-ring of cross-section diameter d sits in a housing groove and
seals the pressure p_s against a rod of radius r_rod sliding axially with speed
U (U > 0 outstroke: the rod moves towards the air side, +z; U < 0 instroke).
Axisymmetric about the rod axis, mesh coordinates (r, z):

* seal: nearly incompressible Mooney–Rivlin, ψ = μ₁/2 (Ī₁ − 3) + μ₂/2 (Ī₂ − 3)
  + κ/2 (J − 1)², 3×3 F with hoop stretch r/R, weight 2πR (forms/hyperelastic);
* housing: groove bottom r = r_g = r_rod + d(1 − squeeze) and air-side wall,
  rigid planes, frictionless augmented-Lagrangian contact; sealed side open;
* sealed pressure: follower pressure p_s on the quarter of the ring boundary
  facing the sealed side (225° ≤ φ ≤ 315°) and p = p_s at the sealed-side end
  of the film (simple robust choice: the fluid at p_s reaches the film through
  the sealed-side flank of Γ_l; the arc between the flank and the groove bottom
  is loaded by p_s whether or not it touches the bottom);
* rod: soft-EHL film on the inner quarter arc Γ_l (135° ≤ φ ≤ 225°): S = P(γ_l)
  on the rod cylinder, h = r − r_rod, v̄ = ½U e_z, steady Reynolds equation (49)
  on the surface of revolution (weight 2π r_rod times the meridian stretch),
  p = p_s / 0 at the sealed / air end, penalty cavitation ε⁻¹ min(p, 0), SUPG;
  fluid traction (46): pressure (axisymmetric Nanson), Couette (μ/h)U e_z and
  Poiseuille −(h/2) grad_S p shear (forms/ehl_axisym.py).

Solution path: the ring starts ``gap0`` clear of the rod with the film on; the
groove bottom is moved in ``mount_steps`` steps to r_g (squeeze) at the mounting
pressure 0.1 MPa and the mounting speed U_m = sign(U) max(|U|, 1000 mm/s) (a
thicker film is easier); p_s is raised to the first target, the speed lowered
geometrically to U, then the other p_s targets follow.  Each continuation
step is cut on Newton failure (the last converged state is kept and written).

Default data (mm, N, s, MPa), after Stupkiewicz (2009) and Stupkiewicz &
Marciniszyn (Tribol. Int. 42, 2009) where the chapter fixes them:

* μ₁ + μ₂ = 3.66 MPa (chapter §8.1); split μ₁ = 2.93, μ₂ = 0.73 (μ₂/μ₁ = 0.25,
  a common ratio for NBR, our choice); κ = 1000 (μ₁ + μ₂) = 3660 MPa;
* d = 3.5 mm, r_rod = 10 mm, squeeze 10 % (typical dynamic O-ring gland);
* oil viscosity μ = 5e-8 MPa·s (0.05 Pa·s), U = 400 mm/s (Fig. 18: outstroke,
  p_s = 1 MPa, U = 400 mm/s);
* mesh density n: element size 0.1/n mm on Γ_l, 0.4/n mm in the bulk; P1
  displacement (default; the chapter's zigzag film oscillations come from the
  piecewise-linear boundary), P1 pressure.

``study=mesh`` repeats the outstroke at the first p_s on the densities
``mesh_levels`` (Figs. 18–19) and reports an oscillation indicator per density
(mean |Δ²h| / 4h̄ in the loaded zone p − p_s > (p_max − p_s)/2: the relative
zigzag amplitude)
and the change of the mean film h̄ of that zone from level to level.

Results per stroke and p_s (prefix ``out_``/``in_`` and ``ps<value>_``): p_max,
h_min and its position, h at the pressure peak, mean film h_mean of the loaded
zone, flux q = h v̄ − h³/(12μ) ∂p/∂z per circumference (median over the loaded
zone), leakage 2π r_rod q, radial load and friction force per circumference,
oscillation indicator, axial equilibrium error (sum of axial forces / axial
force of p_s).  Plots ``profiles.png`` (Fig. 17, out vs in), ``mesh_study.png``
(Figs. 18–19).
"""

import math
import time

import numpy as np
from mpi4py import MPI

from ..meshes.oring import oring_section
from ..newton import NewtonDivergence
from ..oring_problem import ORingProblem
from ..params import InputError, Param
from ..references import inverse_film

__all__ = ["EHLORingCase", "axial_balance", "build", "solve_to"]

P_MOUNT = 0.1        # MPa, sealed pressure during the squeeze
W_REF = 20.0         # MPa/mm, nominal inlet gradient of the film scale h_ref


def _floats(text, name):
    try:
        vals = [float(t) for t in str(text).replace(";", ",").split(",") if t.strip()]
    except ValueError:
        raise InputError(f"parameter {name!r} expects comma-separated numbers") from None
    if not vals:
        raise InputError(f"parameter {name!r} is empty")
    return vals


def geometry(v):
    """Centre, radius, rod radius, final groove bottom and air-side wall (mm)."""
    a = 0.5 * v["d"]
    r_rod = v["r_rod"]
    center = (r_rod + a + v["gap0"], 0.0)
    return center, a, r_rod, r_rod + v["d"] * (1 - v["squeeze"]), a - 0.005


def build(v, U, mesh=None, comm=MPI.COMM_WORLD, dry=False):
    """ORingProblem of the values ``v`` at speed U (mm/s) and mesh density ``mesh``."""
    center, a, r_rod, r_g, z_w = geometry(v)
    msh, ct, ft = oring_section(*center, a, v["mesh"] if mesh is None else mesh, comm=comm)
    mat = {"mu1": v["mu1"], "mu2": v["mu2"], "kappa": v["kappa"]}
    return ORingProblem(msh, ct, ft, center, a, r_rod, r_g, z_w, mat, v["mu"], U,
                        min(P_MOUNT, _floats(v["p_s"], "p_s")[0]), inverse_film(v["mu"], U, W_REF),
                        eps_rel=v["eps"], supg=v["supg"], degree=v["degree"], dry=dry)


def solve_to(prob, v, U, p_s_targets, on_state=None, verbose=False):
    """Mount, raise p_s, go to speed U, then the other p_s; on_state(p_s) after each target.

    Returns the Newton iterations per continuation step.
    """
    its = prob.mount(v["mount_steps"], verbose=verbose)
    first = True
    for p_s in p_s_targets:
        its += prob.ramp(p_s, v["ramp_steps"], verbose=verbose)
        if first and not prob.dry and prob.U != U:
            its += prob.speed(U, v["speed_steps"], verbose=verbose)
        first = False
        if on_state is not None:
            on_state(p_s)
    return its


def axial_balance(prob):
    """Sum of the axial forces on the ring relative to the axial force of p_s (−)."""
    f = prob.forces()
    total = sum(val[1] for val in f.values())
    return abs(total) / abs(f["sealed"][1])


class EHLORingCase:
    """Case ``ehl-oring``; see the module docstring."""

    name = "ehl-oring"
    doc = "soft-EHL of a reciprocating O-ring seal (axisymmetric, housing contact)"
    params = (
        Param("p_s", str, "1", "MPa", "sealed pressures (comma-separated, increasing)"),
        Param("U", float, 400.0, "mm/s", "rod speed (> 0 outstroke, < 0 instroke)"),
        Param("stroke", str, "single", "-", "single (sign of U) or both (U and −U)",
              choices=("single", "both")),
        Param("mu", float, 5e-8, "MPa·s", "oil viscosity", lower=0),
        Param("mesh", int, 4, "-", "mesh density n (element 0.1/n mm on the film arc)",
              lower=1, upper=32, closed=True),
        Param("degree", int, 1, "-", "Lagrange degree of the displacement", choices=(1, 2)),
        Param("squeeze", float, 0.1, "-", "radial squeeze (d − groove depth)/d", lower=0,
              upper=0.3),
        Param("d", float, 3.5, "mm", "cross-section diameter", lower=0),
        Param("r_rod", float, 10.0, "mm", "rod radius", lower=0),
        Param("mu1", float, 2.93, "MPa", "Mooney–Rivlin μ₁", lower=0),
        Param("mu2", float, 0.73, "MPa", "Mooney–Rivlin μ₂", lower=0, closed=True),
        Param("kappa", float, 3660.0, "MPa", "bulk modulus", lower=0),
        Param("eps", float, 1e-4, "-", "cavitation penalty ε relative to 12μℓ²/h_ref³",
              lower=0),
        Param("supg", bool, True, "-", "SUPG in the Reynolds equation"),
        Param("gap0", float, 0.02, "mm", "initial clearance to the rod", lower=0),
        Param("mount_steps", int, 10, "-", "squeeze increments", lower=1),
        Param("ramp_steps", int, 4, "-", "p_s increments per target", lower=1),
        Param("speed_steps", int, 3, "-", "geometric speed increments", lower=1),
        Param("study", str, "none", "-", "none or mesh (density study, Figs. 18–19)",
              choices=("none", "mesh")),
        Param("mesh_levels", str, "1,2,4", "-", "densities of study=mesh"),
    )

    @staticmethod
    def validate(v):
        """Parse the lists and check the consistency of the values."""
        ps = _floats(v["p_s"], "p_s")
        if any(p <= 0 for p in ps):
            raise InputError("p_s must be > 0 MPa (frictionless housing: p_s holds the ring)")
        if ps != sorted(ps):
            raise InputError("p_s must be increasing")
        if v["U"] == 0:
            raise InputError("U must be nonzero (mm/s)")
        levels = _floats(v["mesh_levels"], "mesh_levels")
        if any(k < 1 or k != int(k) for k in levels):
            raise InputError("mesh_levels must be positive integers")
        if v["gap0"] >= 0.5 * v["d"]:
            raise InputError("gap0 must be below the cross-section radius")

    @classmethod
    def run(cls, v, record, progress=None, verbose=False):
        """Mount, pressurise and solve each stroke; optionally the mesh study."""
        comm = MPI.COMM_WORLD
        U = v["U"]
        speeds = [U] if v["stroke"] == "single" else [abs(U), -abs(U)]
        profiles = {"strokes": {}, "mesh": None, "U": abs(U)}
        prob = None
        for Us in speeds:
            tag = "out" if Us > 0 else "in"
            t0 = time.perf_counter()
            prob = build(v, math.copysign(max(abs(Us), 1000.0), Us))
            record.data["num_dofs"] = prob.num_dofs
            states = []

            def on_state(p_s, prob=prob, tag=tag, states=states):
                m = prob.measures()
                m["axial_balance"] = axial_balance(prob)
                for k, unit in cls.UNITS.items():
                    record.result(f"{tag}_ps{p_s:g}_{k}", m[k], unit)
                if prob.mesh.comm.rank == 0:
                    pr = prob.profile()
                    states.append({"p_s": p_s, **{k: pr[k].tolist() for k in ("z", "h", "p")}})
                else:
                    prob.profile()
                if progress is not None:
                    progress.update(1)

            try:
                its = solve_to(prob, v, Us, _floats(v["p_s"], "p_s"), on_state, verbose)
            except NewtonDivergence as err:
                err.problem = prob
                raise
            record.data["newton_iterations"].append({tag: its})
            record.result(f"{tag}_wall_time", time.perf_counter() - t0, "s")
            profiles["strokes"][tag] = states
        if v["study"] == "mesh":
            profiles["mesh"] = cls.mesh_study(v, record)
        record.result("p_s", _floats(v["p_s"], "p_s"), "MPa")
        if comm.rank == 0:
            record.profile = profiles
        return prob

    UNITS = {"p_max": "MPa", "z_p_max": "mm", "h_at_p_max": "mm", "h_mean": "mm", "h_min": "mm",
             "z_h_min": "mm", "flux": "mm^2/s", "leakage": "mm^3/s",
             "load_per_circumference": "N/mm", "friction_force_per_circumference": "N/mm",
             "oscillation": "-", "flux_spread": "-", "axial_balance": "-"}

    @classmethod
    def mesh_study(cls, v, record):
        """Outstroke at the first p_s on the densities ``levels``; returns the profiles."""
        rows, out = [], []
        U = abs(v["U"])
        for n in [int(k) for k in _floats(v["mesh_levels"], "mesh_levels")]:
            t0 = time.perf_counter()
            prob = build(v, max(U, 1000.0), mesh=n)
            its = solve_to(prob, v, U, _floats(v["p_s"], "p_s")[:1])
            m = prob.measures()
            row = {"mesh": n, "num_dofs": prob.num_dofs, "h_at_p_max": m["h_at_p_max"],
                   "h_mean": m["h_mean"],
                   "h_min": m["h_min"], "p_max": m["p_max"], "oscillation": m["oscillation"],
                   "newton_iterations": its, "wall_time": time.perf_counter() - t0}
            if rows:
                row["d_h_mean"] = abs(row["h_mean"] - rows[-1]["h_mean"]) / row["h_mean"]
            rows.append(row)
            pr = prob.profile()
            if pr is not None:
                out.append({"mesh": n, **{k: pr[k].tolist() for k in ("z", "h", "p")}})
        record.result("mesh_study", rows)
        return out

    @staticmethod
    def vtx_fields(prob):
        """Displacement (bulk) and film pressure (Γ_l submesh)."""
        return {"displacement": [prob.u], "pressure": [prob.p]}

    @staticmethod
    def _h_scale(groups):
        """Largest film at the pressure peak over the plotted states (mm)."""
        hs = [st["h"][int(np.argmax(st["p"]))] for states in groups for st in states]
        return max(hs) if hs else 1e-3

    @classmethod
    def plot(cls, profile, outdir):
        """``profiles.png`` (p, h vs z per p_s, out solid / in dashed), ``mesh_study.png``."""
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, (a1, a2) = plt.subplots(2, 1, figsize=(6.5, 6.5), sharex=True)
        for tag, ls in (("out", "-"), ("in", "--")):
            states = profile["strokes"].get(tag, [])
            for k, st in enumerate(states):
                c = plt.cm.viridis(k / max(1, len(states) - 1))
                a1.plot(st["z"], st["p"], ls=ls, color=c, lw=1,
                        label=f"{tag}stroke, p_s = {st['p_s']:g} MPa")
                a2.plot(st["z"], 1e3 * np.asarray(st["h"]), ls=ls, color=c, lw=1)
        a1.set_ylabel("film pressure p (MPa)")
        a1.legend(fontsize=7)
        a1.grid(alpha=0.3)
        a1.set_title(f"O-ring seal, |U| = {profile['U']:g} mm/s")
        a2.set_ylabel("film thickness h (µm)")
        a2.set_ylim(0, 4e3 * cls._h_scale(profile["strokes"].values()))
        a2.set_xlabel("z (mm, position on the rod; air side > 0)")
        a2.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(outdir / "profiles.png", dpi=120)
        plt.close(fig)
        if profile.get("mesh"):
            fig, (a1, a2) = plt.subplots(2, 1, figsize=(6.5, 6.5), sharex=True)
            for st in profile["mesh"]:
                a1.plot(st["z"], st["p"], lw=1, marker=".", ms=2, label=f"density {st['mesh']}")
                a2.plot(st["z"], 1e3 * np.asarray(st["h"]), lw=1, marker=".", ms=2)
            a1.set_ylabel("film pressure p (MPa)")
            a1.legend(fontsize=7)
            a1.grid(alpha=0.3)
            a1.set_title("mesh-density study (outstroke)")
            a2.set_ylabel("film thickness h (µm)")
            a2.set_ylim(0, 4e3 * cls._h_scale([profile["mesh"]]))
            a2.set_xlabel("z (mm)")
            a2.grid(alpha=0.3)
            fig.tight_layout()
            fig.savefig(outdir / "mesh_study.png", dpi=120)
            plt.close(fig)
