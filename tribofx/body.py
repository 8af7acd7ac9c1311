"""A hyperelastic body: mesh and named tags, kinematic kind, material, u, BCs and loads.

Everything lives on the initial mesh: fields are functions of the reference coordinates X.
A body contributes the internal virtual work of eq. (7) to the row of its
displacement u,

    ∫_Ω P(F) : Grad δu dV − ∫_Γt T*·δu dS = 0,        F = I + Grad u,

2πR-weighted for axisymmetric bodies.  With ``shape=True`` it also carries the
ALE shape field w of the wear formulation (X = X̂ + w, eqs. 19–20): the internal
work is then written on the worn configuration, F = (I + Grad u)(I + Grad w)⁻¹
(:func:`tribofx.forms.ale.internal_virtual_work_worn`), and w obeys the
auxiliary elasticity problem (:func:`tribofx.forms.ale.aux_elasticity`) whose
boundary data a wear interface supplies.  An optional constant Eulerian
background velocity V (eq. 26) is stored for interfaces that need v = F V.

Tags are looked up by name (``names = {"contact": 1, ...}``), so that a case or a
user's mesh file names its boundaries once.  Units: mm, N, MPa.

``formulation="mixed"`` adds the volumetric stress p (P1, MPa) as a second
unknown of the body: the stabilised perturbed-Lagrangian (u, p) form of
:func:`tribofx.forms.hyperelastic.mixed_virtual_work`, locking-free for linear
elements of a nearly incompressible solid (the O-ring's elastomer).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, cast, overload

import numpy as np
import ufl
from dolfinx import fem, la
from mpi4py import MPI

from .forms import ale
from .forms import hyperelastic as hf
from .forms import kinematics as kin
from .params import InputError
from .problem import BlockTolerance
from .protocols import ComponentBase

if TYPE_CHECKING:
    from collections.abc import Mapping

    import numpy.typing as npt
    import ufl.core.expr
    from dolfinx import mesh as dmesh

    #: a material: (law of :mod:`tribofx.forms.hyperelastic`, {parameter: value}), each
    #: value a number or a UFL expression (e.g. a modulus graded with the depth)
    Material = tuple[str, Mapping[str, Any]]

__all__ = ["AXISYMMETRIC_MOTION", "FORMULATIONS", "Body", "shear_modulus"]

#: why an axisymmetric body's material or countersurface moves only along the axis
AXISYMMETRIC_MOTION = (
    "an axisymmetric body slides only along its axis: a radial velocity is no rigid motion "
    "of a surface of revolution; give the velocity as (0, V), or model the body in 3D")

#: formulations of the solid (``Body(formulation=...)``)
FORMULATIONS = ("displacement", "mixed")


def shear_modulus(material: str, params: Mapping[str, Any]) -> float:
    """Small-strain shear modulus (MPa) of a law of :mod:`tribofx.forms.hyperelastic`."""
    if "mu" in params:
        return float(params["mu"])
    if "mu1" in params:
        return float(params["mu1"]) + float(params.get("mu2", 0.0))
    raise ValueError(f"no shear modulus in the parameters of {material!r}")


class Body(ComponentBase):
    """A deformable body on the initial mesh ``mesh``.

    Args:
        mesh: the mesh (affine geometry for contact interfaces).
        facet_tags: facet meshtags; ``names`` maps boundary names to their values.
        names: {boundary name: facet tag value}, or a tuple of tag values for a
            boundary made of several tagged parts (the O-ring's housing).
        kind: "3d", "plane_strain" or "axisymmetric".
        material: (law, params) of :mod:`tribofx.forms.hyperelastic`, or
            {cell tag value: (law, params)} for a body of several materials
            (then ``cell_tags`` is required).
        cell_tags: cell meshtags (for several materials).
        degree: Lagrange degree of u.
        quadrature_degree: volume quadrature degree.  None: 2·degree where the
            integrand varies over a cell (degree ≥ 2, or an axisymmetric body, whose
            integrand carries r and u_r/r), the degree of the P-k mass and stiffness
            on affine cells (the rational terms of the stored energy are integrated
            to an error of a higher order than the discretisation's, Ciarlet's
            2k − 2 rule); otherwise UFL's estimate (a P1 body in plane strain or 3D
            has a cellwise constant integrand: one point is exact).  UFL's estimate
            for the neo-Hookean P2 integrand is 17, for an axisymmetric P1 one 33.
        shape: carry the ALE shape field w (finite wear): True — w is an unknown
            with its auxiliary elasticity rows; "image" — w is the image of a
            reduced field owned by another component (e.g. a cross-section
            extruded along the sliding direction, :mod:`tribofx.interfaces.steady_wear`),
            a coefficient here; a ``fem.Function``: that Function is the image
            (for material parameters that depend on it, e.g. a graded layer).
        aux: (E, ν) of the auxiliary elasticity of w (MPa, -).
        velocity: constant Eulerian background velocity V (mm/s), or None.
        name: name of the body (unknown names, reports).
        rtol: relative size of the momentum stopping tolerance (see :meth:`tolerances`).
        force_scale: force (N; N/mm in plane strain) the momentum tolerance is
            relative to (default G·L^{d−1}, see :meth:`tolerances`); a case with
            loads far below the body's stiffness passes its load.
        stiffness: small-strain shear modulus G (MPa) of the tolerances (default: from
            the material parameters; needed when they are UFL expressions, e.g. a
            modulus graded with the depth).
        formulation: "displacement" (u only) or "mixed" (u and the volumetric
            stress p, P1, with the pressure stabilisation β = α h_K²/G of
            :mod:`tribofx.forms.hyperelastic`; not with a shape field).
        alpha: the stabilisation factor α of the mixed formulation (−).
    """

    w: fem.Function | None
    w_n: fem.Function | None
    p: fem.Function | None
    velocity: fem.Constant | None
    _bcs: list[fem.DirichletBC]
    _w_bcs: list[fem.DirichletBC]
    _loads: list[ufl.Form]
    _multiplier_fixes: list[tuple[npt.NDArray[np.int32], int | None]]
    _laws: dict[int | None, tuple[str, dict[str, Any]]]

    def __init__(self, mesh: dmesh.Mesh, facet_tags: dmesh.MeshTags,
                 names: Mapping[str, int | tuple[int, ...]],
                 kind: str, material: Material | dict[int, Material],
                 cell_tags: dmesh.MeshTags | None = None, degree: int = 1,
                 quadrature_degree: int | None = None,
                 shape: bool | str | fem.Function = False,
                 aux: tuple[float, float] = (1.0, 0.3), velocity: npt.ArrayLike | None = None,
                 name: str = "body", rtol: float = 1e-10, force_scale: float | None = None,
                 stiffness: float | None = None, formulation: str = "displacement",
                 alpha: float = 0.1) -> None:
        if kind not in kin.KINDS:
            raise ValueError(f"unknown kind {kind!r}; expected one of {kin.KINDS}")
        if formulation not in FORMULATIONS:
            raise ValueError(f"unknown formulation {formulation!r}; expected one of "
                             f"{FORMULATIONS}")
        if formulation == "mixed" and shape is not False:
            raise InputError("the mixed formulation is not available with a shape field "
                             "(finite wear)")
        if kind == "axisymmetric" and shape is not False:
            raise InputError("finite wear (a shape field) needs a '3d' or 'plane_strain' body: "
                             "the worn-body kinematics of a surface of revolution are not built; "
                             "model a sector of the body in 3D instead")
        if kind == "axisymmetric" and velocity is not None and np.asarray(velocity)[0] != 0:
            raise InputError(AXISYMMETRIC_MOTION)
        self.mesh, self.facet_tags, self.names, self.kind = mesh, facet_tags, dict(names), kind
        self.cell_tags, self.name = cell_tags, name
        self.materials = material if isinstance(material, dict) else {None: material}
        if None not in self.materials and cell_tags is None:
            raise ValueError("several materials need cell_tags")
        # the forms take the numbers as Constants: a body of other moduli reuses the
        # compiled kernels (UFL would bake each value into a new kernel)
        self._laws = {tag: (law, {k: fem.Constant(mesh, float(x))
                                  if isinstance(x, (int, float)) else x
                                  for k, x in params.items()})
                      for tag, (law, params) in self.materials.items()}
        gdim = mesh.geometry.dim
        self.gdim = gdim
        self.V = fem.functionspace(mesh, ("Lagrange", degree, (gdim,)))
        self.u = fem.Function(self.V, name=f"{name}_displacement" if name != "body"
                              else "displacement")
        if quadrature_degree is None and (degree > 1 or kind == "axisymmetric"):
            quadrature_degree = 2 * degree
        qd = {} if quadrature_degree is None else {"quadrature_degree": quadrature_degree}
        self.dx = ufl.Measure("dx", mesh, subdomain_data=cell_tags, metadata=qd)
        self.ds = ufl.Measure("ds", mesh, subdomain_data=facet_tags)
        self.weight = kin.reference_volume_factor(mesh, kind)
        self.velocity = None if velocity is None else fem.Constant(
            mesh, np.asarray(velocity, dtype=float))
        self.v = ufl.TestFunction(self.V)
        self._bcs, self._loads = [], []
        self._multiplier_fixes = []  # interfaces told about prescribed components
        self.w = self.w_n = None
        self._w_bcs = []
        self.shape_is_unknown = shape is True
        if isinstance(shape, fem.Function):
            self.w = shape
        elif shape == "image":
            self.w = fem.Function(self.V, name="shape_change_3d")
        elif shape:
            # a distinct (equal) space: Dirichlet conditions are sorted into blocks by space
            self.Vw = fem.functionspace(mesh, self.V.ufl_element())
            self.w = fem.Function(self.Vw, name="shape_change")
            self.w_n = fem.Function(self.Vw, name="shape_change_old")
            E_a, nu_a = aux
            self._aux = hf.lame_parameters(E_a, nu_a)
        lo = mesh.geometry.x[:, :gdim].min(axis=0, initial=np.inf)
        hi = mesh.geometry.x[:, :gdim].max(axis=0, initial=-np.inf)
        mesh.comm.Allreduce(MPI.IN_PLACE, lo, op=MPI.MIN)
        mesh.comm.Allreduce(MPI.IN_PLACE, hi, op=MPI.MAX)
        self.length = float(np.linalg.norm(hi - lo))
        self.stiffness = float(stiffness) if stiffness is not None else max(
            shear_modulus(m, p) for m, p in self.materials.values())
        self.rtol = rtol
        self.force_scale = force_scale
        self.p = None
        if formulation == "mixed":
            self.Q = fem.functionspace(mesh, ("Lagrange", 1))
            self.p = fem.Function(self.Q, name=f"{name}_volumetric_stress")
            h_K = ufl.CellDiameter(mesh)
            self._beta = fem.Constant(mesh, float(alpha)) * h_K**2 / self.stiffness

    # -- tags ------------------------------------------------------------------
    def tag(self, name: str) -> int | tuple[int, ...]:
        """Facet tag value (or values) of the boundary ``name`` (one-line error if unknown)."""
        if name not in self.names:
            raise InputError(f"{self.name}: no boundary named {name!r}; "
                             f"known: {', '.join(self.names)}")
        return self.names[name]

    def facets(self, name: str) -> npt.NDArray[np.int32]:
        """Local facet indices of the boundary ``name`` (error if empty on all ranks)."""
        tag = self.tag(name)
        facets = (np.unique(np.concatenate([self.facet_tags.find(t) for t in tag]))
                  if isinstance(tag, tuple) else self.facet_tags.find(tag))
        if self.mesh.comm.allreduce(len(facets), op=MPI.SUM) == 0:
            raise InputError(f"{self.name}: boundary {name!r} has no facets")
        return facets

    # -- boundary conditions and loads ------------------------------------------
    @overload
    def add_dirichlet(self, name: str, value: fem.Function,
                      component: int | None = None) -> fem.Function: ...

    @overload
    def add_dirichlet(self, name: str, value: npt.ArrayLike,
                      component: int | None = None) -> fem.Constant: ...

    def add_dirichlet(self, name: str, value: npt.ArrayLike | fem.Function,
                      component: int | None = None) -> fem.Constant | fem.Function:
        """Prescribe u (or one ``component``) on boundary ``name``; returns the value holder.

        ``value``: a vector, a scalar (with ``component``) or a Function of the
        body's space; the returned Constant (or the Function) can be changed later.
        """
        fdim = self.mesh.topology.dim - 1
        facets = self.facets(name)
        if isinstance(value, fem.Function):  # a field, e.g. a manufactured solution
            dofs = fem.locate_dofs_topological(self.V, fdim, facets)
            self._bcs.append(fem.dirichletbc(value, dofs))
            self._multiplier_fixes.append((facets, component))
            return value
        if component is None:
            c = fem.Constant(self.mesh, np.asarray(value, dtype=float))
            dofs = fem.locate_dofs_topological(self.V, fdim, facets)
            self._bcs.append(fem.dirichletbc(c, dofs, self.V))
        else:
            Vc = self.V.sub(component)
            c = fem.Constant(self.mesh, float(cast("float", value)))  # a scalar here
            dofs = fem.locate_dofs_topological(Vc, fdim, facets)
            self._bcs.append(fem.dirichletbc(c, dofs, Vc))
        self._multiplier_fixes.append((facets, component))
        return c

    def prescribed(self) -> list[tuple[npt.NDArray[np.int32], int | None]]:
        """(facets, component) pairs where u is prescribed (component None: all)."""
        return list(self._multiplier_fixes)

    def add_traction(self, name: str, traction: ufl.core.expr.Expr) -> None:
        """Dead nominal traction T* (UFL vector, MPa) on boundary ``name``.

        On a body with a shape field the traction is per unit *worn* area.
        """
        ds = self.ds(self.tag(name))
        if self.w is not None:
            self._loads.append(ale.traction_work_worn(traction, self.w, self.v,
                                                      ufl.FacetNormal(self.mesh), ds))
        else:
            self._loads.append(hf.external_virtual_work(traction, self.v, self.kind, ds))

    def add_body_force(self, force: ufl.core.expr.Expr) -> None:
        """Dead body force B (UFL vector, N/mm³ per unit reference volume): ∫ B·δu dV."""
        self._loads.append(hf.body_force_work(force, self.v, self.kind, self.dx))

    def add_follower_pressure(self, name: str, pressure: ufl.core.expr.Expr | float) -> None:
        """Follower pressure p (MPa) on boundary ``name``: T = −p J F⁻ᵀ N (Nanson)."""
        self._loads.append(hf.follower_pressure_work(pressure, self.u, self.v, self.kind,
                                                     self.ds(self.tag(name))))

    def add_shape_dirichlet(self, name: str, component: int,
                            except_on: str | None = None) -> None:
        """Zero normal motion of the worn boundary: w[component] = 0 on boundary ``name``.

        ``except_on``: a boundary whose nodes stay free (e.g. the worn boundary where
        it meets ``name``: its shape-law rows keep their w columns).
        """
        fdim = self.mesh.topology.dim - 1
        Vc = self.Vw.sub(component)
        dofs = fem.locate_dofs_topological(Vc, fdim, self.facets(name))
        if except_on is not None:
            # a node of ``except_on`` may lie on a rank that holds none of its facets:
            # mark the nodes on the ranks that do and share the marks (owner and ghosts)
            V0, parent = Vc.collapse()
            mark = fem.Function(V0)
            mark.x.array[fem.locate_dofs_topological(V0, fdim, self.facets(except_on))] = 1
            mark.x.scatter_reverse(la.InsertMode.add)
            mark.x.scatter_forward()
            free = np.asarray(parent).ravel()[np.flatnonzero(mark.x.array > 0)]
            dofs = np.setdiff1d(dofs, free).astype(np.int32)
        self._w_bcs.append(fem.dirichletbc(fem.Constant(self.mesh, 0.0), dofs, Vc))

    # -- kinematics ----------------------------------------------------------------
    def position(self) -> ufl.core.expr.Expr:
        """Return the current position x = X̂ + u (UFL) of the initial mesh's points."""
        return kin.spatial_position(self.u)

    def deformation_gradient(self) -> ufl.core.expr.Expr:
        """F relative to the current reference (worn if the body has a shape field)."""
        if self.w is not None:
            return ale.deformation_gradient_worn(self.u, self.w, self.kind)
        return kin.deformation_gradient(self.u, self.kind)

    # -- component protocol (tribofx.problem) ---------------------------------------
    def internal_work(self) -> ufl.Form:
        """Return the internal virtual work of eq. (7) over all materials (worn if shaped).

        Mixed formulation: the u row of the mixed energy (its p row is the second
        block of :meth:`contributions`).
        """
        if self.p is not None:
            return self._mixed()[0]
        R = 0
        for tag, (law, params) in self._laws.items():
            dx = self.dx if tag is None else self.dx(tag)
            if self.w is not None:
                R += ale.internal_virtual_work_worn(self.u, self.w, self.v, self.kind, law,
                                                    params, dx)
            else:
                R += hf.internal_virtual_work(self.u, self.v, self.kind, law, params, dx)
        return cast("ufl.Form", R)   # a sum over at least one material

    def _mixed(self) -> tuple[ufl.Form, ufl.Form]:
        """(R_u, R_p) of the mixed formulation summed over the materials."""
        R_u = R_p = 0
        q = ufl.TestFunction(self.Q)
        for tag, (law, params) in self._laws.items():
            dx = self.dx if tag is None else self.dx(tag)
            ru, rp = hf.mixed_virtual_work(self.u, self.p, self.v, q, self.kind, law, params,
                                           dx, self._beta)
            R_u, R_p = R_u + ru, R_p + rp
        return cast("tuple[ufl.Form, ufl.Form]", (R_u, R_p))

    def strain_energy(self) -> float:
        """Return the stored energy ∫ ψ(F) dV of the current state (N·mm; N·mm/mm in 2D)."""
        E = 0
        for tag, (law, params) in self._laws.items():
            dx = self.dx if tag is None else self.dx(tag)
            if self.w is not None:
                E += ale.stored_energy_worn(self.u, self.w, self.kind, law, params, dx)
            elif self.p is not None:
                F = kin.deformation_gradient(self.u, self.kind)
                E += hf.mixed_strain_energy(F, self.p, law, params) * self.weight * dx
            else:
                E += hf.stored_energy(self.u, self.kind, law, params, dx)
        return self.mesh.comm.allreduce(fem.assemble_scalar(fem.form(cast("ufl.Form", E))),
                                        op=MPI.SUM)

    def unknowns(self) -> list[fem.Function]:
        """Return u, and w for a shaped body or p for a mixed one."""
        return ([self.u] + ([cast("fem.Function", self.w)] if self.shape_is_unknown else [])
                + ([self.p] if self.p is not None else []))

    def contributions(self) -> list[tuple[fem.Function, ufl.Form]]:
        """Return the rows: internal work minus loads (u), volumetric (p), auxiliary (w)."""
        R = self.internal_work()
        for load in self._loads:
            R = R - load
        out = [(self.u, R)]
        if self.p is not None:
            out.append((self.p, self._mixed()[1]))
        if self.shape_is_unknown:
            mu_a, lmbda_a = (fem.Constant(self.mesh, c) for c in self._aux)
            assert self.w is not None   # a shape unknown is a Function
            out.append((self.w, ale.aux_elasticity(self.w, ufl.TestFunction(self.Vw), mu_a,
                                                   lmbda_a, self.dx)))
        return out

    def reaction(self, name: str, component: int) -> float:
        """Reaction force of the supports on boundary ``name`` (units and parts as below).

        The body's own rows (internal work minus its loads) tested with the unit
        field of ``component`` on the dofs of ``name``: at a solved state the
        force the support exerts on the body, from the solid alone — an
        equilibrium check independent of any interface's force measure.  N/mm
        per unit thickness in plane strain; N in 3D, on the modelled part (a
        quarter model: a quarter of the full body's); axisymmetric: the revolved
        body's, N (the weight 2πR).
        """
        fdim = self.mesh.topology.dim - 1
        Vc = self.V.sub(component)
        w = fem.Function(self.V)
        dofs = fem.locate_dofs_topological(Vc, fdim, self.facets(name))
        w.x.array[dofs] = 1.0
        w.x.scatter_forward()
        R = ufl.replace(self.contributions()[0][1], {self.v: w})
        # on a held dof nothing else acts: internal work = loads + support force
        return self.mesh.comm.allreduce(fem.assemble_scalar(fem.form(R)), op=MPI.SUM)

    def bcs(self) -> list[fem.DirichletBC]:
        """Dirichlet conditions of u (and w)."""
        return self._bcs + self._w_bcs

    def bcs_by_unknown(self) -> dict[fem.Function, list[fem.DirichletBC]]:
        """Dirichlet conditions sorted by unknown."""
        out = {self.u: list(self._bcs)}
        if self.shape_is_unknown:
            assert self.w is not None
            out[self.w] = list(self._w_bcs)
        if self.p is not None:
            out[self.p] = []
        return out

    def entity_maps(self) -> list[dmesh.EntityMap]:
        """Return no entity maps: a body's forms live on its own mesh."""
        return []

    def refresh(self) -> None:
        """Nothing computed outside UFL."""

    def tolerances(self) -> dict[fem.Function, BlockTolerance]:
        """Momentum rows: nodal force ≤ rtol·(force scale) (N; N/mm in plane strain).

        The force scale is ``force_scale`` or G·L^{d−1}, G the body's shear modulus
        and L the diameter of its bounding box: the force that strains the whole
        body by 1.  The shape rows (auxiliary elasticity, fictitious modulus E_a)
        use rtol·E_a·L^{d−1}.
        """
        d = 2 if self.kind in ("3d", "axisymmetric") else 1
        scale = self.force_scale if self.force_scale is not None \
            else self.stiffness * self.length**d
        out = {self.u: BlockTolerance(self.rtol * scale, "N" if d == 2 else "N/mm")}
        if self.shape_is_unknown:
            assert self.w is not None
            out[self.w] = BlockTolerance(self.rtol * self._aux[0] * self.length**d, "aux")
        if self.p is not None:
            # volumetric rows ∫ (g − p/K) δp dV: rtol of the body's volume (strain × volume)
            out[self.p] = BlockTolerance(self.rtol * self.length ** (d + 1),
                                         "mm³" if d == 2 else "mm²")
        return out

    def state_fields(self) -> list[fem.Function]:
        """Return u (and w, w_n)."""
        return self.unknowns() + ([cast("fem.Function", self.w_n)] if self.shape_is_unknown
                                  else [])

    def commit(self) -> None:
        """Nothing to move on for the bulk."""
