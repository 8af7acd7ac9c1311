"""The two bodies of ``stribeck``: a plane-strain cylinder or a quarter ball on a rough plane.

Each builder returns the run's pieces (a dict): ``body``, ``film``, ``speed``
(the plane's velocity, a Constant), ``ref`` (the Hertz contact at W), ``U_floor``
(the film's flux scale at creeping speeds), ``axis`` (the normal: y in 2D, z in
3D) and ``copies`` (the whole body's load over the model's: 1, or 2 for the
ball).  Both bodies are at rest; the plane slides at U under them (pure
sliding, entrainment U/2).

* ``cylinder``: radius R, plane strain, both sides of the contact modelled
  (film on ±4a), held at its flat face; the plane at Martin's rigid film of
  W/steps, the body unloaded (the load march starts from the rigid film).
* ``ball``: lower hemisphere, half y ≥ 0 (u_y = 0 on y = 0), the mid-plane held
  (the model of ``ehl-ball``); the film on the cap of radius R sin θ_l = 3a about
  the contact point (p = 0 on its rim, zero flux on y = 0); the load of the
  whole ball is twice the model's.  The start: the ball under the Hertz pressure
  of W/steps, the plane at the Hamrock–Dowson film h_r (at least σ); where the
  asperities' separation at the Hertz p₀ is the larger (creeping speeds) the
  ball starts undeformed, the plane at h_r, like the cylinder.
"""

import math

import numpy as np
from dolfinx import fem

from ..body import Body
from ..forms.hyperelastic import lame_parameters
from ..interfaces import Film
from ..meshes.ball import cap_height, quarter_ball
from ..meshes.roller import ROLLER_NAMES, roller
from ..obstacles import rigid_plane
from ..references import composite_modulus, hamrock_dowson, hertz, rigid_clearance
from ..references_mixed import flat_punch_separation
from .ehl_ball import NAMES as BALL_NAMES

__all__ = ["ball", "cylinder", "first_film", "hertz_contact"]

#: the ball's cap radius R sin θ_l in Hertz radii (inlet and outlet on the cap)
CAP_RADII = 3.0


def hertz_contact(v, W=None):
    """Hertz contact at W (default ``v["W"]``): line (N/mm) or point (N, whole ball)."""
    return hertz(v["W"] if W is None else W, v["R"], v["E"], v["nu"],
                 line=v["geometry"] == "cylinder")


def first_film(v, U, W=None):
    """Return the film (mm) at load W (default W/steps) and sliding speed U, before σ's floor.

    Cylinder: Martin's rigid film; ball: Hamrock–Dowson's central film at the
    entrainment speed U/2.
    """
    W = v["W"] / v["steps"] if W is None else W
    if v["geometry"] == "cylinder":
        return rigid_clearance(W, v["mu"], U, v["R"])
    return hamrock_dowson(W, v["mu"], U / 2, v["R"], composite_modulus(v["E"], v["nu"]))[0]


def _scales(v, U0):
    """Film scale h_r (≥ σ), flux floor U_floor = σ³p₀/(12μ a h_r), Hertz contact at W."""
    ref = hertz_contact(v)
    h_r = max(first_film(v, U0), v["sigma"])
    return h_r, v["sigma"] ** 3 * ref.p0 / (12 * v["mu"] * ref.a * h_r), ref


def cylinder(v, U0, roughness, comm, shape=False):
    """Build the plane-strain cylinder (``shape``: a shape field; its film face alone wears)."""
    R = v["R"]
    h_r, U_floor, ref = _scales(v, U0)
    x_l, h_fine = 4 * ref.a, ref.a / (8 * 2 ** v["mesh"])
    msh, ft = roller(R, x_l, h_fine, R / 4, x_l, comm)
    mu_s, lm = lame_parameters(v["E"], v["nu"])
    body = Body(msh, ft, ROLLER_NAMES, "plane_strain",
                ("neo-hookean", {"mu": mu_s, "lmbda": lm}), name="cylinder",
                shape=shape, aux=(v["E"], 0.3))
    body.add_dirichlet("loaded", np.zeros(2))
    for i in range(2 if shape else 0):   # only the film face wears: the rest keeps its shape
        body.add_shape_dirichlet("loaded", i)
        body.add_shape_dirichlet("free", i, except_on="lubricated")
    speed = fem.Constant(msh, np.array([U0, 0.0]))
    film = Film(body, "lubricated", rigid_plane([0, 0], [0, 1]), v["mu"], V_counter=speed,
                roughness=roughness, eps=1e-4 * 24 * v["mu"] * R / h_r**2, p_c=ref.p0,
                film_scale=h_r, speed_scale=max(U0, U_floor), rtol=1e-8)
    film.add_pressure_bc()
    film.counterpart.offset.value[1] = -h_r
    return {"body": body, "film": film, "speed": speed, "ref": ref, "U_floor": U_floor,
            "axis": 1, "copies": 1.0}


def ball(v, U0, roughness, comm):
    """Build the quarter ball, started under the Hertz pressure of W/steps."""
    R = v["R"]
    h_r, U_floor, ref = _scales(v, U0)
    a = ref.a
    theta = math.asin(CAP_RADII * a / R)
    h_fine = a / (8 * 2 ** v["mesh"])
    msh, _, ft = quarter_ball(R, theta, h_fine, max(R / 3, h_fine), 1.6 * a, comm)
    mu_s, lm = lame_parameters(v["E"], v["nu"])
    body = Body(msh, ft, BALL_NAMES, "3d", ("neo-hookean", {"mu": mu_s, "lmbda": lm}),
                name="ball")
    body.add_dirichlet("midplane", np.zeros(3))
    body.add_dirichlet("symmetry", 0.0, component=1)
    speed = fem.Constant(msh, np.array([U0, 0.0, 0.0]))
    film = Film(body, "lubricated", rigid_plane(np.zeros(3), np.eye(3)[2]), v["mu"],
                V_counter=speed, roughness=roughness,
                eps=1e-4 * 12 * v["mu"] * a**2 / h_r**3, p_c=ref.p0, film_scale=h_r,
                speed_scale=max(U0, U_floor), rtol=1e-8, quadrature_degree=2)
    z_cap = cap_height(R, theta)
    film.add_pressure_bc(lambda X: np.abs(X[2] - z_cap) < 1e-6 * R)
    # the start where the film is the thicker (h_r above the asperities' separation h_a
    # at the Hertz p₀ of W/steps: flat punch, F_{5/2} fit): the ball under the Hertz
    # pressure, the plane at h_r; else (creeping speeds) undeformed, the plane at h_r
    start = hertz_contact(v, v["W"] / v["steps"])
    h_a = -math.inf
    if roughness is not None and roughness.asperity is not None:
        h_a = flat_punch_separation(start.p0, v["sigma"], roughness.asperity.parameters["KE"])
    if h_r >= h_a:
        film.start_from_pressure(lambda x: start.pressure(np.hypot(x[0], x[1])), h_r,
                                 np.zeros(3))
    else:
        film.counterpart.offset.value[2] = -h_r
    return {"body": body, "film": film, "speed": speed, "ref": ref, "U_floor": U_floor,
            "axis": 2, "copies": 2.0}
