"""The O-ring over a reciprocating stroke (``ehl-oring stroke=cycle``).

The long-period limit against the chapter's steady outstroke (an independent solve
of the steady rows) and against the steady instroke, the coupled tangent mid-step
(the transient JFO film with the lumped transport, the open air end and the rough
rod) and Newton's rate, the oil's books (each step's content change against the
fluxes through the ends; the whole cycle), the rows' round-off floor, the
scheme's integrals of the fluxes.  Density 2 (0.05 mm on the film arc) unless
stated, the mixed solid, JFO.
"""

import math

import numpy as np
import pytest
from dolfinx import fem, la
from mpi4py import MPI
from test_ehl_oring import _seal_taylor_orders, assert_exact
from ufl import TestFunction

from tribofx.cases import ehl_oring as Case
from tribofx.cases.ehl_oring import (
    AirLayer,
    air_end,
    build,
    cycle_stepper,
    integral,
    solve_to,
    transient_seal,
)
from tribofx.params import resolve

U0 = 400.0


def values(**over):
    """The case's values at density 2 on the unrefined film arc (25 µm: a cycle's default
    is refined once, ``ehl_oring.arc_halvings``), with ``over``."""
    return resolve(Case.Params, {"mesh": "2", "arc_refine": "0",
                                 **{k: str(x) for k, x in over.items()}})


def cycle(v, steps):
    """The seal at U0, its steady outstroke at p_s = 1 MPa, then ``steps`` steps of the cycle."""
    st = cycle_stepper(v)
    seal = st.seal
    dt = v.period / v.cycle_steps
    st.run(steps * dt, dt)
    return seal, st


@pytest.mark.slow
def test_long_period_follows_the_steady_outstroke():
    """At t = T/8 (U = 400 cos 45° = 282.8 mm/s) the cycle's film is the steady outstroke's
    at that speed, up to the film's lag behind the slowing rod, which is ∝ 1/T.

    Reference: the steady outstroke solved at 282.8 mm/s (the chapter's rows, no
    time).  The lag is the film's response time (τ ~ ℓ/U ~ 1 ms for the contact
    ℓ ≈ 0.3 mm) times the relative deceleration |U̇|/U = (2π/T) tan 45°: 6e-4 at
    T = 10 s for a measure that follows U to the first power (h ∝ U^0.5…0.7: less).
    Asserted: the departure of h_min, the mean film of the loaded zone and the air
    end's flux falls by 10 ± 1.5 from T = 10 s to 100 s (first order in 1/T; the
    time error of BDF2 at 40 steps per period, on rates that are themselves ∝ 1/T,
    is of higher order), and is below 1e-2 at T = 10 s (measured 4.9e-3, 1.5e-3,
    6.3e-3 and 4.9e-4, 1.5e-4, 6.4e-4 at 100 s).
    """
    U = U0 * math.cos(math.pi / 4)
    ref = build(values(U=U), 1000.0)
    solve_to(ref, values(U=U), U, [1.0])
    m_ref = ref.measures()
    q_ref = air_end(ref)[0]
    dev = {}
    for T in (10.0, 100.0):
        seal, st = cycle(values(stroke="cycle", period=T, scheme="bdf2"), 5)
        assert st.t == pytest.approx(T / 8) and seal.U == pytest.approx(U)
        m = seal.measures()
        dev[T] = np.array([m["h_min"] / m_ref["h_min"] - 1, m["h_mean"] / m_ref["h_mean"] - 1,
                           air_end(seal)[0] / q_ref - 1])
    print("departures", dev)
    assert np.all(np.abs(dev[10.0]) < 1e-2)
    assert np.all(np.abs(dev[10.0] / dev[100.0] - 10) < 1.5)


@pytest.mark.slow
def test_cycle_tangent_is_exact_and_newton_quadratic():
    """Mid-step of the rough seal's cycle (σ = 0.2 µm, BDF2, two steps done): the coupled
    tangent (the transient JFO rows with the lumped rate, the open air end, the
    asperity pressure and friction, the solid, the housing contacts) passes the
    Taylor test in every unknown (also with the instroke's vertex-rule Couette share
    ω = 1), and the step converges quadratically (the last
    rate of the residual norms above round-off ≥ 1.8; measured 2.03).  Density 4: at
    density 2 the rough seal's steady start stalls at a residual floor of 9e-7
    mm³/s of the flank rows, above the film's tolerance (not investigated)."""
    v = values(stroke="cycle", sigma=2e-4, mesh=4, scheme="bdf2")
    seal, st = cycle(v, 2)
    state = st.state()
    dt = v.period / v.cycle_steps
    st.wear.begin_step(dt)
    for c, f in st.schedule:
        c.value = f(st.t + dt)
    seal.problem = st.problem
    orders = _seal_taylor_orders(seal, seed=5)
    assert_exact(orders)
    # the instroke's vertex-rule share of the cavitated Couette flux (ω = 1), at this state
    seal.film.vertex_couette.value = 1.0
    orders = _seal_taylor_orders(seal, seed=6)
    seal.film.vertex_couette.value = 0.0
    assert_exact(orders)
    rep = st.problem.solve()
    st.restore(state)
    # the last residual (1.2e-12, measured) is at the round-off of the thick flanks' rows
    # (test_ehl_oring.test_newton_quadratic): residuals below 1e-9 of the first are dropped
    assert rep.iterations <= 12 and rep.rates(floor=1e-9)[-1] > 1.8, rep.residuals


