"""Quasi-steady wear groove of a rigid ball sliding on an elastic half-space (chapter §5.3).

Design
------
The 3D block (``meshes/halfspace.py``) is a structured extrusion along the
sliding direction x of a 2D cross-section mesh in (y, z), so every 3D vertex
sits over a cross-section vertex.  Unknowns (all on initial meshes, DESIGN.md
"Working on the initial mesh"):

* u   — displacement of the 3D block from its initial configuration (Q1 hexahedra);
* λ   — normal contact multiplier on the top surface (nodal, vertex rule);
* w₂  — the shape change Ψ on the cross-section, (w_y, w_z)(y, z) (Q1 quads);
* ζ   — multiplier of the shape update (28) on the top line of the cross-section.

The 3D shape field is w₃ = P w₂ (w_x = 0), P the extrusion (prolongation)
matrix, so Ψ is uniform along x by construction and its unknowns are a small
fraction of all unknowns.  Residuals:

* deformation on the worn body (forms/ale): ∫ P(F):(Grad δu G⁻¹) det G dV̂
  + G_c(u, λ) − ∫_bottom T*·δu dŜ, F = (I + Grad u) G⁻¹, G = I + Grad w₃, the
  ball a rigid sphere in the Eulerian frame attached to it (§4.3), the block
  pushed against it by the dead bottom traction T* = (F/2)/A_bottom e_z (half
  model, symmetry y = 0; rollers on x = ±L_x and y = L_y);
* auxiliary plane elasticity for w₂ on the cross-section with the lumped
  shape update (28) on its top line, driven by the path-averaged rate
  (forms/wear_groove): ∫ η (w₂ − w₂ₙ)·a dŝ + Δt (1/L) (Pᵀ r)_η = 0,
  r_i = ∫_Γ̂c Ẇ j_w φ_i dŜ the 3D nodal wear rate, Ẇ j_w = k |T_N| ‖v_T‖ (eq. 14,
  v = F V, eqs. 26–27), a the mid-step Nanson vector of the line (exact swept
  area, so the groove area balance is discrete-exact); zero normal motion
  elsewhere (w_y = 0 on y = 0, L_y; w = 0 at the bottom).

Jacobian: every block is the exact UFL derivative; the couplings through the
extrusion are assembled as J_{u w₂} = J_{u w₃} P and J_{ζ ·} = (Δt/L) Pᵀ J_{r ·}
(J_{ζ w₂} also gets Pᵀ J_{r w₃} P through the graded wear coefficient and the
graded modulus, which depend on the worn depth).  The blocks are assembled by
DOLFINx as PETSc matrices, multiplied by P (PETSc MatMatMult), nested,
merged into one (MPI)AIJ matrix and factorised by MUMPS.

Parallel layout: the 3D block is distributed by DOLFINx; the cross-section
mesh is replicated on every rank (``COMM_SELF``), so w₂, ζ and their forms are
identical everywhere and w₃ = P w₂ is a local copy on every rank (ghosts
included).  In the global system the few cross-section unknowns (≈ 2 % of all)
are owned by rank 0 (local size n₂ there, 0 elsewhere); P is an MPIAIJ matrix
(rows: owned 3D dofs, columns: global cross-section dofs) and Pᵀ r is summed
over the ranks.  The monolithic row layout on each rank is [u, λ] owned
(+ [w₂, ζ] on rank 0); the Newton update of w₂, ζ is broadcast from rank 0.

Schemes: ``implicit`` (θ = 1) — one monolithic Newton on (u, λ, w₂, ζ);
``explicit`` (θ = 0) — shape update (w₂, ζ) with the rate of the converged
state, then the contact problem (u, λ) on the new shape.  Units: mm, N, s, MPa.
"""

import dolfinx.fem.petsc as fem_petsc
import numpy as np
import ufl
from dolfinx import fem, la
from mpi4py import MPI
from petsc4py import PETSc
from ufl.algorithms import expand_derivatives

