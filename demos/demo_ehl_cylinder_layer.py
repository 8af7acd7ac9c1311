# ---
# jupytext:
#   text_representation:
#     extension: .py
#     format_name: light
# ---

# # Soft-EHL: a rigid cylinder sliding on a coated elastic layer
#
# This demo illustrates how to:
#
# * build a plane-strain hyperelastic **Body** of two materials (a soft layer and
#   a stiffer coating) that moves through its mesh with v = F V (eq. 26: the
#   frame of the cylinder);
# * add a lubricating **Film** on its top Γ_l against a rigid cylinder: the
#   steady Reynolds equation on the lubrication surface S = P(γ_l), the fluid
#   traction (46) on the layer, the exact UFL tangent of the coupling;
# * gather them in one **Problem** and control the load by the cylinder's
#   position with a **Continuation** (a secant on the measured film load, load
#   steps with step cutting);
# * switch to the geometrically linear model and to mass-conserving (JFO)
#   cavitation, and check against the rigid-cylinder (Swift–Stieber) solution.
#
# ## Equations
#
# With x = X + u on Γ_l, its projection y = P(x) on the cylinder and the normal ν,
# the film is h = (x − y)·ν (36–37); with A = (∂P/∂x) F (I − N⊗N) + ν⊗N the map of
# tangents of Γ_l to S, ds_S = |det A| dS and grad_S p = A⁻ᵀ Grad_Γ p.  The
# Reynolds equation (49) on S pulled back to Γ_l, with v̄ = ½ (I − ν⊗ν) F V (41),
#
# $$ \int_{S} \Big( \frac{h^3}{12\mu}\,\mathrm{grad}_S\, p - h\,\bar{v} \Big)
#    \cdot \mathrm{grad}_S\, \delta p \; ds
#    + \int_S \varepsilon^{-1} \min(p, 0)\, \delta p\, ds = 0, $$
#
# (SUPG, Remark 3.2; penalty cavitation → the Swift–Stieber conditions), and the
# virtual work (62) of the layer loaded by the nominal traction
# T = −p J F⁻ᵀN − j((μ/h) v_T + (h/2) grad_S p) (46).  JFO cavitation replaces the
# penalty by the void fraction λ and the weak form (57) with min(p/p_c, λ) = 0 (52).
#
# ## Changing it
#
#     tribofx run ehl-cylinder-layer --set W=1 --set steps=10          # Fig. 22 sweep
#     tribofx run ehl-cylinder-layer --set compare=linear              # both models, one plot
#     tribofx run ehl-cylinder-layer --set compare=alpha               # S_α, Fig. 23
#     tribofx run ehl-cylinder-layer --set cavitation=jfo --set speeds=3000,10000
#
# Units: mm, N, s, MPa (μU = 1e-4 N/mm = 0.1 N/m, as the chapter's Fig. 22).

# +
import argparse
import math
import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx / petsc4py)
import numpy as np
from mpi4py import MPI
from tribofx.forms.hyperelastic import lame_parameters
from tribofx.meshes.layer import BOTTOM, COATING, LAYER, LUBRICATED, coated_layer

from tribofx.body import Body
from tribofx.continuation import ConstantParameter, Continuation
from tribofx.hold import Hold
from tribofx.interfaces import JFO, Film, FilmScales, Fluid, Penalty
from tribofx.obstacles import rigid_cylinder
from tribofx.output import write_summary
from tribofx.plots import plot_film_profiles
from tribofx.problem import Problem
from tribofx.references import cylinder_references, rigid_clearance

parser = argparse.ArgumentParser(description="soft-EHL coated layer demo")
parser.add_argument("--quick", action="store_true", help="coarse mesh, P1, few loads (CI)")
parser.add_argument("--out", default=None, help="write summary.json and plots here")
args, _ = parser.parse_known_args()
comm = MPI.COMM_WORLD
# -

# ## The configuration
#
# Cylinder R = 10 mm; layer H = 5 mm, E = 10 MPa, coating t_c = 0.1 mm, E_c = 100 MPa,
# ν = 0.45 (neo-Hookean); μ = 0.1 Pa·s, U = 1 m/s; Γ_l: |X| ≤ 3 mm, elements
# 0.04 mm (``--quick``, P1) or 0.02 mm (P2) along it.