def _rows(film):
    """The film's Reynolds rows at the current state, owned nodes (ends included)."""
    R = fem.assemble_vector(fem.form(film._reynolds(TestFunction(film.Q))[0],
                                     entity_maps=film.entity_maps() or None))
    R.scatter_reverse(la.InsertMode.add)
    return R.array[:film.Q.dofmap.index_map.size_local].copy()


def _interior_row_bound(film):
    """√N ‖R_int‖₂ ≥ |Σ R_int| (Cauchy–Schwarz): the film's Reynolds rows at the current
    state with the end nodes left out (N interior nodes, every rank)."""
    r = _rows(film)
    n = len(r)
    ends = film._boundary_dofs(film.Q, None)
    r[ends[ends < n]] = 0.0
    comm = film.sub.comm
    N = comm.allreduce(n, op=MPI.SUM) - 2
    return math.sqrt(N) * math.sqrt(comm.allreduce(float(r @ r), op=MPI.SUM))


# on 2 ranks: BDF2, which starts with a backward-Euler step after the mount (the
# coupled start after the mount); the Euler run repeats it serially
@pytest.mark.parametrize("scheme", ["euler", pytest.param("bdf2", marks=pytest.mark.mpi)])
def test_film_content_changes_by_the_net_flux_of_each_step(scheme):
    """Mass conservation of the transient JFO seal: over each step the oil in
    the film changes by the flux in at the sealed end minus the flux out at the air
    end, the scheme's difference of the contents against the fluxes at t_{n+1}:
    (C_{n+1} − C_n)/Δt (backward Euler), (3C_{n+1} − 4C_n + C_{n−1})/(2Δt) (BDF2
    after its backward-Euler start).  The fluxes come from the rows of the end nodes
    (``consistent_fluxes``), the contents from the histories; the two sides differ by
    the sum of the interior rows, zero at convergence: asserted within its
    Cauchy–Schwarz bound √N ‖R_int‖ of the converged state (the solver's tolerance;
    measured differences 3e-9 of fluxes near 14 mm³/s); it fails if a revolved film's
    fluxes miss the weight 2πr_S of the Couette flux or a transient film the surface's
    motion.  Smooth rod, density 2, the outstroke's first three steps (U from 400 to
    356 mm/s: the oil in the film grows by 1 % per 10 ms; BDF2 from its second)."""
    v = values(stroke="cycle", scheme=scheme)
    st = cycle_stepper(v)
    film = st.seal.film
    dt = v.period / v.cycle_steps
    C = [film.content()]
    for k in range(3):
        st.run(st.t + dt, dt)
        C.append(film.content())
        q_in, q_out = film.consistent_fluxes()
        if scheme == "euler" or k == 0:
            rate = (C[-1] - C[-2]) / dt
        else:
            rate = (3 * C[-1] - 4 * C[-2] + C[-3]) / (2 * dt)
        bound = _interior_row_bound(film)
        print(f"t = {st.t:.4f} s: dC/dt {rate:.6e}, q_in − q_out {q_in - q_out:.6e}, "
              f"bound {bound:.2e}")
        assert abs(rate) > 0.5                   # the content does change
        assert abs(rate - (q_in - q_out)) <= bound
    # the rows' round-off floor (added to the p tolerance of a step) bounds what an ulp
    # of the pressures does to them, and is that size: p moved by one ulp up and down
    # alternately along the film (1.5 ε|p| between neighbours at p = 1, just above a
    # power of 2) moves a row by 2 · 1.5 ε K|p|, 3/4 of the floor 4ε max K|p| at the
    # row of the largest K|p| (the thick flank at p_s); asserted within [1/4, 1] of it
    R0 = _rows(film)
    p0 = film.p.x.array.copy()
    z = film.Q.tabulate_dof_coordinates()[:, 1]
    every = np.sort(np.concatenate(MPI.COMM_WORLD.allgather(z)))
    up = np.searchsorted(every, z) % 2 == 1
    film.p.x.array[:] = np.nextafter(p0, np.where(up, np.inf, -np.inf))
    dR = MPI.COMM_WORLD.allreduce(float(np.max(np.abs(_rows(film) - R0), initial=0.0)),
                                  op=MPI.MAX)
    film.p.x.array[:] = p0
    floor = film.row_round_off()
    print(f"rows moved by {dR:.2e} by rounding p; floor {floor:.2e}")
    assert floor / 4 <= dR <= floor


