"""Rough surfaces for mixed lubrication: flow factors, asperity pressure, boundary friction.

A :class:`Roughness` bundles the laws of :mod:`tribofx.forms.mixed` (each a
:class:`tribofx.laws.Law`, so a researcher passes another in one place) and
the roughness data.  A :class:`tribofx.interfaces.Film` given ``roughness=``
binds it to its meshes and uses the one law wherever it enters:

* the Reynolds rows become the average-flow ones (φ_x, φ_s, h_T:
  :func:`tribofx.forms.mixed.average_flow`);
* the traction on the layer gains the asperity pressure p_a(h) and the boundary
  friction μ_b p_a (:func:`tribofx.forms.mixed.asperity_traction`), and its
  fluid shear takes the shear-stress factors (φ_f, φ_fp, Φ_fs:
  :func:`tribofx.forms.mixed.rough_shear_factors`);
* the outputs report the asperity load beside the film's.

Defaults: isotropic Patir–Cheng flow factors, Greenwood–Tripp asperities.
Units: mm, N, s, MPa.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Literal

from .forms import mixed
from .laws import Law

if TYPE_CHECKING:
    from dolfinx import mesh as dmesh

    from .laws import BoundLaw

__all__ = ["Roughness", "greenwood_tripp", "patir_cheng_pressure", "patir_cheng_shear",
           "patir_cheng_shear_stress", "rough_pair"]


def patir_cheng_pressure() -> Law:
    """φ_x(H), isotropic (Patir & Cheng 1978): 1 − 0.90 e^{−0.56H}."""
    return Law(mixed.patir_cheng_pressure_factor, C=0.90, r=0.56)


def patir_cheng_shear() -> Law:
    """Φ_s(H) of one rough surface, isotropic (Patir & Cheng 1979)."""
    return Law(mixed.patir_cheng_shear_factor, A1=1.899, a1=0.98, a2=0.92, a3=0.05,
               A2=1.126, a4=0.25)


def patir_cheng_shear_stress() -> tuple[Law, Law, Law]:
    """(φ_f/H, φ_fp, Φ_fs/H) of the wall shear, isotropic (Patir & Cheng 1979)."""
    return (Law(mixed.patir_cheng_couette_factor, eps=1.0 / 300),
            Law(mixed.patir_cheng_poiseuille_factor, D=1.40, s=0.66),
            Law(mixed.patir_cheng_roughness_shear_factor, A3=11.1, a4=2.31, a5=2.38,
                a6=0.11, H_max=7.0))


def greenwood_tripp(KE: float, sigma: float) -> Law:
    """p_a(h) = K E* F_{5/2}(h/σ) (MPa) with K E* (MPa) and σ (mm); reference value K E*."""
    return Law(lambda h, KE, sigma: mixed.greenwood_tripp_pressure(h, sigma, KE),
               KE=KE, sigma=sigma)


def rough_pair(sigma: float, E_star: float, mu_b: float, eta_beta_sigma: float = 0.1,
               sigma_beta: float = 0.1, share: float = -1.0) -> Roughness:
    """Patir–Cheng flow and Greenwood–Tripp asperities of a rough pair, as :class:`Roughness`.

    ``sigma`` σ (mm), ``E_star`` the contact modulus (MPa), ``mu_b`` the boundary
    friction; ηβσ and σ/β the asperity density and radius (dimensionless; 0.1 and
    0.1 are typical of ground steel against a smooth elastomer or of engineering
    surfaces, Greenwood & Tripp 1970); ``share``: −1 the counterface rough.
    """
    beta = sigma / sigma_beta
    KE = mixed.asperity_constant(eta_beta_sigma / (beta * sigma), beta, sigma) * E_star
    return Roughness(sigma, asperity=greenwood_tripp(KE, sigma), share=share, mu_b=mu_b)


class Roughness:
    """The combined roughness of a lubricated pair and its laws.

    Args:
        sigma: combined RMS roughness σ (mm).
        asperity: a :class:`~tribofx.laws.Law` p_a(h) (MPa), e.g. :func:`greenwood_tripp`;
            None: no asperity contact (average flow only).
        flow: (φ_x, Φ_s) laws of H = h/σ, or None (smooth flow: φ_x = 1, no shear flow).
        share: share s of the shear flow: +1 the layer rough, −1 the counterface
            rough, 0 both alike.
        shear: (φ_f/H, φ_fp, Φ_fs/H) laws of the wall shear (H = h/σ;
            :func:`forms.mixed.rough_shear_factors`; Φ_fs may be None), or None
            (the smooth shear μ/h, h/2 on the nominal gap).
        mu_b: boundary friction coefficient of the asperity contact.
        delta_v: relative slip speed δ_v regularising the boundary friction's direction,
            ε_v = δ_v (|v_layer|² + |v_counter|²)^½ (:func:`forms.mixed.asperity_traction`).
    """

    def __init__(self, sigma: float, asperity: Law | None = None,
                 flow: Literal["patir-cheng"] | tuple[Law, Law] | None = "patir-cheng",
                 share: float = -1.0, mu_b: float = 0.0, delta_v: float = 1e-3,
                 shear: (Literal["patir-cheng"] | tuple[Law, Law, Law | None]
                         | None) = "patir-cheng") -> None:
        self.sigma, self.share, self.mu_b, self.delta_v = float(sigma), float(share), \
            float(mu_b), float(delta_v)
        self.asperity = asperity
        self.flow = (patir_cheng_pressure(), patir_cheng_shear()) if flow == "patir-cheng" \
            else flow
        self.shear = patir_cheng_shear_stress() if shear == "patir-cheng" else shear

    def bind(self, mesh: dmesh.Mesh) -> tuple[BoundLaw | None, BoundLaw | None, BoundLaw | None,
                                              tuple[BoundLaw | None, ...] | None]:
        """Return the bound laws (phi_x, phi_s, p_a, shear) on ``mesh`` (None where absent).

        ``shear`` is the tuple (φ_f/H, φ_fp, Φ_fs/H) or None.
        """
        phi_x = phi_s = None
        if self.flow is not None:
            phi_x, phi_s = (law.bind(mesh) for law in self.flow)
        p_a = self.asperity.bind(mesh) if self.asperity is not None else None
        shear = None if self.shear is None else tuple(
            law.bind(mesh) if law is not None else None for law in self.shear)
        return phi_x, phi_s, p_a, shear
