"""Linear-solver strategies (:mod:`tribofx.solvers`): the iterative fieldsplit gives the
direct answer to solver tolerance, the direct one reuses its symbolic analysis.

Tolerance of "same answer": both runs stop their Newton iterations by the same
per-block test, and Newton converges quadratically (shown in test_taylor and
test_hertz), so the error of a converged iterate is below its last correction
|Δx_last| (e_{k+1} = O(e_k²) ≪ e_k ≈ |Δx_k|).  Two runs of the same problem then
differ by at most the sum of their last corrections; GMRES adds its relative
residual 1e-10 of a correction, far below that.  A floor of 1e-12 of the field's
size covers round-off when both last corrections are at round-off themselves.
"""

import numpy as np
import pytest
import ufl
from dolfinx import fem, mesh
from mpi4py import MPI
from petsc4py import PETSc

from tribofx import solvers
from tribofx.cases import hertz as hertz_case
from tribofx.cases import wear_ball_halfspace
from tribofx.cases.wear_ball_halfspace import groove_mesh
from tribofx.continuation import ConstantParameter
from tribofx.near_nullspace import rigid_body_modes
from tribofx.params import resolve
from tribofx.references import hertz
from tribofx.reports import NewtonDivergence
from tribofx.runner import run_case


def _max(comm, a):
    return comm.allreduce(float(np.max(np.abs(a), initial=0.0)), op=MPI.MAX)


def _last_correction(report, name):
    return report.increments[-1][report.names.index(name)] if report.increments else 0.0


def _hertz_steps(strategy, offsets, friction=0.3, options=None):
    """3D Hertz with friction at prescribed approaches δ (mm): states and reports per step."""
    v = resolve(hertz_case.Params, {"dim": "3", "mesh": "1", "friction": str(friction)})
    hertz_case.validate(v)
    with solvers.run_settings(strategy, options):
        model = hertz_case.build(v)
        body, contact, problem = model.body, model.contact, model.problem
    delta = ConstantParameter(contact.counterpart.offset, 2)
    out = []
    for d in offsets:
        delta.set(d)
        rep = problem.solve()
        problem.commit()
        n_active = contact.body.mesh.comm.allreduce(
            int(np.sum(contact.nodal_data()["active"])), op=MPI.SUM)
        out.append({"u": body.u.x.array.copy(), "lam": contact.lam_n.x.array.copy(),
                    "report": rep, "active": n_active})
    return problem, body, contact, out


@pytest.mark.mpi
def test_iterative_matches_direct_through_active_set_changes():
    """Frictional 3D Hertz loaded in three approach steps: the contact zone grows
    (active set changes in every step, stick and slip nodes), fieldsplit = LU."""
    v = resolve(hertz_case.Params, {"dim": "3"})
    hertz_case.validate(v)
    a, _ = hertz(v.load, v.R, v.E, v.nu)[:2]
    offsets = [0.3 * a**2 / v.R, 0.6 * a**2 / v.R, a**2 / v.R]
    pd, bd, cd, direct = _hertz_steps("direct", offsets)
    pi, bi, ci, iterative = _hertz_steps("iterative", offsets)
    assert pd.solver.name == "direct" and pi.solver.name == "iterative"
    assert pi.snes.getKSP().getPC().getType() == "fieldsplit"
    comm = bd.mesh.comm
    actives = [s["active"] for s in direct]
    assert actives[0] < actives[1] < actives[2], actives   # the test exercises changes
    for sd, si in zip(direct, iterative):
        assert si["active"] == sd["active"]
        for key, name in (("u", "displacement"), ("lam", "contact_pressure_nominal")):
            tol = (_last_correction(sd["report"], name) + _last_correction(si["report"], name)
                   + 1e-12 * _max(comm, sd[key]))
            diff = _max(comm, si[key] - sd[key])
            print(f"{key}: |iterative - direct| = {diff:.2e} <= {tol:.2e}")
            assert diff <= tol
        # more than one Krylov iteration per Newton step: really iterative
        assert si["report"].linear_iterations > si["report"].iterations


