"""Mesh of the soft-EHL ball chosen from the load and the speed (chapter §8.3).

The film of a soft ball is Hertzian: flat (h ≈ h_c) over the contact disc of
radius a and closed by a constriction at the outlet edge, outside which the
Hertz gap opens like (a²/R)(s/a)^{3/2} at a distance s from the edge (up to a
constant of order one: 4√2/(3π) ≈ 0.60 for the sphere).  The width over which
it reaches the film thickness sets the scale of the constriction,

    ℓ = a (h_c R / a²)^{2/3},

with h_c the Hamrock–Dowson central film and a the Hertz radius.  A film whose
constriction is not resolved by the elements along the contact edge (size
h_edge) converges to a spurious branch that dips far below the Hamrock–Dowson
film on the symmetry line, or its load continuation fails.  Measured (module
docstring of :mod:`tribofx.cases.ehl_ball`): at 40 N, μU = 0.078 N/m (ℓ = 0.19
mm) a/8 (h_edge/ℓ = 4.1) dips (h_central 2.3 µm against 16.8) and a/32 along the
edge (h_edge/ℓ = 1.03) resolves the film (64k unknowns); the default 10 N at
0.1 N/m on a/8 (h_edge/ℓ = 1.6) runs with a zig-zag ≤ 5 %.  The rule asks
h_edge ≤ ``MAX_EDGE_RATIO`` ℓ = 2ℓ, between the measured good (1.6) and bad
(4.1) points — a rule calibrated on two points, not a convergence estimate —
with the contact width resolved by a/8 (``mesh`` ≥ 1).
"""

import math

from ..params import InputError
from ..references import composite_modulus, hamrock_dowson, hertz

__all__ = ["MAX_EDGE_RATIO", "LEVELS", "checked_outlet_width", "edge_size", "mesh_levels",
           "outlet_width"]

#: largest element size along the contact edge, in units of the outlet width ℓ
MAX_EDGE_RATIO = 2.0
#: (mesh, edge_refine) in the order of their cost (unknowns: 12k, 64k, 120k, 230k)
LEVELS = ((1, 0), (2, 1), (2, 2), (3, 2))


def outlet_width(v):
    """Width ℓ = a (h_c R / a²)^{2/3} (mm) of the outlet constriction at ``v``'s W and U."""
    a = hertz(v["W"], v["R"], v["E"], v["nu"]).a
    h_c = hamrock_dowson(v["W"], v["mu"], v["U"], v["R"], composite_modulus(v["E"], v["nu"]))[0]
    return a * (h_c * v["R"] / a**2) ** (2 / 3)


def checked_outlet_width(v):
    """Return :func:`outlet_width`, or raise InputError (one line) if it is not finite."""
    try:
        ell = outlet_width(v)
    except (ArithmeticError, ValueError):
        ell = math.nan
    if not 0 < ell < math.inf:
        raise InputError(f"W = {v['W']:g} N, U = {v['U']:g} mm/s, R = {v['R']:g} mm, "
                         f"E = {v['E']:g} MPa give no finite film scale (Hamrock–Dowson)")
    return ell


def edge_size(v, mesh, edge_refine):
    """Element size (mm) along the contact edge: a/(4·2^mesh)/2^edge_refine."""
    return hertz(v["W"], v["R"], v["E"], v["nu"]).a / (4 * 2**mesh) / 2**edge_refine


def mesh_levels(v):
    """``(mesh, edge_refine, resolved)`` of the run.

    Both set by the user: those (``resolved`` says whether they meet the rule).
    One set: the cheapest value of the other that resolves the outlet (h_edge ≤
    2ℓ); none: the cheapest entry of :data:`LEVELS` that does.  If none does,
    the finest candidate with ``resolved`` False.
    """
    mesh, refine = v["mesh"], v["edge_refine"]
    if mesh is not None and refine is not None:
        candidates = [(mesh, refine)]
    elif mesh is not None:
        candidates = [(mesh, e) for e in range(4)]
    elif refine is not None:
        candidates = [(m, refine) for m in (1, 2, 3)]
    else:
        candidates = list(LEVELS)
    ell = outlet_width(v)
    for m, e in candidates:
        if edge_size(v, m, e) <= MAX_EDGE_RATIO * ell * (1 + 1e-12):
            return m, e, True
    return (*candidates[-1], False)