def _balance_bound(t, b, scheme):
    """Bound on |content change − the scheme's integral of q_in − q_out| over the steps.

    Each step's balance c₀ΔC_{n+1} + c₁ΔC_n = Δt_{n+1}(q_in − q_out) holds to Δt_{n+1} b_{n+1}
    (the interior-row bound), so the increments' errors d obey
    |d_{n+1}| ≤ (Δt b + |c₁| |d_n|)/c₀ (backward Euler: c₀ = 1, c₁ = 0); returns Σ|d_n|.
    """
    from tribofx.forms.wear import bdf2_coefficients

    total, d, prev = 0.0, 0.0, 0.0
    for n in range(len(t) - 1):
        dt = t[n + 1] - t[n]
        c0, c1 = (1.0, 0.0) if scheme == "euler" or prev <= 0 else bdf2_coefficients(dt / prev)
        d = (dt * b[n] + abs(c1) * d) / c0
        total, prev = total + d, dt
    return total


@pytest.mark.slow
def test_whole_cycle_keeps_the_oil_balance():
    """The rough seal (σ = 0.2 µm, density 4 with the film arc refined once, 12.5 µm,
    40 steps per period) runs the whole cycle through both reversals with BDF2, and
    over it the oil balances: the intake at the sealed end minus the
    leakage at the air end, each integrated by the film's own scheme
    (``oring_cycle.integral``: Σ Δt_n q(t_{n+1}) for backward Euler), equals the
    change of the film's content, within the steps' interior-row bounds Δt_n √N
    ‖R_int‖ (the solver's tolerance) carried through the scheme's recursion
    (:func:`_balance_bound`; the change is about 0.05 mm³ (0.054 with backward Euler), the sealed
    end passing hundreds of mm³/s in and out while the thick flank breathes).  At 25
    µm the instroke's outlet constriction is one node wide and Newton may stall in
    the instroke.  About 8 min.  Backward Euler's books are checked step by step in
    the default run (``test_film_content_changes_by_the_net_flux_of_each_step``),
    its integral by :func:`test_cycle_integrals_converge_at_the_scheme_order`, and
    its whole cycle on this seal by ``demos/demo_oring_cycle.py`` (without
    ``--quick``: the books of each of the 40 steps)."""
    scheme = "bdf2"
    v = values(stroke="cycle", sigma=2e-4, mesh=4, arc_refine=1, scheme=scheme)
    st = cycle_stepper(v)
    film, T = st.seal.film, v.period
    C0, rec = film.content(), [(0.0, 0.0, 0.0, 0.0)]

    def on_step(stepper, report):
        q_in, q_out = film.consistent_fluxes()
        rec.append((stepper.t, q_in, q_out, _interior_row_bound(film)))

    st.run(T, T / v.cycle_steps, on_step=on_step)
    t, q_in, q_out, bound = np.array(rec).T
    change = film.content() - C0
    net = integral(t, q_in - q_out, scheme)[-1]
    tol = _balance_bound(t, bound[1:], scheme)
    print(f"{len(t) - 1} steps: content change {change:.6e}, intake − leakage {net:.6e}, "
          f"bound {tol:.2e}; leakage {integral(t, q_out, scheme)[-1]:.4f} mm³")
    assert st.t == pytest.approx(T) and st.seal.U == pytest.approx(U0)
    assert abs(change) > 1e-3                    # the cycle does move oil
    assert abs(change - net) <= tol


