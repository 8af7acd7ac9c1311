"""Mixed lubrication: the average-flow Reynolds equation and the asperity contact (UFL).

Rough surfaces separated by a film of nominal thickness h share the load
between the fluid and the asperities.  With σ the combined RMS roughness and
the film parameter H = h/σ:

* Average flow (Patir & Cheng 1978, *J. Lubr. Technol.* 100:12–17; 1979,
  101:220–229), flux per unit width

      q = −φ_x h³/(12μ) grad p + h_T v̄ + (σ/2) s φ_s (v_layer − v_counter),

  φ_x(H) the pressure flow factor, φ_s(H) the shear flow factor, s the share of
  the roughness (V_r,layer² − V_r,counter²: +1 rough layer, −1 rough
  counterface, 0 equal roughness), h_T the expected local gap.  It is the
  smooth flux of :mod:`forms.reynolds` with the effective viscosity μ/φ_x and
  the effective mean velocity v̄_eff = v̄ + (σ/2) s φ_s Δv/h_T
  (:func:`average_flow`), so the chapter's forms (49)/(57), SUPG included, carry
  it unchanged (written on h_T, see :func:`average_flow`).  Isotropic roughness
  (γ = 1, Patir & Cheng 1978 Table 1, 1979 Table 1): φ_x = 1 − 0.90 e^{−0.56H}
  (H > 0.5); φ_s = 1.899 H^0.98 e^{−0.92H + 0.05H²} (H ≤ 5), 1.126 e^{−0.25H}
  (H > 5).
* Expected gap of a Gaussian surface (Wu & Zheng 1989, *J. Tribol.* 111:30),
  h_T = (h/2)(1 + erf(H/√2)) + (σ/√(2π)) e^{−H²/2} (→ h for H ≳ 3).
* Asperity pressure (Greenwood & Williamson 1966; Greenwood & Tripp 1970,
  *Proc. IMechE* 185:625), p_a = K E* F_{5/2}(H),
  K = (16√2/15) π (ηβσ)² √(σ/β) (η asperity density, β asperity radius), E* the
  pair's plane-strain modulus, 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂;
  F_{5/2}(H) = (2π)^{−½} ∫_H^∞ (s − H)^{5/2} e^{−s²/2} ds, here by the smooth fit
  F_{5/2} ≈ 4.4086e-5 (4 − H)^6.804 for H < 4, 0 above (Arcoumanis et al. 1997,
  *Proc. IMechE J* 211:199), C⁶ at H = 4 so that Newton's tangent stays exact.
  Against the integral (:func:`tribofx.references.greenwood_tripp_f52`): −11 %
  at H = 0, −3.5 % at 1, −9 % at 2, −35 % at 2.5 (where p_a is 1/600 of its
  H = 0 value) — the fit the mixed-EHL literature uses; pass another law for
  more (``Roughness(asperity=...)``).

The asperities' traction on the layer is the normal pressure p_a on the
current surface and a boundary friction μ_b p_a against the relative slip
(:func:`asperity_traction`, regularised by a slip speed ε_v relative to the
surfaces' speeds).  The asperities, not the film, wear the surface: Archard's law driven by p_a
(:func:`asperity_wear_load`).  Units: mm, N, s, MPa.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import ufl

from .ehl import LubricationKinematics
from .wear import WearLoad

if TYPE_CHECKING:
    from ufl.core.expr import Expr

__all__ = [
    "GT_FIT",
    "asperity_constant",
    "asperity_traction",
    "asperity_wear_load",
    "average_flow",
    "expected_gap",
    "greenwood_tripp_pressure",
    "patir_cheng_couette_factor",
    "patir_cheng_poiseuille_factor",
    "patir_cheng_pressure_factor",
    "patir_cheng_roughness_shear_factor",
    "patir_cheng_shear_factor",
    "rough_shear_factors",
]

#: the fit F_{5/2}(H) ≈ A (H_c − H)^n of Arcoumanis et al. (1997)
GT_FIT = (4.4086e-5, 4.0, 6.804)


def patir_cheng_pressure_factor(H: Expr, C: Expr | float = 0.90, r: Expr | float = 0.56) -> Expr:
    """Pressure flow factor φ_x = 1 − C e^{−rH} (isotropic: C = 0.90, r = 0.56; H > 0.5)."""
    return 1 - C * ufl.exp(-r * H)


def patir_cheng_shear_factor(
    H: Expr, A1: Expr | float = 1.899, a1: Expr | float = 0.98, a2: Expr | float = 0.92,
    a3: Expr | float = 0.05, A2: Expr | float = 1.126, a4: Expr | float = 0.25,
) -> Expr:
    """Shear flow factor Φ_s(H) of one rough surface (isotropic coefficients, H ≤ 5 / > 5)."""
    Hs = ufl.max_value(H, 1e-12)
    Hl = ufl.min_value(Hs, 5.0)      # both branches are evaluated: no overflow of e^{a3 H²}
    low = A1 * Hl**a1 * ufl.exp(-a2 * Hl + a3 * Hl**2)
    return ufl.conditional(ufl.le(H, 5.0), low, A2 * ufl.exp(-a4 * Hs))


def patir_cheng_couette_factor(H: Expr, eps: Expr | float = 1.0 / 300) -> Expr:
    """Couette shear factor over H, φ_f(H)/H, of Gaussian roughness (Patir & Cheng 1979).

    The mean wall shear of sliding is (μ Δv/h) φ_f = (μ Δv/σ) φ_f/H, with
    φ_f = (35/32) z ∫ (1 − x²)³/(z + x) dx over the fluid part of Patir and
    Cheng's polynomial height density (z = H/3, local gaps below ε* 3σ = σ/100
    count as contact):

        H ≤ 3:  φ_f = (35/32) z {(1 − z²)³ ln((z + 1)/ε*) + [−55 + z(132 + z(345
                + z(−160 + z(−405 + z(60 + 147z)))))]/60},
        H > 3:  φ_f = (35/32) z {(1 − z²)³ ln((z + 1)/(z − 1)) + (z/15)[66 + z²(30z² − 80)]},

    ε* = 1/300.  Written as φ_f/H it is finite through H = 0 (1.745) and falls to 0
    at H = −3(1 − ε*) (all of the gap in contact: no fluid shears), where it is
    held at 0.  Above H = 15 the series φ_f = 1 + Σ_k c_k z^{−2k} of the same integral
    (c = 1/9, 1/33, …, to 1e-13) replaces the closed form, whose terms cancel.
    """
    z = H / 3
    zl = ufl.min_value(ufl.max_value(z, eps - 1), 1.0)
    poly = -55 + zl * (132 + zl * (345 + zl * (-160 + zl * (-405 + zl * (60 + 147 * zl)))))
    low = ufl.max_value((1 - zl**2) ** 3 * ufl.ln((zl + 1) / eps) + poly / 60, 0.0)
    zm = ufl.min_value(ufl.max_value(z, 1 + 1e-9), 5.0)
    mid = (1 - zm**2) ** 3 * ufl.ln((zm + 1) / (zm - 1)) \
        + zm / 15 * (66 + zm**2 * (30 * zm**2 - 80))
    zh = ufl.max_value(z, 5.0)
    series = sum(c / zh ** (2 * k + 1) for k, c in enumerate(_PHI_F_SERIES))
    inner = ufl.conditional(ufl.le(z, 1.0), low, ufl.conditional(ufl.le(z, 5.0), mid,
                                                                  series * 32 / 35))
    return 35 / 96 * inner


#: φ_f = Σ_k c_k z^{−2k} for large z: c_k = (35/32) ∫ x^{2k} (1 − x²)³ dx over (−1, 1)
_PHI_F_SERIES = (1.0, 1 / 9, 1 / 33, 0.011655011655011656, 0.005439005439005439,
                 0.0028794734677087615, 0.0016670635865682307)


def patir_cheng_poiseuille_factor(
    H: Expr, D: Expr | float = 1.40, s: Expr | float = 0.66
) -> Expr:
    """Poiseuille shear factor φ_fp = 1 − D e^{−sH} (Patir & Cheng 1979, isotropic).

    Fitted for H > 0.5; H is held at 0.5 below (φ_fp = −0.006 there, ≈ 0).
    """
    return 1 - D * ufl.exp(-s * ufl.max_value(H, 0.5))


def patir_cheng_roughness_shear_factor(
    H: Expr, A3: Expr | float = 11.1, a4: Expr | float = 2.31, a5: Expr | float = 2.38,
    a6: Expr | float = 0.11, H_max: Expr | float = 7.0,
) -> Expr:
    """Roughness shear factor over H, Φ_fs(H)/H (Patir & Cheng 1979, isotropic).

    Φ_fs = A3 H^a4 e^{−a5 H + a6 H²} for 0.5 ≤ H ≤ 7, 0 above (the fit is 0.013
    at 7), H held at 0.5 below; the traction on either wall gains
    (μ Δv/σ) |s| Φ_fs/H with the share s of the roughness
    (:func:`rough_shear_factors`).
    """
    Hc = ufl.min_value(ufl.max_value(H, 0.5), H_max)
    return ufl.conditional(ufl.le(H, H_max),
                           A3 * Hc ** (a4 - 1) * ufl.exp(-a5 * Hc + a6 * Hc**2), 0.0)


def rough_shear_factors(
    h: Expr, mu: Expr | float, sigma: Expr | float, couette: Callable[[Expr], Expr],
    poiseuille: Callable[[Expr], Expr], roughness_shear: Callable[[Expr], Expr] | None,
    share: float,
) -> tuple[Expr, Expr]:
    """Return the factors of the wall traction of a rough film (Patir & Cheng 1979).

    The tangential traction on either wall is (μ Δv/σ)(φ_f/H + |s| Φ_fs/H) +
    φ_fp (h_T/2) grad p (H = h/σ, nominal; s the share of the roughness).  Patir
    and Cheng's mean *viscous* shear is φ_f ∓ s Φ_fs on the two walls: with no
    mean pressure gradient the roughness's local wedges (pressure high on the
    flanks where the gap closes along the sliding) add the mean Poiseuille shear
    −½⟨p ∂h/∂x⟩ on the smooth wall and take it off the rough wall's viscous shear,
    whose asperity flanks carry it back as form drag.  A body feels the total
    (viscous shear and form drag), and the two walls' totals balance: φ_f + |s| Φ_fs
    on both.  Returns (c, d) that replace μ/h and h/2 of the smooth traction
    (:func:`forms.film_traction.fluid_traction`, ``factors=``); ``couette``,
    ``poiseuille``, ``roughness_shear`` the factor laws of H (None: 0 for Φ_fs);
    the Poiseuille part on the expected gap h_T.
    """
    H = h / sigma
    c = couette(H)
    if roughness_shear is not None and share:
        c = c + abs(share) * roughness_shear(H)
    return (mu / sigma) * c, 0.5 * expected_gap(h, sigma) * poiseuille(H)


def expected_gap(h: Expr, sigma: Expr | float) -> Expr:
    """Return the expected local gap h_T of a Gaussian roughness σ about the gap h (mm).

    Bounded below by 1e-9 σ: in floating point the two terms cancel to 0 (or
    below) far inside the asperity contact (H ≲ −8), where a Newton trial may
    pass; the bound acts below H ≈ −5.6 only, where p_a exceeds 90 K E* (no
    converged state of a mixed film lies there).
    """
    H = h / sigma
    h_T = 0.5 * h * (1 + ufl.erf(H / math.sqrt(2))) \
        + sigma / math.sqrt(2 * math.pi) * ufl.exp(-0.5 * H**2)
    return ufl.max_value(h_T, 1e-9 * sigma)


def asperity_constant(eta: float, beta: float, sigma: float) -> float:
    """K = (16√2/15) π (ηβσ)² √(σ/β) (dimensionless; η in 1/mm², β and σ in mm)."""
    return 16 * math.sqrt(2) / 15 * math.pi * (eta * beta * sigma) ** 2 * math.sqrt(sigma / beta)


def greenwood_tripp_pressure(h: Expr, sigma: Expr | float, KE: Expr | float) -> Expr:
    """Asperity pressure p_a = K E* F_{5/2}(h/σ) (MPa) with the fit :data:`GT_FIT`.

    ``KE``: the product K E* (MPa).
    """
    A, Hc, n = GT_FIT
    s = ufl.max_value(Hc - h / sigma, 0.0)
    return KE * A * s**n


def average_flow(
    kin: LubricationKinematics, mu: Expr | float, sigma: Expr | float,
    phi_x: Callable[[Expr], Expr], phi_s: Callable[[Expr], Expr], share: float,
) -> tuple[LubricationKinematics, Expr]:
    """Kinematics and viscosity that make the smooth Reynolds forms the average-flow ones.

    The flux is written on the expected gap h_T (> 0 for every nominal h, also
    where the nominal surfaces overlap in asperity contact, h < 0):

        q = −φ_x h_T³/(12μ) grad p + h_T v̄ + (σ/2) s φ_s Δv,   φ = φ(H_T), H_T = h_T/σ,

    which is Patir and Cheng's flux wherever their fits hold (H ≳ 3: h_T = h to
    1e-3) and keeps a positive conductance through contact.  ``phi_x``, ``phi_s``:
    the flow factors as UFL of the film parameter; ``share`` s of the shear flow
    (see the module docstring).  Returns (kin with h_T and v̄_eff, μ/φ_x).
    """
    h_T = expected_gap(kin.h, sigma)
    H = h_T / sigma
    v_c = kin.v_counter if kin.v_counter is not None else ufl.zero(len(kin.vbar))
    vbar = kin.vbar + 0.5 * sigma * share * phi_s(H) * (kin.v_layer - v_c) / h_T
    return LubricationKinematics(h=h_T, nu=kin.nu, y=kin.y, A=kin.A, stretch=kin.stretch,
                                 vbar=vbar, v_layer=kin.v_layer, v_counter=kin.v_counter), \
        mu / phi_x(H)


def asperity_traction(
    p_a: Expr, kin: LubricationKinematics, F: Expr, N: Expr, mu_b: float = 0.0,
    delta_v: float = 1e-3, floor_v: float = 1e-12,
) -> Expr:
    """Nominal traction of the asperities on the layer (MPa per reference area).

    −p_a J F⁻ᵀN (the normal pressure on the current surface, Nanson) and the
    boundary friction against the slip v_rel = v_layer − v_counter,

        −μ_b p_a j v_rel/√(|v_rel|² + ε_v²),   ε_v² = δ_v² (|v_layer|² + |v_counter|²) + ε_0²,

    regularised at rest over a slip speed ε_v that follows the speeds of the two
    surfaces (δ_v = ``delta_v``, relative), not a constant in mm/s: in sliding at
    any speed U the friction is μ_b p_a (1 − δ_v²/2 + …), so a Stribeck curve
    levels at μ_b in the boundary regime however slow the rig; in pure rolling
    (v_rel = 0) it vanishes.  ε_0 = ``floor_v`` (mm/s) keeps the tangent finite
    when both surfaces are at rest.
    """
    nJ = ufl.det(F) * ufl.inv(F).T * N
    T = -p_a * nJ
    if mu_b:
        v_l = kin.v_layer
        v_c = ufl.zero(len(v_l)) if kin.v_counter is None else kin.v_counter
        v_rel = v_l - v_c
        eps2 = delta_v**2 * (ufl.dot(v_l, v_l) + ufl.dot(v_c, v_c)) + floor_v**2
        j = ufl.sqrt(ufl.dot(nJ, nJ))
        T = T - mu_b * p_a * j * v_rel / ufl.sqrt(ufl.dot(v_rel, v_rel) + eps2)
    return T


def asperity_wear_load(p_a: Expr, kin: LubricationKinematics, F: Expr, N: Expr) -> WearLoad:
    """Return the asperity contact as the load of Archard wear (:class:`forms.wear.WearLoad`).

    Mixed lubrication wears the surface where the asperities touch: the normal
    traction T_N = −p_a j per unit reference area (j = J|F⁻ᵀN| = ds/dS, Nanson)
    and the sliding speed ‖v_layer − v_counter‖, so Ẇ j_w = k p_a j ‖v_s‖; the
    film pressure p does not wear.
    """
    v_rel = kin.v_layer if kin.v_counter is None else kin.v_layer - kin.v_counter
    nJ = ufl.det(F) * ufl.inv(F).T * N
    return WearLoad(normal=-p_a * ufl.sqrt(ufl.dot(nJ, nJ)),
                    slip_speed=ufl.sqrt(ufl.dot(v_rel, v_rel)))
