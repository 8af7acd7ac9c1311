"""Wear of both bodies of a two-body contact (eqs. 17-18) and the §5.1 case ``wear-reciprocating``.

References: the energy balance of a sliding step (work of the drive = change
of the stored energy of both bodies + frictional dissipation), Archard's law
(worn area = K × dissipated energy, for each body with its own K), eq. (18)
(the master's worn volume is K⁽²⁾/K⁽¹⁾ times the slave's: both are driven by
the slave's dissipation), and the time integral of each body's own rate.
"""

import json

import numpy as np
import pytest
from mpi4py import MPI
from test_two_body import two_blocks

from tribofx.output import bp4_steps
from tribofx.runner import run_case

COMM = MPI.COMM_WORLD


def test_dissipation_balances_the_work_of_the_drive():
    """Steady sliding of a block on a block: W_push = ΔE_stored + Σ ΔD⁽¹⁾ w_c.

    The push moves the slave's top by 0.1 mm in 10 committed sub-steps; the
    work of its support force is integrated by the trapezoidal rule, whose
    error for a force monotone within a sub-step is at most ½ Σ |ΔF| |Δx|; the
    dissipation increment of a sub-step, T_T(τ_{j+1})·Δs, is the right-point
    rule of ∫ T_T·ds, off by at most Σ_nodes w_c |ΔT_T| |Δs|; the Newton
    tolerance adds n_u·atol_u times the step length.  The sum of those bounds
    is the tolerance.
    """
    mu = 0.3
    slave, master, contact, problem, push = two_blocks(COMM, mu, fixed_master=False,
                                                       top=(0.0, -0.02))
    problem.solve()
    problem.commit()
    for k in range(1, 5):                 # into steady sliding
        push.value[:] = [0.1 * k, -0.02]
        problem.solve()
        problem.commit()
    energy0 = slave.strain_energy() + master.strain_energy()
    F0 = slave.reaction("top", 0)
    T0 = contact.nodal_data()["T_t"]
    work = bound = dissipation = 0.0
    x0 = 0.4
    for j in range(1, 11):
        x1 = 0.4 + 0.01 * j
        push.value[:] = [x1, -0.02]
        problem.solve()
        dD = contact.dissipation_increment()
        T1 = contact.nodal_data()["T_t"]
        F1 = slave.reaction("top", 0)
        assert COMM.allreduce(float(dD.min(initial=0.0)), op=MPI.MIN) >= -1e-12
        w = contact._w_c
        dissipation += COMM.allreduce(float(dD @ w), op=MPI.SUM)
        slip = np.divide(dD, np.linalg.norm(T1, axis=1), out=np.zeros_like(dD),
                         where=np.linalg.norm(T1, axis=1) > 0)
        bound += COMM.allreduce(float(np.sum(w * np.linalg.norm(T1 - T0, axis=1) * slip)),
                                op=MPI.SUM)
        work += 0.5 * (F0 + F1) * (x1 - x0)
        bound += 0.5 * abs(F1 - F0) * (x1 - x0)
        problem.commit()
        F0, T0, x0 = F1, T1, x1
    bound += slave.V.dofmap.index_map.size_global * 2 * slave.tolerances()[slave.u].atol * 0.1
    stored = slave.strain_energy() + master.strain_energy() - energy0
    print(f"work {work:.6e} stored {stored:.3e} dissipation {dissipation:.6e} bound {bound:.2e}")
    assert dissipation > 0.5 * work          # it is sliding, not storing
    assert abs(work - stored - dissipation) <= bound


def _run(tmp_path, name, *sets):
    overrides = dict(s.split("=", 1) for s in ("mesh=0", "cycles=100", "dt=10",
                                                "fast_steps=8") + sets)
    out = tmp_path / name
    run_case("wear-reciprocating", overrides, out=out, progress=False)
    return json.loads((out / "summary.json").read_text())


# implicit is slow (14 s): the bdf2 run takes the same Picard iteration of cycles, and
# its first step is backward Euler (the same swept area Δt ∫ W̄̇ dŜ)
@pytest.mark.parametrize("scheme", ["explicit", pytest.param("implicit", marks=pytest.mark.slow),
                                    "bdf2"])
