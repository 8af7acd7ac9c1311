# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # Finite wear of a hyperelastic pin: the implicit (monolithic ALE) scheme
#
# This demo illustrates how to:
#
# * give a hyperelastic **Body** a *shape field* w (``shape=True``): every unknown
#   lives on the initial, never-moved mesh, the worn configuration is X = X̂ + w
#   and the body's virtual work is written on it;
# * add a **Contact** interface (frictionless, augmented Lagrangian, nodal
#   multiplier λ_N on the contact facet submesh) and a **Wear** interface on top
#   of it (Archard's law and the discrete shape evolution law with its
#   multiplier ζ on the same submesh);
# * integrate the slow time with the **Stepper**: the implicit θ-scheme (θ = 1)
#   solves (u, λ_N, w, ζ) in one monolithic Newton problem with the exact UFL
#   tangent, cuts a failed step and writes a checkpoint every step;
# * load the pin by a **Continuation** of its load factor;
# * check the worn area against Archard's law integrated over time.
#
# ## Equations (chapter §3–§4)
#
# A neo-Hookean plane-strain pin (width W, height H, rounded tip of radius R)
# is pressed by a uniform traction q on its top face onto a rigid plane sliding
# at speed V (chapter §4.4, Figs. 2–4).  With G = I + Grad w the deformation
# relative to the worn body is F = (I + Grad u) G⁻¹ (eq. 19); volumes carry
# det G and areas Nanson's vector cof(G) N̂.  The residuals are
#
# $$
# \int_{\hat\Omega} P(F) : (\mathrm{Grad}\,\delta u\, G^{-1}) \det G \, d\hat V
# - \int_{\hat\Gamma_t} T^*\!\cdot\delta u\, j_w\, d\hat S + G_c(u, \lambda_N) = 0,
# $$
#
# the auxiliary elasticity of w with the reaction ∫ ζ δw·a(w) dŜ (along the worn
# boundary's Nanson vector at the step's end, so that the nodes' positions along
# the boundary depend on its shape alone), and the discrete
# shape evolution law (28) with the nominal Archard rate (14) in pressure form,
# Ẇ j_w = k V |λ_N|, imposed nodally on Γ̂_c:
#
# $$
# (w_{n+1} - w_n)\cdot a = -\Delta t\, k V |\lambda_{N,n+\theta}|, \qquad
# a = \int_0^1 \mathrm{cof}\,G(s)\,\hat N \, ds ,
# $$
#
# the step average of the Nanson vector, so that (w − w_n)·a dŜ is the exact
# area swept by a boundary facet.  Then the worn area ∫(1 − det G) dV̂ equals
# Σ Δt ∫ k V |λ_N| dS, and by vertical equilibrium ∫ |λ_N| dS = qW (the sides
# are held in x only, the top traction is dead): the worn area is k (qW) V t,
# whatever the pressure distribution.
#
# ## Changing it
#
# ``scheme=EXPLICIT`` (θ = 0) in ``Wear`` gives the explicit scheme (stable only for
# Δt < Δt_cr ∼ h/E, eq. 31); ``law="spatial"`` the spatial Archard law (16);
# ``k_grad`` a depth-graded coefficient; ``friction`` in ``Contact`` (with
# ``slip="eulerian"`` and a body velocity) the dissipation form (14).  The
# same configuration is the case ``wear-pin`` (``tribofx run wear-pin``), whose
# ``study=dt`` reproduces the error-versus-Δt study of Fig. 4.  Units: mm, N, s, MPa.

# +
import argparse
import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx / petsc4py)
import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI
from tribofx.forms.hyperelastic import lame_parameters
from tribofx.meshes.pin import NAMES, pin_body

from tribofx.body import Body
from tribofx.continuation import ConstantParameter, Continuation
from tribofx.interfaces import Contact, Wear
from tribofx.obstacles import rigid_plane
from tribofx.output import write_summary, write_vtx
from tribofx.plots import plot_wear_pin
from tribofx.references import hertz
from tribofx.scheme import IMPLICIT
from tribofx.stepper import Stepper

parser = argparse.ArgumentParser(description="pin-on-flat finite wear demo")
parser.add_argument("--quick", action="store_true", help="10 x 10 mesh (CI)")
parser.add_argument("--out", default=None, help="write summary.json, plots, VTX, checkpoint")
args, _ = parser.parse_known_args()
comm = MPI.COMM_WORLD
# -

# ## The configuration
#
# W = H = 2 mm, R = 4 mm (tip height 0.127 mm), q = 2 MPa, V = 10 mm/s,
# k = 5·10⁻⁶ mm³/(N·mm), E = 640 MPa (small-deformation regime), ν = 0.3:
# the nominal worn area k q W V T = 0.2 mm² per mm at T = 1000 s flattens the
# tip.  Five implicit steps of Δt = 200 s (the chapter's Fig. 3, right) on the
# 20 × 20 structured mesh (``--quick``: 10 × 10).