# +
R, H, t_c, x_l, mu, U = 10.0, 5.0, 0.1, 3.0, 1e-7, 1000.0
level, degree = (0, 1) if args.quick else (1, 2)
msh, cells, facets = coated_layer(3 * H, H, t_c, x_l, 0.04 / 2**level, H / 5, comm)


def lubricated_layer(W_first, E=10.0, E_c=100.0, model="finite", cavitation="penalty",
                     shear=True):
    """Body, Film and Problem for a first load W_first (N/mm) of the sweep."""
    law = "linear" if model == "linear" else "neo-hookean"
    mats = {tag: (law, dict(zip(("mu", "lmbda"), lame_parameters(Ei, 0.45))))
            for tag, Ei in ((LAYER, E), (COATING, E_c))}
    layer = Body(msh, facets, {"lubricated": LUBRICATED, "bottom": BOTTOM}, "plane_strain",
                 mats, cell_tags=cells, degree=degree, velocity=(U, 0.0), name="layer")
    layer.add_dirichlet("bottom", np.zeros(2))
    # scales of the rigid film at the first load: h_r = 2.45 μUR/W, ℓ = √(2Rh_r)
    h_r = rigid_clearance(W_first, mu, U, R)
    ell = math.sqrt(2 * R * h_r)
    film = Film(layer, "lubricated", rigid_cylinder(np.array([0.0, R]), R), Fluid(mu),
                scales=FilmScales(pressure=6 * mu * U * ell / h_r**2, film=h_r, speed=U),
                cavitation=JFO() if cavitation == "jfo"
                else Penalty(1e-6 * 12 * mu * ell**2 / h_r**3),
                model=model, shear=shear)
    if cavitation == "jfo":
        film.add_inlet(lambda X: np.isclose(X[0], -x_l))   # flooded inlet, natural outlet
    else:
        film.add_pressure_bc()                              # p = 0 at both ends of Γ_l
    film.counterpart.offset.value[1] = h_r                  # the cylinder at the rigid film
    film.jfo_initial_guess()
    return layer, film, Problem([layer, film], name=f"layer_{model}_{cavitation}")


def sweep(run, loads):
    """Film measures at each load: the cylinder position s found for W by a secant on 1/W."""
    layer, film, problem = run
    position = Continuation(problem, ConstantParameter(film.counterpart.offset, 1),
                            response=lambda: -1 / film.force()[1], rtol=1e-6)
    held = Hold(position, 0.0, transform=lambda W: 1 / W,
                slope=1 / rigid_clearance(1.0, mu, U, R))   # d(1/W)/ds, rigid film
    out = []
    for W in loads:
        held.march(W, predictor=False)      # the load march: a failed step is cut in half
        prof = comm.bcast(film.profile(), root=0)
        F = film.force()
        x = prof["y" if film.model == "finite" else "X"][:, 0]
        out.append({"W": -F[1], "h_min": prof["h"].min(), "p_max": prof["p"].max(),
                    "friction": abs(F[0] / F[1]), "x": x, "p": prof["p"], "h": prof["h"]})
    return out
# -

# ## Finite deformation against the geometrically linear model (Fig. 22)
#
# The sweep of Fig. 22 (to 1 N/mm) is ``tribofx run ehl-cylinder-layer --set
# compare=linear``; here W = 0.05, 0.2 (``--quick``) or 0.2, 0.4, 0.6 N/mm.

# +
loads = [0.05, 0.2] if args.quick else [0.2, 0.4, 0.6]
res = {model: sweep(lubricated_layer(loads[0], model=model), loads)
       for model in ("finite", "linear")}
d_h = [abs(f["h_min"] / lin["h_min"] - 1) for f, lin in zip(res["finite"], res["linear"])]
d_p = [abs(f["p_max"] / lin["p_max"] - 1) for f, lin in zip(res["finite"], res["linear"])]
if comm.rank == 0:
    print("relative difference finite/linear: h_min", [f"{d:.1e}" for d in d_h],
          "p_max", [f"{d:.1e}" for d in d_p])
    for k, W in enumerate(loads):
        f, lin = res["finite"][k], res["linear"][k]
        print(f"W = {W:.2f} N/mm: h_min {1e3 * f['h_min']:.3f} (linear {1e3 * lin['h_min']:.3f})"
              f" µm, p_max {f['p_max']:.4f} ({lin['p_max']:.4f}) MPa, friction "
              f"{f['friction']:.4f}")
