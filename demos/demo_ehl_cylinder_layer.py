# # Soft-EHL: rigid cylinder sliding against a coated elastic layer
#
# This demo illustrates the fully coupled, finite-deformation soft-EHL problem
# of the chapter's §7 on the example of §8.2 (plane strain):
#
# * the solid: a neo-Hookean layer (H = 5 mm, E = 10 MPa, ν = 0.45) with a
#   stiffer coating (t_c = 0.1 mm, E_c = 100 MPa) bonded to a rigid substrate,
#   virtual work (62) with the nominal fluid traction on Γ_l;
# * the film: the steady Reynolds equation (49) on the lubrication surface
#   S = P(γ_l), the closest-point projection of the deformed layer surface onto
#   the rigid cylinder (R = 10 mm), pulled back to Γ_l:
#
#       h = (x − y)·ν,  A = F_y (I − N⊗N) + ν⊗N,  ds_S = |det A| dS,
#       grad_S p = A^{-T} Grad_Γ p,  v̄ = ½ (I − ν⊗ν) F V,
#
#   in the frame of the cylinder (the layer flows with v = F V, eq. 26,
#   μU = 1e-4 N/mm as in Fig. 22), penalty cavitation, SUPG;
# * the coupling (i)–(iii) of §7.3: h depends on u, the traction (46)
#   −p n − (μ/h) v_T − (h/2) grad_S p loads the layer, and S itself moves
#   with the deformation; one monolithic Newton method with the exact tangent
#   (UFL derivative of everything above, eq. 72);
# * load control: the vertical position of the cylinder is found by a secant
#   iteration for each load W, with load continuation and step cutting.
#
# The geometrically linear model (classical EHL: geometry and operators of the
# undeformed configuration, h linear in u) is run for comparison, as the dashed
# lines of the chapter's Fig. 22.  Units: mm, N, s, MPa.
#
# ## Changing a parameter
#
#     tribofx run ehl-cylinder-layer --set W=1 --set steps=10          # Fig. 22 sweep
#     tribofx run ehl-cylinder-layer --set model=linear --set shear=false
#     tribofx run ehl-cylinder-layer --set E_c=10 --set mesh=2         # no stiff coating
#     tribofx run ehl-cylinder-layer --set compare=linear              # both models, one plot
#     tribofx run ehl-cylinder-layer --set compare=alpha               # α = 0, 0.5, 1 (Fig. 23)
#
# Run this script as
#
#     python demos/demo_ehl_cylinder_layer.py --out results/ehl-cylinder-layer

import argparse
import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx / petsc4py)
from mpi4py import MPI

from tribofx.runner import run_case

parser = argparse.ArgumentParser(description="soft-EHL coated layer demo")
parser.add_argument("--out", default="results/ehl-cylinder-layer")
args = parser.parse_args()
rank0 = MPI.COMM_WORLD.rank == 0

# a short sweep W = 0.2, 0.4, 0.6 N/mm on a moderate mesh (P2 displacement);
# ``compare=linear`` runs it for the finite and the geometrically linear model in
# one run: results ``finite_*`` and ``linear_*``, both models on the same axes in
# ``profiles_finite_vs_linear.png`` (as the chapter's Fig. 22)
common = {"W": "0.6", "steps": "3", "mesh": "0", "degree": "2"}
s = run_case("ehl-cylinder-layer", dict(common, compare="linear"), f"{args.out}/finite-vs-linear",
             progress=False)
assert s["status"] == "ok", s["status"]
allres = {k: v["value"] for k, v in s["results"].items()}
res = {m: {k[len(m) + 1:]: x for k, x in allres.items() if k.startswith(m + "_")}
       for m in ("finite", "linear")}
if rank0:
    print(f"finite and linear: {s['wall_time_s']:.1f} s, {s['num_dofs']} unknowns, Newton "
          f"iterations per secant trial {s['variant_newton_iterations']}")
for model, r in res.items():
    if rank0:
        print(f"{model}:")
        for k, W in enumerate(r["steps_W"]):
            print(f"  W = {W:.3f} N/mm: h_min = {1e3 * r['steps_h_min'][k]:.2f} µm, "
                  f"h_central = {1e3 * r['steps_h_central'][k]:.2f} µm, "
                  f"p_max = {r['steps_p_max'][k]:.4f} MPa, "
                  f"friction = {r['steps_friction_coefficient'][k]:.4f}")