def test_wear_reciprocating_both_bodies(tmp_path, scheme):
    """Worn areas of pin and block against Archard, eq. (18) and their own rates.

    Each shape step (28) sweeps exactly the volume Δt ∫ W̄̇ dŜ (the swept Nanson
    vector), to the tolerance of the ζ rows (1e-12 × body size per unit length,
    i.e. ~1e-11 mm² per mm of a surface of a few mm, against worn areas of
    ~1e-3 mm²): relative 1e-7 is a safe bound; BDF2 (constant Δt after its
    backward-Euler start) sweeps Δa_{n+1} = (2/3) Δt ∫ W̄̇ dŜ + (1/3) Δa_n.  Archard
    (14): worn area of the pin = K_pin × its dissipated energy (the θ-schemes,
    whose steps sum the rates); eq. (18): the block's worn area = K_block/K_pin ×
    the pin's (both driven by one dissipation: any linear scheme).  The block's
    drive over the last cycle did the work of the dissipation, to the bound of
    its trapezoidal rule.
    """
    s = _run(tmp_path, scheme, f"scheme={scheme}", "K_block=3e-5")
    assert s["status"] == "ok"
    r = {k: v["value"] for k, v in s["results"].items()}
    p = {k: v["value"] if isinstance(v, dict) else v for k, v in s["parameters"].items()}
    a_pin, a_block = np.array(r["worn_area_pin"]), np.array(r["worn_area_block"])
    dt = np.array(r["dt"])
    assert len(a_pin) == 3 and a_pin[-1] > 1e-4
    rel = 1e-7
    assert a_block[-1] == pytest.approx(p["K_block"] / p["K_pin"] * a_pin[-1], rel=rel)
    if scheme != "bdf2":
        assert a_pin[-1] == pytest.approx(p["K_pin"] * r["dissipated_energy"][-1], rel=rel)
    for a, rate in ((a_pin, r["rate_integral_pin"]), (a_block, r["rate_integral_block"])):
        swept = dt[1:] * np.array(rate[1:])
        if scheme == "bdf2":
            assert np.allclose(dt[2:], dt[1], rtol=1e-12)
            for n in range(1, len(swept)):
                swept[n] = 2 / 3 * swept[n] + 1 / 3 * (a[n] - a[n - 1])
        assert np.allclose(a[1:], np.cumsum(swept), rtol=rel, atol=0)
    for W, D, B in zip(r["drive_work"][1:], r["cycle_dissipation"][1:], r["drive_work_bound"][1:]):
        assert abs(W - D) <= B
    # the VTX time series holds the initial state and every slow step, for both bodies
    for body in ("pin", "block"):
        assert bp4_steps(tmp_path / scheme / f"{body}_series.bp") == len(a_pin)


def test_wear_reciprocating_bdf2_under_error_control(tmp_path):
    """scheme=bdf2 with tol = 1e-4 mm on the cycles (first step 2 s, 100 cycles, T = 20
    s): the controller varies the step (measured 2, 4, 8, 6 s, no rejection), and
    each body's worn area obeys the variable-step BDF2 recurrence of its recorded
    cycle-averaged rate integrals, c₀ Δa_{n+1} + c₁ Δa_n = Δt_{n+1} ∫W̄̇ dŜ
    (forms.wear.bdf2_coefficients, ω = Δt_{n+1}/Δt_n; backward Euler first), to the
    relative 1e-7 of test_wear_reciprocating_both_bodies."""
    from tribofx.forms.wear import bdf2_coefficients

    s = _run(tmp_path, "tol", "scheme=bdf2", "tol=1e-4", "dt=2")
    assert s["status"] == "ok"
    r = {k: v["value"] for k, v in s["results"].items()}
    dt = np.array(r["dt"])
    print("steps", dt[1:], "rejected", r["rejected_steps"], "estimates", r["error_estimate"][1:])
    assert len(set(np.round(dt[2:], 6))) > 1          # the controller changed the step
    for a, rate in ((r["worn_area_pin"], r["rate_integral_pin"]),
                    (r["worn_area_block"], r["rate_integral_block"])):
        da, rate = np.diff(a), np.array(rate)
        assert da[0] == pytest.approx(dt[1] * rate[1], rel=1e-7)
        for n in range(1, len(da)):
            c0, c1 = bdf2_coefficients(dt[n + 1] / dt[n])
            assert c0 * da[n] + c1 * da[n - 1] == pytest.approx(dt[n + 1] * rate[n + 1],
                                                                rel=1e-7)


