"""Reciprocating O-ring seal: axisymmetric soft EHL (chapter §8.1, Figs. 15–19).

An elastomeric O-ring of cross-section diameter d sits in a housing groove and
seals the pressure p_s against a rod of radius r_rod sliding axially with speed
U (U > 0 outstroke: the rod moves towards the air side, +z; U < 0 instroke).
Axisymmetric about the rod axis, mesh coordinates (r, z):

* seal: nearly incompressible Mooney–Rivlin, ψ = μ₁/2 (Ī₁ − 3) + μ₂/2 (Ī₂ − 3)
  + κ/2 (J − 1)², 3×3 F with hoop stretch r/R, weight 2πR (forms/hyperelastic);
* housing: groove bottom r = r_g = r_rod + d(1 − squeeze) and air-side wall,
  rigid planes, frictionless augmented-Lagrangian contact; sealed side open;
* sealed pressure: follower pressure p_s on the quarter of the ring boundary
  facing the sealed side (225° ≤ φ ≤ 315°) and p = p_s at the sealed-side end
  of the film (simple robust choice: the fluid at p_s reaches the film through
  the sealed-side flank of Γ_l; the arc between the flank and the groove bottom
  is loaded by p_s whether or not it touches the bottom);
* rod: soft-EHL film on the inner quarter arc Γ_l (135° ≤ φ ≤ 225°): S = P(γ_l)
  on the rod cylinder, h = r − r_rod, v̄ = ½U e_z, steady Reynolds equation (49)
  on the surface of revolution (weight 2π r_rod times the meridian stretch),
  SUPG; cavitation (``cavitation``): JFO (57, mass-conserving, the default with
  the mixed solid: void fraction λ, p ≥ 0, λ ≥ 0, pλ = 0 at the nodes; flooded
  inlet p = p_s or 0, λ = 0 at the upstream end, a natural outlet downstream in
  outstroke, p = p_s at the sealed end in instroke) or the penalty ε⁻¹ min(p, 0)
  with p = p_s / 0 at the sealed / air end (the chapter's; the default with the
  displacement solid);
  fluid traction (46): pressure (axisymmetric Nanson), Couette (μ/h)U e_z and
  Poiseuille −(h/2) grad_S p shear (forms/ehl_axisym.py).

Solution path: the ring starts ``gap0`` clear of the rod with the film on; the
groove bottom is moved in ``mount_steps`` steps to r_g (squeeze) at the mounting
pressure 0.1 MPa and the mounting speed U_m = sign(U) max(|U|, 1000 mm/s) (a
thicker film is easier); p_s is raised to the first target, the speed lowered
geometrically to U, then the other p_s targets follow.  Each continuation
step is cut on Newton failure (the last converged state is kept and written).

Core configuration: a :class:`~tribofx.body.Body` (axisymmetric Mooney–Rivlin,
follower pressure p_s on the sealed arc), two
:class:`~tribofx.interfaces.Contact` on the housing arc (sealed ∪ housing facets)
against :func:`~tribofx.obstacles.rigid_plane` (groove bottom, moved by its
offset; air-side wall), a :class:`~tribofx.interfaces.Film` on Γ_l against the
rod line r = r_rod moving with ``V_counter`` = U e_z, one
:class:`~tribofx.problem.Problem` with the admissible line search (a trial step
is accepted when it keeps the film open, h > 0, and R finite: ‖R‖ is a poor
merit function with the thick-film flanks of Γ_l) and
:class:`~tribofx.continuation.Continuation` in the groove offset, p_s and U.

``stroke=cycle``: the transient film over a reciprocating stroke,
U(t) = U cos(2πt/``period``), from the steady outstroke at the first p_s, with
an open air end supplied by the layer the rod carried out and an optional rough
rod (``sigma``); :mod:`tribofx.cases.oring_cycle`.

Default data (mm, N, s, MPa), after Stupkiewicz (2009) and Stupkiewicz &
Marciniszyn (Tribol. Int. 42, 2009) where the chapter fixes them:

* μ₁ + μ₂ = 3.66 MPa (chapter §8.1); split μ₁ = 2.93, μ₂ = 0.73 (μ₂/μ₁ = 0.25,
  a common ratio for NBR, our choice); κ = 1000 (μ₁ + μ₂) = 3660 MPa;
* d = 3.5 mm, r_rod = 10 mm, squeeze 10 % (typical dynamic O-ring gland);
* oil viscosity μ = 5e-8 MPa·s (0.05 Pa·s), U = 400 mm/s (Fig. 18: outstroke,
  p_s = 1 MPa, U = 400 mm/s);
* mesh density n: element size 0.1/n mm on Γ_l (0.1/(n·2^k) with
  ``arc_refine`` k: the film's inlet, where its thickness is set, is a few
  elements long at 100 mm/s), 0.4/n mm in the bulk; P1
  displacement with a P1 volumetric stress (``formulation=mixed``, default:
  locking-free; the chapter's zigzag film oscillations are the volumetric
  locking of the P1 displacement solid, ``formulation=displacement``), P1 film
  pressure.

``study=mesh`` repeats the outstroke at the first p_s on the densities
``mesh_levels`` (Figs. 18–19) and reports an oscillation indicator per density
(mean |Δ²h| / 4h̄ in the loaded zone p − p_s > (p_max − p_s)/2: the relative
zigzag amplitude)
and the change of the mean film h̄ of that zone from level to level.

Your own cross-section (``mesh_file``): a 2D gmsh ``.msh`` in the meridian plane
(r, z) with the physical groups ``lubricated`` (Γ_l, one open curve facing the
rod), ``sealed`` (loaded by p_s) and ``housing`` (the rest of the boundary that
may touch the groove bottom or the air-side wall; both housing contacts act on
sealed ∪ housing, as on the built section), read and checked by
:func:`tribofx.meshes.user.read_user_mesh`.  It replaces ``d`` (the radial
extent of the mesh, also the groove depth of ``squeeze``) and ``mesh`` (the
elements are the user's; ``study=mesh`` is rejected).  The section is moved so
that its innermost node is at r = r_rod + gap0 and its z extent centred at
z = 0; with a the radial half extent, the groove bottom starts 10⁻³ a inside
its outermost node and the air-side wall 0.005 mm below its top, as for the
built circle.  a also sets the penalty scale ℓ = a/4 and the augmentation
ρ_N = E/a of the housing contacts: a geometric scale for the built section
too (no element size is taken from either mesh; SUPG takes the cell size of
Γ_l).  Γ_l must end at its two z extremes, each the only node of Γ_l at that
height (checked): p = p_s at the lower (sealed-side) end, p = 0 at the upper
one.  All other parameters apply as for the built section.

Results per stroke and p_s (prefix ``out_``/``in_`` and ``ps<value>_``): p_max,
h_min and its position, h at the pressure peak, mean film h_mean of the loaded
zone, flux q = h v̄ − h³/(12μ) ∂p/∂z per circumference (median over the loaded
zone), leakage 2π r_rod q, radial load and friction force per circumference,
oscillation indicator, axial equilibrium error (sum of axial forces / axial
force of p_s).  Plots ``profiles.png`` (Fig. 17, out vs in), ``mesh_study.png``
(Figs. 18–19).  VTX of u and p at the end and as time series per stroke
(``outstroke_displacement_series.bp``, ``outstroke_pressure_series.bp``, ``in…``:
one time index per sealed pressure, its p_s in ``series_points``).
"""