@pytest.mark.parametrize("scheme, order", [("euler", 1), ("bdf2", 2)])
def test_cycle_integrals_converge_at_the_scheme_order(scheme, order):
    """The per-cycle leakage and intake integrate the fluxes by the film's own scheme
    (``oring_cycle.integral``, so that intake − leakage is the content change):
    ∫₀¹ cos(2πt) … against sin(2πt)/2π on steps of alternating length (ratio 1.5,
    as cut steps are), errors falling at the scheme's order (measured 1.00 and 2.02;
    asserted ± 0.1 over a factor 4 in Δt)."""
    err = []
    for n in (40, 160):
        dt = np.tile([1.0, 1.5], n // 2)
        t = np.concatenate([[0.0], np.cumsum(dt / dt.sum())])
        Q = integral(t, np.cos(2 * np.pi * t), scheme)
        err.append(np.max(np.abs(Q - np.sin(2 * np.pi * t) / (2 * np.pi))))
    assert abs(math.log(err[0] / err[1], 4) - order) < 0.1, err


def test_air_layer_returns_at_the_mirror_time():
    """The instroke's supply at t is the outstroke's air-end content at 2t_r − t.

    A rod point at the air end at t in the instroke was there at the mirror time
    of the outstroke (the stroke z(t) = z₀ + (UT/2π) sin(2πt/T) is symmetric
    about each reversal t_r = T/4 + kT).  Recorded contents c(t) = 1 + t (mm, a
    line, so the interpolation is exact): supply(T/4 + s) = c(T/4 − s); before the
    first record (2t_r − t < 0) the first one (the steady outstroke); in the second
    cycle the reversal at 5T/4 mirrors into that cycle's outstroke.
    """
    T = 0.1
    layer = AirLayer({}, T)
    for t in np.linspace(0.0, T / 4, 11):
        layer.record(t, 1 + t, U=1.0)
    layer.record(0.3 * T, 99.0, U=-1.0)          # an instroke state is not recorded
    for s in (0.0, 0.01, 0.02):
        assert layer.supply(T / 4 + s) == pytest.approx(1 + T / 4 - s, rel=1e-12)
    assert layer.supply(0.7 * T) == pytest.approx(1.0)
    for t in np.linspace(T, 1.25 * T, 11):
        layer.record(t, 5 + t, U=1.0)
    assert layer.supply(1.25 * T + 0.01) == pytest.approx(5 + 1.25 * T - 0.01, rel=1e-12)


def _steady_departure(seal, stepper):
    """Relative departures of h_min, h_mean, p_max of the transient state from the steady
    film at the same instant (the rate weights set to 0: the steady rows, solved by
    Newton from the transient state); the state is restored."""
    film = seal.film
    m = seal.measures()
    state, weights = stepper.state(), [float(c.value) for c in film.history.weights]
    for c in film.history.weights:
        c.value = 0.0
    stepper.problem.solve()
    ref = seal.measures()
    for c, w in zip(film.history.weights, weights):
        c.value = w
    stepper.restore(state)
    return np.array([m[k] / ref[k] - 1 for k in ("h_min", "h_mean", "p_max")])


@pytest.mark.slow
def test_long_period_follows_the_steady_instroke():
    """In the instroke the film follows the steady instroke at the same speed and supply,
    up to a lag ∝ 1/T.  The rough seal (σ = 0.2 µm, density 4, BDF2) is built in
    the instroke at its peak speed −400 mm/s (t = T/2), the air end supplied with
    a flooding layer (c = 0.05 mm; the contact takes what a layer of 0.5 µm
    brings and the rest leaks back), solved steady, and stepped to t = 5T/8
    (−282.8 mm/s, 5 steps).  Reference: the steady rows at that instant, solved
    from the transient state.  Asserted: the departures of h_min, the mean film and
    p_max fall by 10 ± 1.5 from T = 10 s to 100 s (first order in 1/T; measured
    9.1, 9.7, 9.6), and those of the mean film and p_max are below the lag
    estimate of the outstroke test, 1e-2, at 10 s (measured 3.8e-3, 5.5e-5).
    h_min, at the outlet constriction on the sealed side (one node wide at this
    density, a thin film whose squeeze is slow), lags more: 7.6e-2 at 10 s,
    8.3e-3 at 100 s."""
    v0 = values(stroke="cycle", sigma=2e-4, mesh=4, scheme="bdf2")
    seal = transient_seal(v0, -U0)
    seal.supply.value = 0.05
    seal.film.vertex_couette.value = 1.0
    solve_to(seal, v0, -U0, [1.0])
    dev = {}
    for T in (10.0, 100.0):
        st = cycle_stepper(values(stroke="cycle", sigma=2e-4, mesh=4, scheme="bdf2",
                                  period=T), seal=seal)
        start = st.state()
        st.t = T / 2
        st.layer.h.update({"t": [-1.0, 0.0], "c": [0.05, 0.05]})   # the same layer throughout
        st.run(5 * T / 8, T / 40)
        assert seal.U == pytest.approx(-U0 * math.cos(math.pi / 4))
        dev[T] = _steady_departure(seal, st)
        st.restore(start)
    print("departures", dev)
    assert np.all(np.abs(dev[10.0][1:]) < 1e-2)
    assert np.all(np.abs(dev[10.0] / dev[100.0] - 10) < 1.5)