@pytest.mark.mpi
def test_iterative_and_lagged_groove_reduced_problem():
    """The monolithic wear step of §5.3 (ReducedProblem: displacement, multipliers, the
    replicated cross-section shape Ψ and its multipliers ζ): the unworn contact and one
    implicit step.  The fieldsplit (Ψ and ζ in the Schur field) and the lagged LU equal
    LU; the lagged LU factorises less often than Newton iterates, and its Newton
    iterations are those of LU (the same exact Newton, GMRES to 1e-10)."""
    case = wear_ball_halfspace
    v = case.resolved(resolve(case.Params, {}))
    a = hertz(v.F, v.R, v.E, v.nu).a
    h = 0.9 * a
    comm = MPI.COMM_WORLD
    states = {}
    for strategy in ("direct", "iterative", "lagged"):
        with solvers.run_settings(strategy):
            stepper, info = case.build(v, comm, h=h,
                                       mesh=groove_mesh(comm, a, h, 1.8, (3, 3, 4)))
        reps = [case.initial_contact(stepper, info)] + stepper.step(50.0).reports
        wear = stepper.wear
        states[strategy] = (wear.body.u.x.array.copy(), wear.w2.x.array.copy(), reps[-1],
                            stepper.problem, [r.iterations for r in reps])
        assert stepper.problem.solver.name == strategy
    ud, wd, rd, _, itd = states["direct"]
    for strategy in ("iterative", "lagged"):
        ui, wi, ri, pi, its = states[strategy]
        tol_u = (_last_correction(rd, "displacement") + _last_correction(ri, "displacement")
                 + 1e-12 * _max(comm, ud))
        tol_w = (_last_correction(rd, "shape_change") + _last_correction(ri, "shape_change")
                 + 1e-12 * _max(comm, wd))
        du, dw = _max(comm, ui - ud), _max(comm, wi - wd)
        print(f"{strategy}: |du| = {du:.2e} <= {tol_u:.2e}, |dw| = {dw:.2e} <= {tol_w:.2e}, "
              f"Newton {its} (direct {itd})")
        assert du <= tol_u and dw <= tol_w
    pi = states["iterative"][3]
    assert [pi.u[k].name for k in solvers.bulk_fields(pi)[0]] == ["displacement"]
    # the first implicit system has its right-hand side in the shape-multiplier rows
    # alone (2.9e-5 mm), where rtol 1e-10 lies below the round-off of the displacement
    # rows: GMRES stops on the Newton test's floor (krylov_guard), not by an LU fallback
    assert not pi.solver.guard.fallbacks and not states["lagged"][3].solver.guard.fallbacks
    pl, itl = states["lagged"][3:]
    assert itl == itd
    print(f"lagged: {pl.solver.factorisations} factorisations for {sum(itl)} Newton iterations")
    assert 1 <= pl.solver.factorisations < sum(itl)
    assert pl.snes.getKSP().getType() == "gmres"
    # the factor MUMPS made is the compressed one: BLR factors (ICNTL(35)) at the
    # dropping tolerance CNTL(7) and BLR contribution blocks (ICNTL(37)), set under
    # the problem's options prefix
    F = pl.snes.getKSP().getPC().getFactorMatrix()
    assert F.getMumpsIcntl(35) == 1 and F.getMumpsIcntl(37) == 1
    assert F.getMumpsCntl(7) == pl.solver.blr


@pytest.mark.mpi
def test_krylov_floor_is_the_newton_test():
    """GMRES stops before rtol only when its true residual is below η of the Newton
    stopping test in every row (krylov_guard): checked on the true residual b − A x of
    each solve of the groove's implicit step, rebuilt here from the KSP's operator."""
    case = wear_ball_halfspace
    v = case.resolved(resolve(case.Params, {}))
    a = hertz(v.F, v.R, v.E, v.nu).a
    comm = MPI.COMM_WORLD
    with solvers.run_settings("iterative"):
        stepper, info = case.build(v, comm, h=0.9 * a,
                                   mesh=groove_mesh(comm, a, 0.9 * a, 1.8, (3, 3, 4)))
    p = stepper.problem
    ksp = p.snes.getKSP()
    seen = []

    def check(ksp, b, x):
        if ksp.getConvergedReason() != PETSc.KSP.ConvergedReason.CONVERGED_ATOL:
            return
        A = ksp.getOperators()[0]
        r = b.duplicate()
        A.mult(x, r)
        r.aypx(-1.0, b)
        rows = p.solver.guard.bound(p)[0]
        excess = float(np.max(np.abs(r.getArray(readonly=True)) / rows))
        seen.append(comm.allreduce(excess, op=MPI.MAX))

    ksp.setPostSolve(check)    # replaces the guard's fallback: every solve must converge
    case.initial_contact(stepper, info)
    stepper.step(50.0)
    print(f"floor stops: max |r_k| / (η atol_i w_k) = {seen}")
    assert seen and max(seen) <= 1.0