@pytest.mark.slow
def test_wear_reciprocating_bdf2_error_follows_tol(tmp_path):
    """Error control on the cycles: the final worn profiles of pin and block under
    tol = 1e-5 and 1e-6 mm (first step 2 s, T = 20 s) against a fixed-step BDF2
    reference at Δt = 0.5 s (its own error: 7.6e-8 mm against Δt = 0.25 s; fixed steps
    converge at order 2.3: 3.8e-7 at Δt = 1 s, 1.6e-6 at 2 s) are within 2 tol, the
    factor of test_wear.test_bdf2_error_control_follows_the_tolerance (the controller
    holds Milne's estimate at tol·Δt/T per step, so that the steps' errors add up to
    about tol).  Measured (pin, block): tol 1e-5: 1.6e-6, 3.9e-8 mm (7 steps, 2
    rejected); tol 1e-6: 1.1e-6, 4.7e-8 mm (12 steps, 4 rejected; the sum of the
    estimates 6.4e-7).  At tol ≥ 1e-5 the 20 s are too short for the tolerance to
    limit the steps: from the first step they grow by the cap ×2 per step (estimates
    ≤ 0.2 of the allowance), so the error there is that of the step sizes (~1e-6 mm at
    tol 1e-4 and 1e-5 alike), below tol.  Slow (2 min, ``--runslow``)."""
    ref = _run(tmp_path, "ref", "scheme=bdf2", "dt=0.5")["results"]
    for tol in (1e-5, 1e-6):
        r = _run(tmp_path, f"tol{tol:g}", "scheme=bdf2", f"tol={tol}", "dt=2")["results"]
        err = [float(np.abs(np.array(r[f"final_profile_{b}"]["value"])
                            - np.array(ref[f"final_profile_{b}"]["value"])).max())
               for b in ("pin", "block")]
        print(f"tol {tol:g}: errors {err}, accepted {r['accepted_steps']['value']}, "
              f"rejected {r['rejected_steps']['value']}")
        assert max(err) <= 2 * tol


@pytest.mark.parametrize("scheme", ["explicit", "bdf2"])
def test_both_bodies_worn_tangent_taylor(scheme):
    """Exact tangent with both bodies worn (eqs. 17-18): after a slow step of the
    §5.1 case, the fast-time problem (pin and block displacements on their worn shapes,
    the two-body contact multipliers) and the slow-time shape problem of both bodies
    (w and ζ of pin and block, driven by their cycle-averaged rates) have Taylor
    remainders of order 2.  BDF2: at its second step, whose shape rows carry the
    volume swept in the first (weights c₀, c₁ ≠ 0).  Directions: 1e-6 mm and 1e-6 MPa
    keep the active and stick sets (as tests/test_two_body.py)."""
    from tribofx.cases import wear_reciprocating as Case
    from tribofx.params import resolve
    from tribofx.testing import block_taylor_orders, exact_tangent

    v = resolve(Case.Params, {"mesh": "0", "cycles": "100", "dt": "10", "fast_steps": "8",
                              "scheme": scheme})
    Case.validate(v)
    run = Case.build(v)
    Case.load_up(run, v)
    st = run.stepper
    st.start()
    for _ in range(2 if scheme == "bdf2" else 1):
        st.step(10.0)
    for wear in (run.wear_pin, run.wear_block):
        assert wear.max_depth() > 0
        wear.dt.value = 10.0   # the residual of the step (end_step zeroed Δt)
        if scheme == "bdf2":   # the second step's weights and the first step's volumes
            assert wear.bdf.c1.value != 0 and np.abs(wear.bdf.swept_old.x.array).max() > 0
    # slide on by a tenth of a fast step, uncommitted: right after a commit the slip is
    # zero and the slipping nodes sit on the kink of the Coulomb cone
    cycle = run.cycle
    cycle.drive(float(run.motion.value[0]) + 0.1 * 2 * v.A / v.fast_steps)
    st.problem.solve()
    rng = np.random.default_rng(3 + COMM.rank)
    for problem in (p for p in (st.problem, st.shape) if p is not None):
        dirs = [1e-6 * rng.standard_normal(len(f.x.array)) for f in problem.u]
        # each unknown's columns alone; the round-off floor where the residual is linear
        for name, (orders, rem, floor) in block_taylor_orders(problem, dirs, eps0=1.0).items():
            print(name, "orders", orders, "remainders", rem, "floor", floor)
            assert exact_tangent(orders, rem, floor), (name, orders, rem, floor)
