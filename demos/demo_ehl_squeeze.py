# ---
# jupytext:
#   text_representation:
#     extension: .py
#     format_name: light
# ---

# # A soft cylinder squeezes a film: transient soft-EHL
#
# This demo illustrates how to:
#
# * make the chapter's steady film transient, ``Film.transient("bdf2")``: the
#   Reynolds rows gain the rate of the fluid content c = ρθhJ_S at fixed reference
#   point and the mean velocity relative to the moving lubrication surface,
#
# $$ \int_{\Gamma_l} \frac{d}{dt}\big(\rho\theta h J_S\big)\,\delta p\, dS
#    - \int_S \big(q - \rho\theta h\,\dot y_t\big)\cdot\nabla_S\delta p\, ds = 0, $$
#
#   (``forms/squeeze.py``; the derivation is in ``docs/films.md``);
# * integrate it in time with the core's ``Stepper`` (the film is its evolving
#   interface: BDF2, started by one backward-Euler step);
# * hold a body by the film alone: the cylinder's top carries a dead load and
#   nothing else holds it, the squeeze term fixes its rigid motion (one
#   monolithic Newton iteration per step, no outer load iteration).
#
# Two runs of the ``ehl-squeeze`` configuration (a half cylinder, plane strain,
# R = 10 mm, above a rigid plane, film h_start = 10 µm, μ = 0.1 Pa·s):
#
# 1. a stiff cylinder (E = 10⁷ MPa) under 0.05 N/mm: the film thins as on a rigid
#    cylinder, dh/dt = −W/K(h) with Reynolds' squeeze resistance K of the exact
#    gap (``tribofx.references.squeeze_film_under_load``, RK4, independent of the
#    FE code);
# 2. a soft cylinder (E = 10 MPa, ν = 0.45) under 0.5 N/mm: the film pressure
#    flattens it before the fluid drains, and fluid stays trapped at the centre —
#    the elastohydrodynamic dimple, h_center > h_min.
#
# ## Changing it
#
#     tribofx run ehl-squeeze --set dim=3 --set control=load --set F=0.02
#     tribofx run ehl-squeeze --set control=speed --set V=2 --set scheme=euler

# +
import argparse
import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx / petsc4py)
from mpi4py import MPI

from tribofx.cases import ehl_squeeze
from tribofx.output import write_summary
from tribofx.params import resolve
from tribofx.references import squeeze_film_under_load

parser = argparse.ArgumentParser(description="transient squeeze film demo")
parser.add_argument("--quick", action="store_true", help="fewer, longer steps (CI)")
parser.add_argument("--out", default=None, help="write summary.json here")
args, _ = parser.parse_known_args()
comm = MPI.COMM_WORLD
steps = 8 if args.quick else 32


def squeeze(**over):
    """Build the cylinder, its transient film and the Stepper; step to T; per-step measures."""
    v = resolve(ehl_squeeze.Params,
                {k: str(x) for k, x in dict(control="load", dt=over["T"] / steps,
                                            **over).items()})
    model = ehl_squeeze.build(v)    # Body + Film(...).transient("bdf2") + Stepper, the plane
    stepper = model.stepper
    y0 = float(model.plane.value[1])
    out = []
    stepper.run(v.T, v.dt, on_step=lambda st, rep: out.append(
        (st.t, ehl_squeeze.measures(model, v, y0))))
    return v, out
# -

# ## 1. The stiff cylinder thins as Reynolds' rigid one

# +
v1, out = squeeze(F=0.05, E1=1e7, T=2e-3)
t = [s for s, _ in out]
h_ref = squeeze_film_under_load(2, v1.R, v1.mu, v1.F, v1.h_start, t,
                                ehl_squeeze.extent(v1))
stiff = [(s, m["h_center"], float(r)) for (s, m), r in zip(out, h_ref)]
if comm.rank == 0:
    for s, h, r in stiff:
        print(f"t = {1e3 * s:.2f} ms: h_center {1e3 * h:.4f} µm, rigid {1e3 * r:.4f} µm")
# -

# ## 2. The soft cylinder traps a dimple

# +
v2, out = squeeze(F=0.5, E1=10, nu1=0.45, T=5e-3)
soft = [(s, m["h_center"], m["h_min"], m["p_center"]) for s, m in out]
if comm.rank == 0:
    for s, hc, hm, pc in soft:
        print(f"t = {1e3 * s:.2f} ms: h_center {1e3 * hc:.3f} µm, h_min {1e3 * hm:.3f} µm, "
              f"p_center {pc:.3f} MPa")
if args.out:
    write_summary(comm, f"{args.out}/summary.json", {"stiff": stiff, "soft": soft})
# -

# ## Checks
#
# * Stiff: h_center follows the rigid thinning to 1.5 % of the thinning h₀ − h
#   (the mesh error of the squeeze resistance at the default mesh is 1.2 %,
#   ``tests/test_squeeze.py``; BDF2's time error with T/8 steps is 0.15 %).
# * Soft: fluid trapped at the centre, h_center > 1.1 h_min at 5 ms, and the film
#   is far thicker than the rigid cylinder's under the same load.

# +
for s, h, r in stiff:
    assert abs(h - r) <= 0.015 * (v1.h_start - r) + 1e-12, (s, h, r)
s, hc, hm, _ = soft[-1]
assert hc > 1.1 * hm
rigid = squeeze_film_under_load(2, v2.R, v2.mu, v2.F, v2.h_start, [s],
                                ehl_squeeze.extent(v2))[0]
assert hm > 5 * rigid
if comm.rank == 0:
    print("demo_ehl_squeeze: all checks passed")
# -
