"""Archard-type wear at finite deformation (chapter §3, eqs. 10–18; §4.4, eq. 28).

Rates are volumes per unit area and time (mm/s).  Notation:

* ``Ẇ`` nominal wear rate, per unit area of the *undeformed (worn)* configuration
  Ω (eq. 10); ``ẇ`` spatial wear rate, per unit current area (eq. 11);
  j ẇ = J Ẇ (eq. 12).
* ``ḋ = t_T·v_T`` spatial, ``Ḋ = j ḋ = T_T·v_T`` nominal frictional dissipation
  density (eq. 13; MPa·mm/s = N/(mm·s)).
* Nominal Archard law (14): Ẇ = K Ḋ; spatial law (15)–(16): ẇ = k ḋ, i.e.
  Ẇ = (k/J) Ḋ.  With Coulomb friction ‖T_T‖ = μ|T_N| and the classical
  Archard coefficient k_A (mm³/(N·mm)): Ẇ = k_A |T_N| ‖v_T‖, so K = k_A/μ.
  Frictionless contact (the pin example) uses the pressure form directly.
* Slave/master rates (17)–(18).

The tractions entering these laws are nominal tractions *per unit area of the
worn configuration*.  When the contact multiplier λ is a traction per unit area
of the initial configuration Γ̂_c (every unknown lives on the initial mesh), the
volume removed per unit initial area and time is Ẇ j_w = k_A |λ| ‖v_T‖ with
j_w = dS/dŜ (the rate forms below take j_w where they need it).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import ufl

if TYPE_CHECKING:
    from typing import TypeVar

    import numpy as np
    import numpy.typing as npt
    from ufl.core.expr import Expr

    # a number or an array of nodal values (cycle averages at the slow time scale)
    Values = TypeVar("Values", float, npt.NDArray[np.float64])
    # a UFL expression or an array of nodal values (a dissipation density)
    Density = TypeVar("Density", Expr, npt.NDArray[np.float64])

__all__ = [
    "WearLoad",
    "archard_rate",
    "bdf2_coefficients",
    "constant_coefficient",
    "pressure_dependent_coefficient",
    "archard_dissipation_form",
    "archard_nominal",
    "archard_pressure_form",
    "depth_graded_coefficient",
    "cycle_average_rate",
    "shape_update_residual",
    "wear_depth",
]


def archard_nominal(K: Expr | float, D_nominal: Density) -> Density:
    """Nominal Archard law Ẇ = K Ḋ (eq. 14); K in mm³/(N·mm)·(1/μ) = 1/MPa."""
    return K * D_nominal


def archard_pressure_form(
    k: Expr | float, T_n: Expr | float, slip_speed: Expr | float, J: Expr | None = None
) -> Expr:
    """Archard law in the pressure form Ẇ = k |T_N| ‖v_T‖ (frictionless or K = k/μ).

    With ``J`` given, the spatial law (15) in pressure form, ẇ = k |t_N| ‖v_T‖,
    written nominally by (12)/(16): Ẇ = (k/J) |T_N| ‖v_T‖ (T_N = j t_N).

    Args:
        k: Archard coefficient (mm³/(N·mm) = 1/MPa); may be a UFL expression (e.g.
            depth dependent, :func:`depth_graded_coefficient`).
        T_n: nominal normal traction (≤ 0 in contact, MPa).
        slip_speed: ‖v_T‖ (mm/s).
        J: det F of the deformation relative to the worn configuration (None:
            nominal law (14)).
    """
    rate = k * ufl.max_value(-T_n, 0) * slip_speed
    return rate if J is None else rate / J


def archard_dissipation_form(
    k: Expr | float, mu: Expr | float, t_t: Expr, v_t: Expr, J: Expr | None = None
) -> Expr:
    """Archard law driven by the frictional dissipation, Ẇ = K Ḋ, K = k/μ (eqs. 13–14).

    ``t_t`` is the nominal friction traction and ``v_t`` the slip velocity (or a
    slip increment, giving the wear increment ΔW = K T_T·Δs), so Ḋ = T_T·v_T is
    the nominal dissipation density (13₂).  With Coulomb sliding, ‖T_T‖ = μ|T_N|
    and T_T ∥ v_T, this equals the pressure form k |T_N| ‖v_T‖; in stick it is 0.
    With ``J`` given: the spatial law (15)–(16), Ẇ = (K/J) Ḋ.

    Args:
        k: Archard coefficient (mm³/(N·mm)); may be a UFL expression.
        mu: Coulomb friction coefficient μ > 0.
        t_t: nominal friction traction T_T (MPa), oriented along the slip.
        v_t: slip velocity (mm/s) or slip increment (mm).
        J: det F relative to the worn configuration (None: nominal law (14)).
    """
    rate = archard_nominal(k / mu, ufl.dot(t_t, v_t))
    return rate if J is None else rate / J


def cycle_average_rate(increment: Values, period: float) -> Values:
    """Average wear rate at the slow time scale, W̄̇ = ΔW / Δτ (eq. 23).

    ``increment`` is the wear ΔW accumulated over one fast-time cycle of duration
    ``period`` = Δτ (eq. 22), e.g. Σ_j K T_T·Δs_j over the sub-steps j of a stroke
    cycle (numbers or numpy arrays).
    """
    return increment / period


def depth_graded_coefficient(k0: Expr | float, grad: Expr | float, depth: Expr) -> Expr:
    """Wear coefficient varying linearly with the worn depth, k = k₀ max(1 + g d, 0).

    A graded surface layer (chapter §5.3, Fig. 10b): g > 0 when the coefficient
    rises with depth, g < 0 when it rises towards the surface (the clip at 0 keeps
    a layer that is worn through from producing negative wear).

    Args:
        k0: coefficient at the initial surface (mm³/(N·mm)).
        grad: relative gradient g (1/mm).
        depth: wear depth d below the initial surface (mm), e.g. −w·N̂.
    """
    return k0 * ufl.max_value(1 + grad * depth, 0)


@dataclass(frozen=True)
class WearLoad:
    """What an interface supplies to Archard wear at a point of the worn surface (UFL).

    Every traction is nominal, per unit initial area of the worn surface Γ̂
    (where the wear rows are integrated).

    Attributes:
        normal: normal traction T_N (≤ 0 when pressed, MPa), for the pressure form.
        pressure: argument p of a wear-coefficient law k(p) (MPa); None: −T_N.
        slip_speed: sliding speed ‖v_T‖ of the pressure form (mm/s); None: the
            speed the :class:`tribofx.interfaces.Wear` is given.
        shear, slip, friction: friction traction T_T, slip velocity v_T (or slip
            increment) and friction coefficient μ of the dissipation form (17),
            all given or all None.
    """

    normal: ufl.core.expr.Expr | float
    pressure: ufl.core.expr.Expr | float | None = None
    slip_speed: ufl.core.expr.Expr | float | None = None
    shear: ufl.core.expr.Expr | None = None
    slip: ufl.core.expr.Expr | None = None
    friction: ufl.core.expr.Expr | float | None = None

    @property
    def law_pressure(self) -> ufl.core.expr.Expr | float:
        """The pressure p of k(p): ``pressure``, or −T_N."""
        return -self.normal if self.pressure is None else self.pressure


def archard_rate(
    k: Expr | float, load: WearLoad, speed: Expr | float | None = None, J: Expr | None = None
) -> Expr:
    """Nominal Archard rate per unit initial area, Ẇ j_w, of one :class:`WearLoad` (eqs. 14–17).

    Without a friction traction (``load.shear`` None): the pressure form k |T_N|
    ‖v_T‖ (:func:`archard_pressure_form`; ‖v_T‖ = ``load.slip_speed``, else
    ``speed``).  With friction: the dissipation form (17), K T_T·v_T with
    K = k/μ (:func:`archard_dissipation_form`).  With ``J`` (det F relative to
    the worn configuration): the spatial law (16).  The result is the volume
    removed per unit initial area and time (mm/s).
    """
    if load.shear is None:
        v = speed if load.slip_speed is None else load.slip_speed
        assert v is not None        # a speed is given (a product with None raises)
        return archard_pressure_form(k, load.normal, v, J)
    # shear, slip and friction come together (k/None and a dot with None raise)
    assert load.friction is not None and load.slip is not None
    return archard_dissipation_form(k, load.friction, load.shear, load.slip, J)


def wear_depth(w: Expr, N_hat: Expr) -> Expr:
    """Wear depth d = −w·N̂ below the initial surface (mm), N̂ its outer unit normal."""
    return -ufl.dot(w, N_hat)


def bdf2_coefficients(omega: float) -> tuple[float, float]:
    """Variable-step BDF2 weights (c₀, c₁) of the swept volumes, ω = Δt_{n+1}/Δt_n.

    For y' = f: c₀ (y_{n+1} − y_n) + c₁ (y_n − y_{n−1}) = Δt_{n+1} f_{n+1} with
    c₀ = (1 + 2ω)/(1 + ω), c₁ = −ω²/(1 + ω) (second order for any ω > 0;
    ω = 1: 3/2, −1/2).  ω = 0 gives backward Euler (1, 0), the start.
    """
    return (1 + 2 * omega) / (1 + omega), -omega**2 / (1 + omega)


def shape_update_residual(
    w: Expr, w_old: Expr, a: Expr, rate_density: Expr, dt: Expr | float, eta: Expr,
    ds: ufl.Measure, bdf2: tuple[Expr | float, Expr | float, Expr] | None = None,
) -> ufl.Form:
    """Weak form of the discrete shape evolution law (28) on the contact boundary.

    ∫_Γ̂c η [(w − w_n)·a + Δt Ẇ_{n+θ} j_w] dŜ = 0, where ``a`` is the Nanson
    vector cof(∇̂Ψ) N̂ of the worn boundary (so that (w − w_n)·a dŜ is the volume
    swept per unit initial area) and ``rate_density`` = Ẇ j_w.  Evaluated with a
    vertex quadrature rule this is the nodal update of the normal component.

    Args:
        w: shape-change field at t_{n+1} (mm).
        w_old: shape-change field at t_n (mm).
        a: unnormalised worn normal (Nanson vector, dimensionless).
        rate_density: Ẇ j_w (mm/s).
        dt: time step Δt (s).
        eta: test function of the constraint multiplier.
        ds: measure over the initial contact boundary Γ̂_c.
        bdf2: None (the θ-scheme), or ``(c0, c1, swept_old)``: the variable-step
            BDF2 law in swept volumes per unit initial area,
            ∫ η [c₀ (w − w_n)·a + c₁ s_n + Δt Ẇ_{n+1} j_w] dŜ = 0, with s_n the
            volume swept in the previous step ((w_n − w_{n−1})·a_n, a nodal field)
            and (c₀, c₁) of :func:`bdf2_coefficients`.  The worn volume then obeys
            BDF2 exactly: c₀ ΔV_{n+1} + c₁ ΔV_n = −Δt ∫ Ẇ dS.
    """
    if bdf2 is None:
        return eta * (ufl.dot(w - w_old, a) + dt * rate_density) * ds
    c0, c1, swept_old = bdf2
    return eta * (c0 * ufl.dot(w - w_old, a) + c1 * swept_old + dt * rate_density) * ds


def constant_coefficient(p: Expr, k: Expr | float) -> Expr:
    """Archard's constant wear coefficient k (mm³/(N·mm))."""
    return k + 0 * p


def pressure_dependent_coefficient(
    p: Expr, k0: Expr | float, p_s: Expr | float, m: Expr | float
) -> Expr:
    """k(p) = k₀ (1 + (p⁺/p_s)^m): mild wear below the pressure p_s, severe above (MPa).

    A smooth transition of the kind seen in wear maps (Lim & Ashby 1987); any
    law k(p, ...) of the contact pressure p = −T_N enters :class:`tribofx.interfaces.Wear`
    the same way.
    """
    return k0 * (1 + (ufl.max_value(p, 0) / p_s) ** m)