from .contact_problem import ContactProblem, ContactSettings
from .forms import ale
from .forms import contact as cf
from .forms import hyperelastic as hf
from .forms import wear as wf
from .forms import wear_groove as gf
from .meshes import halfspace as hs
from .newton import NewtonDivergence, NewtonReport
from .obstacles import AnalyticObstacle
from .params import InputError
from .submesh import facet_submesh
from .stepper import MeshInversion

__all__ = ["GrooveProblem"]

BLOCKS = ("u", "l", "w", "z")


def _nonzero(a):
    a = expand_derivatives(a)
    return None if a.empty() else a


class _Extrusion:
    """The 0/1 extrusion matrix P (one unit entry per row): index arrays and PETSc (MPI)AIJ.

    ``rows`` are local 3D dofs (owned and ghost), ``cols`` cross-section dofs
    (replicated numbering); ``n_own``/``start``/``n_glob`` the owned rows, the
    global index of the first and the global number of 3D dofs.  The PETSc
    matrix holds the owned rows; its columns are owned by rank 0.
    """

    def __init__(self, rows, cols, shape, comm, n_own, start, n_glob):
        self.rows, self.cols, self.shape, self.comm = rows, cols, shape, comm
        own = rows < n_own
        self.rows_own, self.cols_own = rows[own], cols[own]
        indptr = np.zeros(n_own + 1, dtype=PETSc.IntType)
        np.add.at(indptr, self.rows_own + 1, 1)
        indptr = np.cumsum(indptr).astype(PETSc.IntType)
        order = np.argsort(self.rows_own, kind="stable")
        n2 = shape[1]
        self.mat = PETSc.Mat().createAIJ(
            size=((n_own, n_glob), (n2 if comm.rank == 0 else 0, n2)),
            csr=(indptr, self.cols_own[order].astype(PETSc.IntType),
                 np.ones(len(self.rows_own))), comm=comm)
        self.mat.assemble()

    def apply(self, v2):
        """P v₂ on the local 3D dofs (owned and ghost)."""
        out = np.zeros(self.shape[0])
        out[self.rows] = v2[self.cols]
        return out

    def transpose(self, v3):
        """Pᵀ v₃ (sum over the x layers of the owned entries, summed over the ranks)."""
        loc = np.bincount(self.cols_own, weights=v3[self.rows_own], minlength=self.shape[1])
        return self.comm.allreduce(loc, op=MPI.SUM) if self.comm.size > 1 else loc

    def average(self, rate3, L):
        """(1/L) Pᵀ r: the path average of :func:`forms.wear_groove.path_averaged_rate`."""
        return gf.path_averaged_rate(self, rate3, L)

    @property
    def T(self):  # noqa: N802 - matrix-like transpose for path_averaged_rate
        return _Transposed(self)


class _Transposed:
    def __init__(self, P):
        self.P = P

    def __matmul__(self, v):
        return self.P.transpose(v)


