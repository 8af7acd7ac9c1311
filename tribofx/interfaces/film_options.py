"""What a film is made of, option by option: its fluid, cavitation model, quadrature and scales.

A :class:`~tribofx.interfaces.Film` (and :class:`~tribofx.interfaces.TwoBodyFilm`,
:class:`~tribofx.interfaces.RigidFilm`) takes its options as a few small values
instead of two dozen loose arguments::

    film = Film(ball, "cap", rigid_plane(origin, normal),
                Fluid(viscosity=barus(1e-8, 2e-2)),
                cavitation=Penalty(eps=1e-4 * 12 * mu * a**2 / h_c**3),
                quadrature=Quadrature("vertex"),
                scales=FilmScales(pressure=p0, film=h_c, speed=U))

* :class:`Fluid` — the lubricant: the viscosity μ(p) (a number in MPa·s or a
  viscosity :class:`tribofx.laws.Law`, :mod:`tribofx.forms.fluid`) and the
  density ρ(p)/ρ₀ (None: incompressible);
* :class:`Penalty` or :class:`JFO` — the cavitation model (None: none, p may
  fall below the cavity pressure); the penalty ε⁻¹ min(p, 0) of the Reynolds rows
  (the penalty method the chapter's O-ring uses, Wu 1986) or the mass-conserving
  JFO model of §6.5 (void fraction λ, complementarity (52), weak form (57));
* :class:`Quadrature` — the rule of the integrals over Γ_l: Gauss of a degree,
  or the vertex rule (second order for P1 fields, exact for nodal data);
* :class:`FilmScales` — the pressure, film and speed scales of the stopping test
  and of the row scales (they do not change the solution, only when Newton
  stops), and the pressure scale of SUPG's Péclet number and the JFO
  complementarity.  A film given none derives them from its problem
  (:meth:`FilmScales.soft_ehl`, :meth:`FilmScales.hydrodynamic`).

Units: mm, N, s, MPa.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

if TYPE_CHECKING:
    from ..laws import Law

__all__ = ["JFO", "Cavitation", "FilmScales", "Fluid", "Penalty", "Quadrature", "named_cavitation"]


@dataclass(frozen=True)
class Fluid:
    """The lubricant: viscosity μ(p) (MPa·s, or a law) and density ρ(p)/ρ₀ (None: constant)."""

    viscosity: float | Law
    density: Law | None = None


@dataclass(frozen=True)
class Penalty:
    """Penalty cavitation: ε⁻¹ min(p, 0) added to the Reynolds rows, ε in MPa·s/mm.

    Smaller ε enforces p ≥ 0 more tightly (the Swift–Stieber conditions as ε → 0);
    a usual choice is a small fraction of the film's hydraulic resistance,
    e.g. 1e-4 · 12 μ ℓ²/h³ for a contact of size ℓ and film h.
    """

    eps: float
    name: ClassVar[str] = "penalty"

    def __post_init__(self) -> None:
        if not self.eps > 0:
            raise ValueError(f"Penalty(eps={self.eps!r}): the penalty parameter must be > 0")


@dataclass(frozen=True)
class JFO:
    """Mass-conserving JFO cavitation: the void fraction λ and its complementarity with p."""

    name: ClassVar[str] = "jfo"


#: a film's cavitation model (None: no cavitation model)
Cavitation = Penalty | JFO


def named_cavitation(name: str, eps: float | None = None) -> Cavitation | None:
    """Return the model named ``name``: "none", "penalty" (ε ``eps``; None: none) or "jfo"."""
    if name == "jfo":
        return JFO()
    if name == "penalty":
        return None if eps is None else Penalty(eps)
    if name == "none":
        return None
    raise ValueError(f"unknown cavitation model {name!r}: none, penalty or jfo")


@dataclass(frozen=True)
class Quadrature:
    """Rule of the integrals over Γ_l: ``"gauss"`` of ``degree`` or ``"vertex"``.

    The vertex rule evaluates the film terms at the nodes, where a meshed
    countersurface's data and a P1 surface are exact (no chord sag h_e²/8R of a
    Gauss point inside a thin film); a node projecting onto a kinked
    countersurface vertex then gets ∂P/∂x = 0 (docs/contact.md).
    """

    rule: str = "gauss"      # "gauss" or "vertex"
    degree: int = 4

    def __post_init__(self) -> None:
        if self.rule not in ("gauss", "vertex"):
            raise ValueError(f"quadrature rule {self.rule!r}: gauss or vertex")

    def metadata(self) -> dict[str, str | int]:
        """Return the UFL measure metadata of the rule."""
        if self.rule == "vertex":
            return {"quadrature_rule": "vertex", "quadrature_degree": 1}
        return {"quadrature_degree": self.degree}


@dataclass(frozen=True)
class FilmScales:
    """Scales of a film's stopping test, row scales, SUPG and JFO complementarity.

    ``pressure`` p_c (MPa): SUPG's Péclet number and the JFO complementarity
    (e.g. the Hertz pressure p₀); ``film`` h_ref (mm): the film thickness of the
    tolerances and row scales (e.g. the central film); ``speed`` U (mm/s): the
    flux scale U·h_ref of the Reynolds tolerance (e.g. the entrainment speed).
    """

    pressure: float = 1.0
    film: float = 1e-2
    speed: float = 1.0

    @classmethod
    def soft_ehl(cls, viscosity: float, speed: float, length: float, modulus: float
                 ) -> FilmScales:
        """Return the elastic–viscous scales of a film on a soft solid (``Film``'s default).

        The viscous pressure μUℓ/h² that a film of thickness h builds over the length
        ℓ deflects a solid of plane-strain modulus E' by about pℓ/E'; where the
        deflection is as large as the film, h³ = μUℓ²/E' and p = E'h/ℓ.  ``viscosity``
        μ₀ (MPa·s), ``speed`` U (mm/s), ``length`` ℓ (mm), ``modulus`` E' (MPa).  A
        film that does not move (U = 0, a squeeze film) has no such scale: h = 1e-3 ℓ.
        """
        h = (viscosity * speed * length**2 / modulus) ** (1 / 3) if speed > 0 else 1e-3 * length
        return cls(pressure=modulus * h / length, film=h, speed=speed)

    @classmethod
    def hydrodynamic(cls, viscosity: float, speed: float, film: float, length: float
                     ) -> FilmScales:
        """Return the scales of a film of a given gap (``RigidFilm``'s default).

        ``film`` the least gap h (mm), ``length`` the inlet length ℓ over which the
        gap doubles (mm; √(2Rh) for a cylinder): the pressure 6μUℓ/h² of the wedge.
        Surfaces at rest (U = 0) build no wedge pressure: the class default p_c = 1 MPa
        then stands (a squeeze film is better given its own scales).
        """
        wedge = 6 * viscosity * speed * length / film**2
        return cls(pressure=wedge if wedge > 0 else cls.pressure, film=film, speed=speed)

    def __post_init__(self) -> None:
        for key in ("pressure", "film"):
            if not getattr(self, key) > 0:
                raise ValueError(f"FilmScales({key}={getattr(self, key)!r}): must be > 0")
        if not self.speed >= 0:
            raise ValueError(f"FilmScales(speed={self.speed!r}): must be >= 0")