def test_failed_krylov_solve_falls_back_to_lu(tmp_path):
    """GMRES capped at 2 iterations fails in every Newton iteration: each system is
    solved by LU instead, and after two failures the problem's KSP becomes that LU for
    good (the second event says so), so Newton takes the direct path's iterations
    and reaches its solution; the events are in the report and in summary.json, and with
    the fallback made to fail too, the error names the Krylov reason and its iteration
    count."""
    v = resolve(hertz_case.Params, {"dim": "3"})
    hertz_case.validate(v)
    a = hertz(v.load, v.R, v.E, v.nu)[0]
    offsets = [0.5 * a**2 / v.R, a**2 / v.R]
    pd, bd, _, direct = _hertz_steps("direct", offsets)
    pi, bi, _, fell = _hertz_steps("iterative", offsets, options={"ksp_max_it": 2})
    comm = bd.mesh.comm
    events = [e for si in fell for e in si["report"].linear_fallbacks]
    assert len(events) == 2 and "switched" in events[1] and "switched" not in events[0]
    assert all(e["reason"] == "DIVERGED_MAX_IT" and e["iterations"] == 2 for e in events)
    for sd, si in zip(direct, fell):
        assert si["report"].iterations == sd["report"].iterations
        tol = (_last_correction(sd["report"], "displacement")
               + _last_correction(si["report"], "displacement") + 1e-12 * _max(comm, sd["u"]))
        assert _max(comm, si["u"] - sd["u"]) <= tol
    summary = run_case("hertz", {"dim": "2", "mesh": "0", "solver": "iterative"},
                       tmp_path / "r", comm=comm, progress=False,
                       petsc_options={"ksp_max_it": "2"})
    assert summary["status"] == "ok"
    events = [e for v in summary["linear_fallbacks"].values() for e in v]
    assert events and all(e["direct"] == "converged" for e in events)
    # the fallback itself fails (an unpreconditioned GMRES of 1 iteration): Newton stops
    # and its message names both
    options = {"ksp_max_it": 2, "fallback_ksp_type": "gmres", "fallback_pc_type": "none",
               "fallback_ksp_max_it": 1}
    with pytest.raises(NewtonDivergence, match="DIVERGED_MAX_IT after 2 iterations, "
                                                "LU fallback failed"):
        _hertz_steps("iterative", offsets[:1], options=options)


@pytest.mark.mpi
def test_direct_reuses_symbolic_factorisation():
    """MUMPS analyses the pattern once; every Newton iteration of every load step
    after it refactorises numerically only (PETSc event counts)."""
    PETSc.Log.begin()
    sym, num = PETSc.Log.Event("MatLUFactorSym"), PETSc.Log.Event("MatLUFactorNum")
    before = sym.getPerfInfo()["count"], num.getPerfInfo()["count"]
    v = resolve(hertz_case.Params, {"dim": "3"})
    hertz_case.validate(v)
    a, _ = hertz(v.load, v.R, v.E, v.nu)[:2]
    problem, _, _, steps = _hertz_steps("direct", [0.5 * a**2 / v.R, a**2 / v.R])
    newton = sum(s["report"].iterations for s in steps)
    n_sym = sym.getPerfInfo()["count"] - before[0]
    n_num = num.getPerfInfo()["count"] - before[1]
    print(f"{newton} Newton iterations: {n_sym} symbolic, {n_num} numeric factorisations")
    assert newton > 2
    assert n_sym == 1 and n_num == newton


def test_rigid_body_modes_are_the_kernel_of_elasticity():
    """K r = 0 for the 3 (2D) or 6 (3D) modes, K assembled by UFL without conditions."""
    comm = MPI.COMM_WORLD
    for msh in (mesh.create_unit_square(comm, 4, 5), mesh.create_unit_cube(comm, 3, 2, 4)):
        d = msh.geometry.dim
        V = fem.functionspace(msh, ("Lagrange", 1, (d,)))
        u, w = ufl.TrialFunction(V), ufl.TestFunction(V)
        eps = ufl.sym(ufl.grad(u))
        a = fem.form(ufl.inner(2 * eps + ufl.tr(eps) * ufl.Identity(d), ufl.grad(w)) * ufl.dx)
        import dolfinx.fem.petsc as fp

        K = fp.assemble_matrix(a)
        K.assemble()
        modes = rigid_body_modes(V)
        assert modes.shape[0] == (3 if d == 2 else 6)
        for m in modes:
            r = K.createVecRight()
            r.setArray(m)
            y = K.createVecLeft()
            K.mult(r, y)
            # round-off: entries of K ~ 1, |r| ~ 1, 30 terms per row
            assert y.norm(PETSc.NormType.INFINITY) <= 1e-12 * K.norm(PETSc.NormType.INFINITY)
            assert r.norm() > 0.1