from ..params import InputError, Param, number_list
from .ehl_oring_run import ORingRun
from .film_setup import (
    VISCOSITY_PARAMS,
    cavitation_model,
    density,
    formulation_param,
    viscosity,
)

__all__ = ["EHLORingCase"]

class EHLORingCase(ORingRun):
    """Case ``ehl-oring``; see the module docstring."""

    name = "ehl-oring"
    doc = "soft-EHL of a reciprocating O-ring seal (axisymmetric, housing contact)"
    params = (
        Param("p_s", str, "1", "MPa", "sealed pressures (comma-separated, increasing)"),
        Param("U", float, 400.0, "mm/s", "rod speed (> 0 outstroke, < 0 instroke)"),
        Param("stroke", str, "single", "-", "single (sign of U), both (U and −U, steady) or "
              "cycle (transient: U cos(2πt/period) from the steady outstroke; first p_s; "
              "tribofx.cases.oring_cycle)",
              choices=("single", "both", "cycle")),
        Param("period", float, 0.1, "s", "stroke=cycle: period of the rod's motion", lower=0),
        Param("cycle_steps", int, 40, "-", "stroke=cycle: time steps per period (halved on "
              "Newton failure)", lower=4),
        Param("cycles", float, 1.0, "-", "stroke=cycle: periods to run", lower=0),
        Param("scheme", str, "euler", "-", "stroke=cycle: time scheme of the film, euler "
              "or bdf2", choices=("euler", "bdf2")),
        Param("sigma", float, 0.0, "mm", "stroke=cycle: RMS roughness σ of the rod (0: "
              "smooth; > 0: mixed film, Patir–Cheng flow, Greenwood–Tripp asperities, "
              "ηβσ = σ/β = 0.1)",
              lower=0, closed=True),
        Param("mu_b", float, 0.1, "-", "boundary friction of the asperities (sigma > 0)",
              lower=0, closed=True),
        Param("mu", float, 5e-8, "MPa·s", "oil viscosity", lower=0),
        Param("mesh", int, 4, "-", "mesh density n (element 0.1/n mm on the film arc)",
              lower=1, upper=32, closed=True),
        Param("arc_refine", int, None, "-", "halvings of the element size on the film arc "
              "(0.1/(n·2^k) mm; the bulk keeps 0.4/n mm; default: 1 with stroke=cycle, "
              "else 0)", lower=0, upper=3, closed=True),
        Param("degree", int, 1, "-", "Lagrange degree of the displacement", choices=(1, 2)),
        formulation_param("mixed"),
        Param("squeeze", float, 0.1, "-", "radial squeeze (d − groove depth)/d", lower=0,
              upper=0.3),
        Param("d", float, 3.5, "mm", "cross-section diameter", lower=0),
        Param("r_rod", float, 10.0, "mm", "rod radius", lower=0),
        Param("mu1", float, 2.93, "MPa", "Mooney–Rivlin μ₁", lower=0),
        Param("mu2", float, 0.73, "MPa", "Mooney–Rivlin μ₂", lower=0, closed=True),
        Param("kappa", float, 3660.0, "MPa", "bulk modulus", lower=0),
        Param("cavitation", str, "auto", "-",
              "penalty (ε⁻¹ min(p, 0), Swift–Stieber limit), jfo (mass-conserving: void "
              "fraction λ, flooded inlet, natural outlet) or auto: jfo with the mixed solid, "
              "penalty with the displacement one (a locked, zig-zag surface makes JFO's "
              "semismooth iteration cycle)", choices=("auto", "penalty", "jfo")),
        Param("eps", float, 1e-4, "-", "cavitation penalty ε relative to 12μℓ²/h_ref³",
              lower=0),
        Param("supg", bool, True, "-", "SUPG in the Reynolds equation"),
        Param("gap0", float, 0.02, "mm", "initial clearance to the rod", lower=0),
        Param("mount_steps", int, 10, "-", "squeeze increments", lower=1),
        Param("ramp_steps", int, 4, "-", "p_s increments per target", lower=1),
        Param("speed_steps", int, 3, "-", "geometric speed increments", lower=1),
        Param("study", str, "none", "-", "none or mesh (density study, Figs. 18–19)",
              choices=("none", "mesh")),
        Param("mesh_levels", str, "1,2,4", "-", "densities of study=mesh"),
        Param("mesh_file", str, "", "-",
              "your own cross-section: a 2D gmsh .msh in (r, z) with physical groups "
              "lubricated (Γ_l facing the rod, one open curve), sealed (loaded by p_s), "
              "housing (touches groove bottom/wall); replaces d (its radial extent) and "
              "mesh; moved to r_min = r_rod + gap0, z extent centred at 0"),
    ) + VISCOSITY_PARAMS

    @staticmethod
    def validate(v):
        """Parse the lists and check the consistency of the values."""
        viscosity(v)
        density({**v, "cavitation": cavitation_model(v)})
        ps = number_list(v["p_s"], "p_s")
        if any(p <= 0 for p in ps):
            raise InputError("p_s must be > 0 MPa (frictionless housing: p_s holds the ring)")
        if ps != sorted(ps):
            raise InputError("p_s must be increasing")
        if v["U"] == 0:
            raise InputError("U must be nonzero (mm/s)")
        if v["stroke"] == "cycle" and (v["U"] < 0 or cavitation_model(v) != "jfo"
                                       or v["study"] != "none"):
            raise InputError("stroke=cycle starts from the outstroke (U > 0) and needs "
                             "cavitation=jfo (mass-conserving) and study=none")
        if v["sigma"] > 0 and v["stroke"] != "cycle":
            raise InputError("sigma (a rough rod) is built for stroke=cycle")
        levels = number_list(v["mesh_levels"], "mesh_levels")
        if any(k < 1 or k != int(k) for k in levels):
            raise InputError("mesh_levels must be positive integers")
        if v["mesh_file"]:
            if v["study"] != "none" or v["arc_refine"]:
                raise InputError("mesh_file works with study=none and arc_refine=0 only")
        elif v["gap0"] >= 0.5 * v["d"]:
            raise InputError("gap0 must be below the cross-section radius")

    UNITS = {"p_max": "MPa", "z_p_max": "mm", "h_at_p_max": "mm", "h_mean": "mm", "h_min": "mm",
             "z_h_min": "mm", "flux": "mm^2/s", "leakage": "mm^3/s",
             "load_per_circumference": "N/mm", "friction_force_per_circumference": "N/mm",
             "oscillation": "-", "flux_spread": "-", "axial_balance": "-"}