# +
W, H, R, q, V, k, E, nu = 2.0, 2.0, 4.0, 2.0, 10.0, 5e-6, 640.0, 0.3
T, dt = 1000.0, 200.0
n = 10 if args.quick else 20
msh, facet_tags = pin_body(W, H, R, n, comm)

# the body with its shape field w and the auxiliary elasticity of w (E_a = E)
mu, lmbda = lame_parameters(E, nu)
body = Body(msh, facet_tags, NAMES, "plane_strain", ("neo-hookean", {"mu": mu, "lmbda": lmbda}),
            shape=True, aux=(E, 0.3))
load = fem.Constant(msh, 0.0)  # load factor of the dead top traction (per worn area)
body.add_traction("top", load * ufl.as_vector([0.0, -q]))
body.add_dirichlet("sides", 0.0, component=0)  # laterally constrained, free vertically
body.add_shape_dirichlet("sides", 0)  # the worn shape keeps the sides ...
body.add_shape_dirichlet("top", 1)  # ... and the top face

# the interfaces: contact with the rigid plane y = 0, wear on that contact
contact = Contact(body, "contact", rigid_plane(np.zeros(2), np.array([0.0, 1.0])),
                  rho_n=E / (W / n))
wear = Wear(contact, k=k, speed=V, scheme=IMPLICIT)

# the slow time: θ = 1 -> one monolithic Problem in (u, λ_N, w, ζ)
checkpoint = f"{args.out}/checkpoint" if args.out else None
stepper = Stepper([body, contact, wear], wear, parameters=[load], checkpoint=checkpoint,
                  name="demo_pin")
# -

# ## Loading and wearing
#
# Newton starts from a rigid translation of the pin by the Hertz approach plus
# the compression of the shank, so that the tip nodes start in contact; the
# Continuation drives the load factor from 0 to 1 (halving on failure).  Then
# the stepper advances the slow time, logging the worn area, the maximum wear
# depth and the contact half-width after every step.

# +
a = hertz(q * W, R, E, nu, line=True).a
body.u.x.array.reshape(-1, 2)[:, 1] = -(a * a / (2 * R) + q * H / E)
Continuation(stepper.problem, ConstantParameter(load)).march(1.0, steps=1, predictor=False)

history = []


def log(st, report):
    area, _ = contact.measures()
    history.append({"t": st.t, "worn_area": wear.worn_volume(), "depth": wear.max_depth() + 0.0,
                    "half_width": area / 2, "rate": wear.wear_rate_integral(),
                    "newton": report.iterations if report else 0})


log(stepper, None)
stepper.run(T, dt, on_step=log)
if comm.rank == 0:
    share = 100 * stepper.shape_unknown_fraction()
    print(f"{stepper.problem.num_dofs} unknowns, {share:.0f} % of them in Ψ (w and ζ)")
    print(" t (s)   worn area (mm²/mm)  max depth (mm)  half-width (mm)  Newton")
    for h in history:
        print(f"{h['t']:6.0f}   {h['worn_area']:18.8f}  {h['depth']:14.5f}  "
              f"{h['half_width']:15.4f}  {h['newton']:6d}")
shape = wear.gather_shape()
if args.out:
    write_vtx(comm, f"{args.out}/displacement.bp", [body.u, body.w])
    write_summary(comm, f"{args.out}/summary.json", {"case": "demo_wear_pin", "n": n,
                                                     "history": history})
    if comm.rank == 0:
        plot_wear_pin({"time": [h["t"] for h in history], "times": [h["t"] for h in history],
                       "wear_volume": [h["worn_area"] for h in history],
                       "max_wear_depth": [h["depth"] for h in history],
                       "profiles": [shape["X_worn"].tolist()], "scheme": "implicit", "dt": dt},
                      args.out)
# -

# ## Checks
#
# * Worn area = k (qW) V t at every step.  The Newton residuals are at their
#   stopping tolerances (momentum 1e-10 G L, gap 1e-10 L, shape rows 1e-12 L):
#   summed over the ~n contact nodes, the balance holds to ~1e-9 relative.
# * The implicit rate is that of t_{n+1}: worn area = Σ Δt ∫ Ẇ dS (the discrete
#   geometric conservation law of the swept Nanson vector), to the same tolerance.
# * The tip is worn flat: the contact covers the pin width to within one element
#   (half-width > W/2 − h), and the maximum depth exceeds the tip height 0.127 mm.

# +
t = np.array([h["t"] for h in history])
area = np.array([h["worn_area"] for h in history])
archard = k * q * W * V * t
assert np.allclose(area, archard, rtol=1e-9, atol=1e-12), (area, archard)
integral = np.concatenate([[0.0], np.cumsum(np.diff(t) * [h["rate"] for h in history[1:]])])
assert np.allclose(area, integral, rtol=1e-9, atol=1e-12), (area, integral)
assert history[-1]["half_width"] > W / 2 - W / n, history[-1]
assert history[-1]["depth"] > 0.127, history[-1]
if comm.rank == 0:
    print(f"worn area {area[-1]:.9f} = k q W V T = {archard[-1]:.9f} mm²/mm")
    print("demo_wear_pin: all checks passed")
# -