# -

# ## Mass-conserving cavitation and the rigid-cylinder limit
#
# JFO at W = 0.1 N/mm: the discrete fluxes through the ends of Γ_l; and a stiff
# layer (E = E_c = 10⁴ MPa, no shear tractions needed: the film is that of a rigid
# cylinder) against the Swift–Stieber solution of the rigid cylinder–plane problem
# at the same minimum film (``tribofx.references.cylinder_references``).

# +
run = lubricated_layer(0.1, cavitation="jfo")
jfo = sweep(run, [0.1])[-1]
film = run[1]
q_in, q_out = film.consistent_fluxes()
prof = comm.bcast(film.profile(), root=0)
i = int(np.argmax(prof["p"]))
r = i + int(np.nonzero(prof["lam"][i:] > 1e-8)[0][0])      # first cavitated node
h_rupture = 0.5 * (prof["h"][r - 1] + prof["h"][r])
stiff = sweep(lubricated_layer(0.25, E=1e4, E_c=1e4, shear=False), [0.25])[-1]
ss = cylinder_references(R, stiff["h_min"], 0.5 * U, mu, -x_l, x_l)["swift_stieber"]
if comm.rank == 0:
    print(f"JFO: q_in = {q_in:.6g}, q_out = {q_out:.6g} mm²/s, U h_rupture/2 = "
          f"{0.5 * U * h_rupture:.6g}; stiff layer: p_max {stiff['p_max']:.5f} MPa "
          f"(Swift–Stieber {ss['p_max']:.5f}), W {stiff['W']:.5f} ({ss['load']:.5f}) N/mm")
if args.out:
    keys = ("W", "h_min", "p_max", "friction")
    write_summary(comm, f"{args.out}/summary.json", {
        "case": "demo_ehl_cylinder_layer", "flux_in": q_in, "flux_out": q_out,
        **{m: [{k: s[k] for k in keys} for s in out] for m, out in res.items()},
        **{m: {k: s[k] for k in keys} for m, s in (("jfo", jfo), ("stiff", stiff))}})
    if comm.rank == 0:
        plot_film_profiles(None, f"{args.out}/profiles.png", "coated layer", {
            m: {"label": m, "steps": s} for m, s in res.items()})
# -

# ## Checks
#
# * The two models differ by terms of higher order in the deformation (strain ∝ W):
#   the difference of p_max grows with the load, and both differences are below
#   1 % at the smallest load (strains ≈ 1e-3).  The h_min difference is printed,
#   not checked: it is not monotone (measured 0.30, 0.47, 0.30 % at 0.2, 0.4,
#   0.6 N/mm and 0.01 % at 1 N/mm, P2), nor is that of p_max beyond 0.8 N/mm
#   (1.2 % there, 0.9 % at 1 N/mm) — the full run stops at 0.6 N/mm.
# * JFO conserves mass: q_out = q_in to solver tolerance (1e-8 relative), and at
#   the rupture point (p = ∂p/∂x = 0) the flux is the Couette flux U h/2 — within
#   2 % (h interpolated over the rupture element, S tilted by ≈ 0.03 rad there).
# * Stiff layer: deflection ≈ 0.3 % of h, curvature of S O(2h/R) = 0.2 %, P1 pressure
#   with 0.04 mm (0.02 mm) elements over ℓ = √(2Rh) ≈ 0.43 mm ≈ 1 % (0.3 %) and
#   the penalty: 3 % (2 %) on p_max and the load.

# +
assert all(a < b for a, b in zip(d_p, d_p[1:])), d_p
assert d_h[0] < 1e-2 and d_p[0] < 1e-2
assert q_in > 0 and abs(q_out - q_in) <= 1e-8 * q_in
assert abs(q_in / (0.5 * U * h_rupture) - 1) < 2e-2
tol = 3e-2 if args.quick else 2e-2
assert abs(stiff["p_max"] / ss["p_max"] - 1) < tol and abs(stiff["W"] / ss["load"] - 1) < tol
if comm.rank == 0:
    print("demo_ehl_cylinder_layer: all checks passed")
# -