def test_bulk_and_interface_fields():
    """Displacements are the AMG field; facet and replicated unknowns go to the Schur field."""
    v = resolve(hertz_case.Params, {"dim": "3", "mesh": "0", "friction": "0.3"})
    hertz_case.validate(v)
    with solvers.run_settings("auto"):
        problem = hertz_case.build(v).problem
    bulk, rest = solvers.bulk_fields(problem)
    assert [problem.u[k].name for k in bulk] == ["displacement"]
    assert [problem.u[k].name for k in rest] == ["contact_pressure_nominal",
                                                 "friction_traction_nominal"]
    # auto: a small 3D problem is solved directly
    assert problem.solver.name == "direct"
    with pytest.raises(ValueError):
        with solvers.run_settings("magic"):
            pass


@pytest.mark.parametrize("cell,expected", [("tetrahedron", "iterative"),
                                           ("hexahedron", "lagged")])
def test_auto_above_threshold(monkeypatch, cell, expected):
    """``auto`` above the size threshold: AMG on tetrahedra, the lagged LU on hexahedra
    (where GAMG's iterations double per refinement); a block clamped at x = 0."""
    from tribofx.forms.hyperelastic import lame_parameters

    from tribofx.body import Body
    from tribofx.problem import Problem

    msh = mesh.create_box(MPI.COMM_WORLD, [np.zeros(3), np.ones(3)], [3, 2, 2],
                          getattr(mesh.CellType, cell))
    left = mesh.locate_entities_boundary(msh, 2, lambda x: np.isclose(x[0], 0.0))
    ft = mesh.meshtags(msh, 2, np.sort(left).astype(np.int32), np.ones(len(left), np.int32))
    mu, lmbda = lame_parameters(1.0, 0.3)
    body = Body(msh, ft, {"left": 1}, "3d", ("neo-hookean", {"mu": mu, "lmbda": lmbda}))
    body.add_dirichlet("left", np.zeros(3))
    monkeypatch.setattr(solvers, "AUTO_THRESHOLD", 10)
    with solvers.run_settings("auto"):
        problem = Problem([body], name=f"auto_{cell}")
    assert problem.solver.name == expected


@pytest.mark.mpi
def test_iterative_single_field_is_amg():
    """A body alone (no interface unknowns): GMRES + GAMG on the whole matrix, equal to LU.

    A neo-Hookean block clamped at x = 0 and pulled by a dead traction at x = 1
    (finite strain, several Newton steps); tolerance as for the split problems.
    """
    from tribofx.forms.hyperelastic import lame_parameters

    from tribofx.body import Body
    from tribofx.problem import Problem

    comm = MPI.COMM_WORLD
    out = {}
    for strategy in ("direct", "iterative"):
        msh = mesh.create_box(comm, [np.zeros(3), np.ones(3)], [6, 4, 4],
                              mesh.CellType.tetrahedron)
        fdim = 2
        msh.topology.create_connectivity(fdim, 3)
        left = mesh.locate_entities_boundary(msh, fdim, lambda x: np.isclose(x[0], 0.0))
        right = mesh.locate_entities_boundary(msh, fdim, lambda x: np.isclose(x[0], 1.0))
        idx = np.concatenate([left, right]).astype(np.int32)
        val = np.concatenate([np.full(len(left), 1), np.full(len(right), 2)]).astype(np.int32)
        order = np.argsort(idx)
        ft = mesh.meshtags(msh, fdim, idx[order], val[order])
        mu, lmbda = lame_parameters(1.0, 0.3)
        body = Body(msh, ft, {"left": 1, "right": 2}, "3d",
                    ("neo-hookean", {"mu": mu, "lmbda": lmbda}))
        body.add_dirichlet("left", np.zeros(3))
        body.add_traction("right", ufl.as_vector([0.3, 0.0, 0.05]))
        with solvers.run_settings(strategy):
            problem = Problem([body], name=f"block_{strategy}")
        rep = problem.solve()
        pc = problem.snes.getKSP().getPC()
        out[strategy] = (body.u.x.array.copy(), rep, pc.getType())
    (ud, rd, pcd), (ui, ri, pci) = out["direct"], out["iterative"]
    assert pcd == "lu" and pci == "gamg"
    assert ri.iterations == rd.iterations and ri.iterations >= 3
    tol = (_last_correction(rd, "displacement") + _last_correction(ri, "displacement")
           + 1e-12 * _max(comm, ud))
    diff = _max(comm, ui - ud)
    print(f"|iterative - direct| = {diff:.2e} <= {tol:.2e}")
    assert diff <= tol