# ## Checks
#
# * the load is reached at every step (secant tolerance 1e-6);
# * the film gets thinner and the peak pressure higher with the load;
# * the friction coefficient (Couette drag / W) falls with the load (μU/h grows
#   more slowly than the load);
# * the finite and linear peak pressures differ more at higher load
#   (finite-deformation effects grow with the strain; at these loads and this
#   coarse mesh the differences stay below 1 %, and the h_min difference is not
#   monotone, so it is printed, not checked).
fin, lin = res["finite"], res["linear"]
for r in (fin, lin):
    assert all(abs(W / (0.2 * (k + 1)) - 1) < 1e-5 for k, W in enumerate(r["steps_W"]))
    assert all(a > b for a, b in zip(r["steps_h_min"], r["steps_h_min"][1:]))
    assert all(a < b for a, b in zip(r["steps_p_max"], r["steps_p_max"][1:]))
    assert all(a > b for a, b in zip(r["steps_friction_coefficient"],
                                     r["steps_friction_coefficient"][1:]))
diff_h = [abs(a / b - 1) for a, b in zip(fin["steps_h_min"], lin["steps_h_min"])]
diff_p = [abs(a / b - 1) for a, b in zip(fin["steps_p_max"], lin["steps_p_max"])]
assert all(a < b for a, b in zip(diff_p, diff_p[1:])), diff_p
if rank0:
    print("relative difference finite/linear per step: h_min",
          [f"{d:.2e}" for d in diff_h], "p_max", [f"{d:.2e}" for d in diff_p])

# ## Mass-conserving cavitation, lubrication surface S_α, continuation in speed
#
# * ``cavitation=jfo``: void fraction λ (P1 on Γ_l) and the weak form (57) on S
#   with nodal complementarity min(p/p_c, λ) = 0 (semismooth Newton); flooded
#   inlet, so the film ruptures as with the penalty (Swift–Stieber) model;
# * ``alpha``: the Reynolds equation on S_α = (1 − α) P(γ_l) + α γ_l (Fig. 23);
# * ``speeds``: continuation in U at the final load (μU from 0.1 to 1 N/m), with
#   step cutting, recording the friction coefficient against μU
#   (``friction_vs_speed.png``).
light = {"W": "0.2", "steps": "2", "mesh": "0", "degree": "1"}
runs = {"penalty": {}, "jfo": {"cavitation": "jfo"}, "alpha=1": {"alpha": "1"},
        "jfo+speeds": {"cavitation": "jfo", "speeds": "3000,10000"}}
out = {}
for name, extra in runs.items():
    s = run_case("ehl-cylinder-layer", dict(light, **extra),
                 f"{args.out}/{name.replace('=', '').replace('+', '-')}", progress=False)
    assert s["status"] == "ok", s["status"]
    out[name] = {k: v["value"] for k, v in s["results"].items()}
    if rank0:
        r = out[name]
        print(f"{name}: {s['wall_time_s']:.1f} s, h_min = {1e3 * r['h_min']:.3f} µm, "
              f"p_max = {r['p_max']:.5f} MPa, friction = {r['friction_coefficient']:.5f}")
sp = out["jfo+speeds"]
if rank0:
    for muU, f in zip(sp["speed_mu_U"], sp["speed_friction_coefficient"]):
        print(f"  μU = {1e3 * muU:.2f} N/m: friction coefficient {f:.4f}")
for key in ("p_max", "h_min"):
    assert abs(out["jfo"][key] / out["penalty"][key] - 1) < 5e-3, key
    assert abs(out["alpha=1"][key] / out["penalty"][key] - 1) < 5e-2, key
f = sp["speed_friction_coefficient"]
assert all(a < b for a, b in zip(f, f[1:])), f

# ## α-study (Fig. 23) in one run
#
# ``compare=alpha``: the same load sweep with the Reynolds equation on S_α for
# α = 0, 0.5, 1 (results ``alpha0_*``, ``alpha0.5_*``, ``alpha1_*``, plot
# ``profiles_alpha.png``).  Moving S from the cylinder (α = 0) to the layer
# surface (α = 1) changes the film and the pressure only slightly here (slopes of
# both surfaces are small in the contact); the changes are monotone in α.
s = run_case("ehl-cylinder-layer", dict(light, W="0.4", compare="alpha"), f"{args.out}/alpha",
             progress=False)
assert s["status"] == "ok", s["status"]
ra = {k: v["value"] for k, v in s["results"].items()}
names = ra["variants"]
hm = [ra[f"{n}_h_min"] for n in names]
pm = [ra[f"{n}_p_max"] for n in names]
if rank0:
    for n, h, p in zip(names, hm, pm):
        print(f"  {n}: h_min = {1e3 * h:.3f} µm, p_max = {p:.5f} MPa")
assert all(a < b for a, b in zip(hm, hm[1:])), hm
assert all(a > b for a, b in zip(pm, pm[1:])), pm
if rank0:
    print("demo_ehl_cylinder_layer: all checks passed")