class GrooveProblem(ContactProblem):
    """Rigid ball on an extruded half-space block with a cross-section wear groove.

    Args:
        msh, ft: 3D block and its facet tags (``meshes.halfspace``).
        sec, sec_ft: cross-section mesh (y, z) and its facet tags.
        E, nu: substrate Young's modulus (MPa) and Poisson ratio.
        R: ball radius (mm); F: normal load on the full ball (N; the model carries F/2).
        V: sliding speed (mm/s); L: sliding length per cycle (mm); k: Archard
            coefficient of the substrate (mm³/(N·mm)).
        h: element size at the contact (sets ρ_N = E/h).
        scheme: "implicit" or "explicit".
        material: strain energy (``forms.hyperelastic``), default neo-Hookean.
        graded: (α, h_L) of the FGM layer (Fig. 10b), E and k × (1 + α max(1 − d/h_L, 0));
            None: homogeneous.
        law: "nominal" (eq. 14) or "spatial" (eqs. 15–16).
    """

    def __init__(self, msh, ft, sec, sec_ft, E, nu, R, F, V, L, k, h, scheme="implicit",
                 material="neo-hookean", graded=None, law="nominal", quadrature_degree=2):
        if sec.comm.size > 1:
            raise InputError("wear-ball-halfspace: the cross-section mesh must be replicated "
                             "(created on COMM_SELF)")
        if scheme not in ("implicit", "explicit"):
            raise ValueError(f"unknown scheme {scheme!r}")
        mu, lmbda = hf.lame_parameters(E, nu)

        def factory(m, Vs):
            return AnalyticObstacle(Vs.mesh, "sphere", np.array([0.0, 0.0, R]), radius=R)

        super().__init__(msh, ft, hs.TOP, "3d", material, {"mu": mu, "lmbda": lmbda}, factory,
                         ContactSettings(rho_n=E / h), quadrature_degree=quadrature_degree)
        self.scheme, self.R, self.F, self.L, self.speed = scheme, R, F, L, V
        self.E = E
        self.dt = 0.0
        # -- 3D deformation on the worn configuration -----------------------
        self.w3 = fem.Function(self.V, name="shape_change_3d")
        X3 = ufl.SpatialCoordinate(msh)
        depth = gf.material_depth(X3, self.w3)
        alpha, thick = graded if graded else (0.0, 1.0)
        fg = gf.graded_factor(depth, alpha, thick) if graded else 1.0
        params = {"mu": mu * fg, "lmbda": lmbda * fg}
        v = self._v
        R_uc, R_n, _ = cf.augmented_lagrangian_contact(
            self.u, v, self.geometry, self.lam_n, ufl.TestFunction(self.Q), E / h, self.dsc)
        xmin, xmax = msh.comm.allreduce(msh.geometry.x[:, 0].min(), MPI.MIN), \
            msh.comm.allreduce(msh.geometry.x[:, 0].max(), MPI.MAX)
        ymax = msh.comm.allreduce(msh.geometry.x[:, 1].max(), MPI.MAX)
        q = 0.5 * F / ((xmax - xmin) * ymax)
        self.bottom_traction = q
        self._xlen = xmax - xmin
        R_ext = hf.external_virtual_work(ufl.as_vector([0.0, 0.0, q]), v, "3d", self.ds(hs.BOTTOM))
        self.R_u = ale.internal_virtual_work_worn(self.u, self.w3, v, "3d", material, params,
                                                  self.dx) + R_uc - R_ext
        self.R_n = R_n
        # wear rate (eq. 14, pressure form, Eulerian slip speed eqs. 26-27), per unit initial area
        t_n, _ = cf.contact_tractions(self.geometry, self.lam_n, E / h)
        slip = gf.groove_slip_speed(self.u, self.geometry, ufl.as_vector([-V, 0.0, 0.0]))
        kk = k * (gf.graded_factor(depth, alpha, thick) if graded else 1.0)
        J = ufl.det(ale.deformation_gradient_worn(self.u, self.w3, "3d")) \
            if law == "spatial" else None
        self.rate_density = gf.groove_rate_density(kk, t_n, slip, J)
        rate_form = self.rate_density * ufl.TestFunction(self.Q) * self.dsc
        # -- cross-section shape problem -------------------------------------
        self.sec, self.sec_ft = sec, sec_ft
        self.line, self.emap2, _ = facet_submesh(sec, sec_ft, hs.TOP, "groove line")
        self.V2 = fem.functionspace(sec, ("Lagrange", 1, (2,)))
        self.Q2 = fem.functionspace(self.line, ("Lagrange", 1))
        self.w2 = fem.Function(self.V2, name="shape_change")
        self.w2n = fem.Function(self.V2, name="shape_change_old")
        self.zeta = fem.Function(self.Q2, name="shape_multiplier")
        dsl = ufl.Measure("ds", sec, subdomain_data=sec_ft, subdomain_id=hs.TOP,
                          metadata={"quadrature_rule": "vertex", "quadrature_degree": 1})
        dx2 = ufl.Measure("dx", sec)
        a = ale.nanson_vector(0.5 * (self.w2 + self.w2n), ufl.FacetNormal(sec))
        dw, eta = ufl.TestFunction(self.V2), ufl.TestFunction(self.Q2)
        mu_a, lmbda_a = hf.lame_parameters(E, 0.3)
        R_w = (ale.aux_elasticity(self.w2, dw, mu_a, lmbda_a, dx2)
               + self.zeta * ufl.dot(dw, a) * dsl)
        # eq. 28 without its rate term; Δt (1/L) Pᵀ r is added algebraically
        R_z = wf.shape_update_residual(self.w2, self.w2n, a, 0.0, 0.0, eta, dsl)
        # -- extrusion matrices ------------------------------------------------
        X3d = self.V.tabulate_dof_coordinates()
        X2d = self.V2.tabulate_dof_coordinates()[:, :2]
        comm = msh.comm
        self.comm = comm
        imV, bsV, imQ = self.V.dofmap.index_map, self.V.dofmap.index_map_bs, \
            self.Q.dofmap.index_map
        self._nown = {"u": imV.size_local * bsV, "l": imQ.size_local,
                      "w": len(self.w2.x.array), "z": len(self.zeta.x.array)}
        self._start = {"u": imV.local_range[0] * bsV, "l": imQ.local_range[0], "w": 0, "z": 0}
        self._nglob = {"u": imV.size_global * bsV, "l": imQ.size_global,
                       "w": self._nown["w"], "z": self._nown["z"]}
        if comm.rank != 0:  # the cross-section unknowns are owned by rank 0
            self._nown["w"] = self._nown["z"] = 0
        self._layout = comm.allgather((dict(self._nown), dict(self._start)))
        self.Pw = _Extrusion(*hs.prolongation(X3d, X2d, components=[(1, 0), (2, 1)]), comm,
                             self._nown["u"], self._start["u"], self._nglob["u"])
        self.Pc = _Extrusion(*hs.prolongation(self.Q.tabulate_dof_coordinates(),
                                              self.Q2.tabulate_dof_coordinates()[:, :2]), comm,
                             self._nown["l"], self._start["l"], self._nglob["l"])
        # -- compiled forms ------------------------------------------------------
        em3, em2 = {"entity_maps": [self.emap]}, {"entity_maps": [self.emap2]}
        self.fn = {"u": self.u, "l": self.lam_n, "w": self.w2, "z": self.zeta}
        res3 = {"u": self.R_u, "l": self.R_n, "r": rate_form}
        res2 = {"w": R_w, "z": R_z}
        self._F = {key: fem.form(f, **em3) for key, f in res3.items()}
        self._F.update({key: fem.form(f, **em2) for key, f in res2.items()})
        self._J = {}
        for key, f in res3.items():
            for unk, fun in (("u", self.u), ("l", self.lam_n), ("w", self.w3)):
                d = _nonzero(ufl.derivative(f, fun, ufl.TrialFunction(fun.function_space)))
                if d is not None:
                    self._J[key, unk] = fem.form(d, **em3)
        for key, f in res2.items():
            for unk, fun in (("w", self.w2), ("z", self.zeta)):
                d = _nonzero(ufl.derivative(f, fun, ufl.TrialFunction(fun.function_space)))
                if d is not None:
                    self._J[key, unk] = fem.form(d, **em2)
        G2 = ale.shape_gradient(self.w2)
        self._groove_area = fem.form((1 - ufl.det(G2)) * dx2)
        DG0 = fem.functionspace(sec, ("DG", 0))
        self._detG = fem.Function(DG0)
        self._detG_expr = fem.Expression(ufl.det(G2), DG0.element.interpolation_points)
        q3 = ufl.TestFunction(self.Q)
        self._lumped3 = fem.form(q3 * self.dsc, **em3)
        # -- Dirichlet masks ------------------------------------------------------
        tol = 1e-9 * (xmax - xmin)
        bc_u = np.zeros((len(X3d), 3), dtype=bool)
        bc_u[np.abs(np.abs(X3d[:, 0]) - xmax) < tol, 0] = True      # rollers on x = ±L_x
        bc_u[np.abs(X3d[:, 1]) < tol, 1] = True                     # symmetry y = 0
        bc_u[np.abs(X3d[:, 1] - ymax) < tol, 1] = True              # roller y = L_y
        zmin = X2d[:, 1].min()
        bc_w = np.zeros((len(X2d), 2), dtype=bool)
        bc_w[np.abs(X2d[:, 0]) < tol, 0] = True                     # w_y = 0 on y = 0
        bc_w[np.abs(X2d[:, 0] - ymax) < tol, 0] = True              # w_y = 0 on y = L_y
        bc_w[np.abs(X2d[:, 1] - zmin) < tol, :] = True              # w = 0 at the bottom
        self._bc = {"u": bc_u.ravel(), "l": np.zeros(len(self.lam_n.x.array), bool),
                    "w": bc_w.ravel(), "z": np.zeros(len(self.zeta.x.array), bool)}
        self._X_line = self.Q2.tabulate_dof_coordinates()[:, 0]
        self._Xq = self.Q.tabulate_dof_coordinates()
        top2 = np.abs(X2d[:, 1]) < tol
        self._top2 = np.flatnonzero(top2)
        self._rate_fixed = None
        self.rtol, self.atol, self.max_it = 1e-9, 5e-10, 30

    def global_sizes(self):
        """Global numbers of unknowns per block: u, λ (3D), w₂, ζ (cross-section)."""
        return dict(self._nglob)

    # -- assembly --------------------------------------------------------------
    def sync(self):
        """w₃ = P w₂ (the groove is uniform along x); local copy, ghosts included."""
        self.w3.x.array[:] = self.Pw.apply(self.w2.x.array)

    def _vec(self, key):
        """Assembled residual vector: owned part for the 3D blocks, all for the section."""
        vec = fem.assemble_vector(self._F[key])
        if key in ("w", "z"):
            return vec.array.copy()
        vec.scatter_reverse(la.InsertMode.add)
        n = self._nown["u" if key == "u" else "l"]
        return vec.array[:n].copy()

    def _mat(self, key, unk):
        A = fem_petsc.assemble_matrix(self._J[key, unk])
        A.assemble()
        return A

    def _norm(self, r):
        s = float(np.dot(r, r))
        return float(np.sqrt(self.comm.allreduce(s, op=MPI.SUM) if self.comm.size > 1 else s))

    def _offsets(self, blocks):
        """Per rank: offset of its rows in the monolithic vector and of each block in them."""
        sizes = [sum(n[b] for b in blocks) for n, _ in self._layout]
        roff = np.concatenate([[0], np.cumsum(sizes)])
        boff = []
        for n, _ in self._layout:
            o, d = 0, {}
            for b in blocks:
                d[b] = o
                o += n[b]
            boff.append(d)
        return roff, boff

    def _global_index(self, blocks, b, g):
        """Monolithic global index of the block-``b`` global dof indices ``g``."""
        roff, boff = self._offsets(blocks)
        if b in ("w", "z"):
            return roff[0] + boff[0][b] + g
        starts = np.array([s[b] for _, s in self._layout])
        owner = np.searchsorted(starts, g, side="right") - 1
        ob = np.array([bo[b] for bo in boff])
        return roff[owner] + ob[owner] + g - starts[owner]

    def rate_vector(self):
        """Nodal 3D wear rate r_i = ∫_Γ̂c Ẇ j_w φ_i dŜ (mm³/s) at the current state (owned)."""
        self.sync()
        return self._vec("r")

    def _residual(self, blocks):
        self.sync()
        c = self.dt / self.L
        out = []
        for b in blocks:
            if b == "z":
                r = self._vec("z")
                rate = self._vec("r") if self._rate_fixed is None else self._rate_fixed
                r = r + c * self.Pc.average(rate, 1.0)
            else:
                r = self._vec(b)
            r[self._bc[b][:len(r)]] = 0.0
            out.append(r[:self._nown[b]])
        return np.concatenate(out)

    def _jacobian(self, blocks):
        c = self.dt / self.L
        made, parts = [], []  # parts: (row block, column block, matrix, local to rank 0)
        for b in blocks:
            for d in blocks:
                if b in ("u", "l"):
                    if d in ("u", "l") and (b, d) in self._J:
                        parts.append((b, d, self._mat(b, d), False))
                    elif d == "w" and (b, "w") in self._J:
                        J3 = self._mat(b, "w")
                        made.append(J3)
                        # J_{u w2} = J_{u w3} P
                        parts.append((b, d, J3.matMult(self.Pw.mat), False))
                elif b == "w":
                    if d in ("w", "z") and ("w", d) in self._J:
                        parts.append((b, d, self._mat("w", d), True))
                else:  # shape update rows: R_z + (Δt/L) Pᵀ r
                    if d == "w" and ("z", "w") in self._J:
                        parts.append((b, d, self._mat("z", "w"), True))
                    if self._rate_fixed is None and ("r", d) in self._J:
                        Jr = self._mat("r", d)
                        made.append(Jr)
                        if d == "w":
                            Jr = Jr.matMult(self.Pw.mat)
                            made.append(Jr)
                        B = self.Pc.mat.transposeMatMult(Jr)
                        B.scale(c)
                        parts.append((b, d, B, False))
        K = self._stitch(parts, blocks)
        for m in made + [p[2] for p in parts]:
            m.destroy()
        return K

    def _stitch(self, parts, blocks):
        """One (MPI)AIJ matrix from the block parts (COO merge), Dirichlet rows → identity."""
        roff, boff = self._offsets(blocks)
        rank = self.comm.rank
        my0 = roff[rank]
        ri, ci, vals = [], [], []
        for b, d, A, rank0_only in parts:
            if rank0_only and rank != 0:
                continue
            ip, ind, val = A.getValuesCSR()
            nrow = len(ip) - 1
            if nrow == 0:
                continue
            ri.append(my0 + boff[rank][b] + np.repeat(np.arange(nrow), np.diff(ip)))
            ci.append(self._global_index(blocks, d, np.asarray(ind, dtype=np.int64)))
            vals.append(val)
        ri = np.concatenate(ri) if ri else np.zeros(0, np.int64)
        ci = np.concatenate(ci) if ci else np.zeros(0, np.int64)
        vals = np.concatenate(vals) if vals else np.zeros(0)
        bc = np.concatenate([self._bc[b][:self._nown[b]] for b in blocks])
        nloc = len(bc)
        keep = ~bc[ri - my0]
        rbc = my0 + np.flatnonzero(bc)
        ri = np.concatenate([ri[keep], rbc])
        ci = np.concatenate([ci[keep], rbc])
        vals = np.concatenate([vals[keep], np.ones(len(rbc))])
        # sum duplicate entries (the two parts of the ζ–w₂ block), sort by (row, column)
        N = int(roff[-1])
        key, inv = np.unique((ri - my0) * N + ci, return_inverse=True)
        vals = np.bincount(inv.ravel(), weights=vals, minlength=len(key))
        ri, ci = key // N, key % N
        indptr = np.zeros(nloc + 1, dtype=PETSc.IntType)
        np.add.at(indptr, ri + 1, 1)
        indptr = np.cumsum(indptr).astype(PETSc.IntType)
        K = PETSc.Mat().createAIJ(size=((nloc, N), (nloc, N)),
                                  csr=(indptr, ci.astype(PETSc.IntType), vals), comm=self.comm)
        K.assemble()
        return K

    def residual(self, blocks=BLOCKS):
        """Residual of the listed blocks (owned rows; w₂, ζ on rank 0), Dirichlet rows zeroed."""
        return self._residual(blocks)

    def jacobian(self, blocks=BLOCKS):
        """Exact Jacobian (PETSc (MPI)AIJ) of :meth:`residual`, Dirichlet rows → identity."""
        return self._jacobian(blocks)

    def _get(self, blocks):
        return np.concatenate([self.fn[b].x.array[:self._nown[b]] for b in blocks])

    def _set(self, blocks, x):
        i = 0
        for b in blocks:
            n = self._nown[b]
            f = self.fn[b]
            if b in ("w", "z"):
                vals = x[i:i + n] if self.comm.rank == 0 else None
                if self.comm.size > 1:
                    vals = self.comm.bcast(vals, root=0)
                f.x.array[:] = vals
            else:
                f.x.array[:n] = x[i:i + n]
                f.x.scatter_forward()
            i += n
        self.sync()

    def _lu(self, A, rhs):
        comm = self.comm
        ksp = PETSc.KSP().create(comm)
        ksp.setOperators(A)
        ksp.setType("preonly")
        pc = ksp.getPC()
        pc.setType("lu")
        pc.setFactorSolverType("mumps")
        N = A.getSize()[0]
        b = PETSc.Vec().createWithArray(rhs, size=(len(rhs), N), comm=comm)
        x = b.duplicate()
        ksp.solve(b, x)
        ok = ksp.getConvergedReason() >= 0
        out = x.array.copy()
        for o in (ksp, A, x, b):
            o.destroy()
        ok = bool(ok and np.all(np.isfinite(out)))
        if comm.size > 1:
            ok = comm.allreduce(ok, op=MPI.LAND)
        return out if ok else None

    def newton(self, blocks, verbose=False):
        """Semismooth Newton on the listed blocks (others frozen); returns a NewtonReport."""
        x0 = self._get(blocks)
        rep = NewtonReport()
        r0 = None
        x = x0.copy()
        verbose = verbose and self.comm.rank == 0
        for it in range(self.max_it + 1):
            R = self._residual(blocks)
            r = self._norm(R)
            rep.residuals.append(r)
            if verbose:
                print(f"  newton {it:2d} [{''.join(blocks)}]: |R| = {r:.3e}")
            if not np.isfinite(r):
                break
            r0 = r if r0 is None else r0
            if (it > 0 and r <= max(self.rtol * r0, self.atol)) or r <= 1e-3 * self.atol:
                rep.iterations = it
                return rep
            if it == self.max_it:
                break
            dx = self._lu(self._jacobian(blocks), R)
            if dx is None:
                break
            rep.increments.append(self._norm(dx))
            alpha = 1.0
            for _ in range(7):  # backtracking (Armijo) against active-set cycling
                self._set(blocks, x - alpha * dx)
                if self._norm(self._residual(blocks)) < (1 - 1e-4 * alpha) * r:
                    break
                alpha *= 0.5
            else:
                alpha = 1.0
                self._set(blocks, x - dx)
            x = x - alpha * dx
        self._set(blocks, x0)
        raise NewtonDivergence(f"Newton did not converge (residuals "
                               f"{['%.2e' % v for v in rep.residuals]})")

    # -- state -----------------------------------------------------------------
    def _all(self):
        return [self.u, self.lam_n, self.w2, self.w2n, self.zeta]

    def state(self):
        """Copy of all unknowns and the shape history."""
        return [f.x.array.copy() for f in self._all()]

    def restore(self, state):
        """Restore a state from :meth:`state`."""
        for f, a in zip(self._all(), state):
            f.x.array[:] = a
        self.sync()

    def solve_contact(self, verbose=False):
        """Contact problem (u, λ) on the current worn shape; returns the NewtonReport."""
        self.dt = 0.0
        return self.newton(("u", "l"), verbose)

    def min_volume_factor(self):
        """Smallest det(I + Grad w₂) over the cross-section cells (≤ 0: inverted)."""
        self._detG.interpolate(self._detG_expr)
        return float(np.min(self._detG.x.array))

    def step(self, dt, verbose=False):
        """Advance the groove by Δt (s); returns the list of Newton reports.

        On failure the entry state is restored and NewtonDivergence (or
        MeshInversion) is raised.
        """
        saved = self.state()
        self.w2n.x.array[:] = self.w2.x.array
        try:
            if self.scheme == "implicit":
                self.dt = dt
                reports = [self.newton(BLOCKS, verbose)]
            else:
                self._rate_fixed = self.rate_vector()  # θ = 0: rate of the converged state
                self.dt = dt
                reports = [self.newton(("w", "z"), verbose)]
                self._rate_fixed = None
                if self.min_volume_factor() <= 0:
                    raise MeshInversion("shape update inverts the cross-section mesh")
                reports.append(self.solve_contact(verbose))
            if self.min_volume_factor() <= 0:
                raise MeshInversion("shape update inverts the cross-section mesh")
        except NewtonDivergence:
            self._rate_fixed = None
            self.restore(saved)
            raise
        finally:
            self.dt = 0.0
        return reports

    # -- post-processing -------------------------------------------------------
    def groove_area(self):
        """Worn cross-section area of the modelled half y ≥ 0, ∫ (1 − det G₂) dÂ (mm²)."""
        return float(fem.assemble_scalar(self._groove_area))

    def averaged_rate_integral(self):
        """(1/L) ∫_Γ̂c Ẇ j_w dŜ: growth rate of the half groove area (mm²/s) at the current state."""
        s = float(np.sum(self.rate_vector()))
        return (self.comm.allreduce(s, op=MPI.SUM) if self.comm.size > 1 else s) / self.L

    def line_profile(self):
        """Top line of the cross-section: initial Ŷ, worn (Y, Z) and depth −w_z, sorted by Ŷ."""
        X2 = self.V2.tabulate_dof_coordinates()[self._top2, :2]
        w = self.w2.x.array.reshape(-1, 2)[self._top2]
        o = np.argsort(X2[:, 0])
        return {"Y_hat": X2[o, 0], "worn": (X2 + w)[o], "depth": -w[o, 1]}

    def _surface_owned(self):
        n = self._nown["l"]
        vec = fem.assemble_vector(self._lumped3)
        vec.scatter_reverse(la.InsertMode.add)
        lam = self.lam_n.x.array[:n]
        return {"X": self._Xq[:n, :2].copy(), "p": np.maximum(-lam, 0.0),
                "weight": vec.array[:n].copy(), "active": lam < 0}

    def surface_data(self):
        """Top-surface nodes: initial (x, y), nominal pressure p = −λ, lumped weight, active.

        In parallel the owned nodes of all ranks, sorted by (x, y), on every rank.
        """
        d = self._surface_owned()
        if self.comm.size == 1:
            return d
        parts = self.comm.allgather(d)
        d = {k: np.concatenate([p[k] for p in parts]) for k in d}
        o = np.lexsort((d["X"][:, 1], d["X"][:, 0]))
        return {k: a[o] for k, a in d.items()}

    def contact_extent(self):
        """Half-length along x and half-width along y of the contact (last active node), mm."""
        d = self.surface_data()
        X = d["X"][d["active"]]
        if len(X) == 0:
            return 0.0, 0.0
        return float(np.abs(X[:, 0]).max()), float(X[:, 1].max())

    def contact_force(self):
        """Σ |λ_i| weight_i: normal contact force on the modelled half (N).

        Equals the vertical force F/2 when the contact normals are nearly vertical
        (small-deformation regime); at finite deformation it exceeds it by the
        tilt of the ball normal.
        """
        d = self._surface_owned()
        s = float(np.sum(d["p"] * d["weight"]))
        return self.comm.allreduce(s, op=MPI.SUM) if self.comm.size > 1 else s

    def averaged_pressure(self):
        """Pressure integrated along the sliding path, ∫ p dx (N/mm), per line node.

        Lumped: (Pᵀ(p_i w_i))_j / ∫ φ_j dy.  Returns (y, ∫ p dx) sorted by y.
        """
        d = self._surface_owned()
        # ∫ p φ_j dx dy divided by the line weight ∫ φ_j dy = ∫ p dx (lumped)
        num = self.Pc.transpose(d["p"] * d["weight"])
        den = self.Pc.transpose(d["weight"])
        line_w = den / self._xlen  # ∫ φ_j dy = ∫∫ φ_j dx dy / (2 L_x)
        o = np.argsort(self._X_line)
        return self._X_line[o], (num / line_w)[o]