def test_iterative_without_bulk_field_falls_back_to_direct():
    """A film alone (reynolds-slider) has nothing for AMG: solver=iterative gives LU."""
    from tribofx.cases import reynolds_slider

    v = resolve(reynolds_slider.Params, {})
    reynolds_slider.validate(v)
    with solvers.run_settings("iterative") as run:
        _, problem = reynolds_slider.build(v)
        assert problem.solver.name == "direct"
        assert "no bulk field" in run.used[problem.name]


def _delayed_pivot_matrix(n=400, m=200, seed=0):
    """A KKT matrix [[εI, B], [Bᵀ, 0]] (ε = 1e-8): LU must delay almost every pivot."""
    rng = np.random.default_rng(seed)
    A = PETSc.Mat().createAIJ([n + m, n + m], nnz=40, comm=PETSc.COMM_SELF)
    A.setOption(PETSc.Mat.Option.NEW_NONZERO_ALLOCATION_ERR, False)
    A.setUp()
    for i in range(n):
        A.setValue(i, i, 1e-8)
        for j in rng.integers(0, m, 3):
            v = rng.normal()
            A.setValue(i, n + j, v)
            A.setValue(n + j, i, v)
    A.assemble()
    return A


def test_mumps_workspace_grows_after_an_out_of_workspace_factorisation():
    """MUMPS error −9 (workspace too small) is recovered by doubling ICNTL(14).

    The delayed-pivot matrix needs more than the default 20 % of extra
    workspace, so the first factorisation fails with INFOG(1) = −9 and, on the
    same analysis, keeps failing (PETSc skips the numeric factorisations after a
    failed one); :func:`grow_workspace` doubles ICNTL(14) and resets the PC
    before each new solve.  How many doublings MUMPS needs depends on its
    pivoting (its version, the BLAS): the test asks for doublings from 20 %
    until the factorisation succeeds, within the 8 the loop allows.  Reference:
    the solution's residual |Ax − b| against the solve's accuracy (LU with
    threshold pivoting, backward error ~1e-14 |A||x|).
    """
    from tribofx.solvers import WORKSPACE_ERRORS, grow_workspace

    A = _delayed_pivot_matrix()
    ksp = PETSc.KSP().create(PETSc.COMM_SELF)
    ksp.setOptionsPrefix("test_workspace_")
    ksp.setOperators(A)
    ksp.setType("preonly")
    pc = ksp.getPC()
    pc.setType("lu")
    pc.setFactorSolverType("mumps")
    assert grow_workspace(pc) is None            # no factor yet: nothing to do
    b, x = A.createVecLeft(), A.createVecRight()
    b.set(1.0)
    ksp.solve(b, x)
    F = pc.getFactorMatrix()
    assert F.getMumpsInfog(1) in WORKSPACE_ERRORS and F.getMumpsIcntl(14) == 20
    grown = []
    while F.getMumpsInfog(1) in WORKSPACE_ERRORS and len(grown) < 8:
        grown.append(grow_workspace(pc))
        ksp.setOperators(A)                      # as SNES does at each Newton iteration
        ksp.solve(b, x)
        F = pc.getFactorMatrix()
    print("ICNTL(14) grown to", grown)
    assert F.getMumpsInfog(1) == 0 and ksp.getConvergedReason() > 0
    assert grown == [20 * 2 ** (k + 1) for k in range(len(grown))]
    r = A.createVecLeft()
    A.mult(x, r)
    r.axpy(-1.0, b)
    assert r.norm() <= 1e-10 * b.norm() * max(1.0, x.norm())
    assert grow_workspace(pc) is None            # a successful factorisation: nothing to do
    del PETSc.Options()["test_workspace_mat_mumps_icntl_14"]
