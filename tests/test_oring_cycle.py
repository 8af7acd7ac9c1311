"""The O-ring over a reciprocating stroke (``ehl-oring stroke=cycle``, issue 31).

The long-period limit against the chapter's steady outstroke (an independent solve
of the steady rows), the coupled tangent mid-step (the transient JFO film with the
lumped transport, the open air end and the rough rod) and Newton's rate.  Density
2 (0.05 mm on the film arc), the mixed solid, JFO.
"""

import math

import numpy as np
import pytest
from dolfinx import la
from test_ehl_oring import _seal_taylor_orders

from tribofx.cases.ehl_oring import EHLORingCase as Case
from tribofx.cases.oring_cycle import AirLayer, air_end, cycle_stepper
from tribofx.cases.oring_seal import build, solve_to
from tribofx.params import resolve

U0 = 400.0


def values(**over):
    return resolve(Case.params, {"mesh": "2", **{k: str(x) for k, x in over.items()}})


def cycle(v, steps):
    """The seal at U0, its steady outstroke at p_s = 1 MPa, then ``steps`` steps of the cycle."""
    st = cycle_stepper(v)
    seal = st.seal
    st.layer.record(0.0, air_end(seal)[0], U0)
    dt = v["period"] / v["cycle_steps"]
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
    dt = v["period"] / v["cycle_steps"]
    st.wear.begin_step(dt)
    for c, f in st.schedule:
        c.value = f(st.t + dt)
    seal.problem = st.problem
    orders = _seal_taylor_orders(seal, seed=5)
    assert np.all(orders > 1.8), orders
    # the instroke's vertex-rule share of the cavitated Couette flux (ω = 1), at this state
    seal.film.vertex_couette.value = 1.0
    orders = _seal_taylor_orders(seal, seed=6)
    seal.film.vertex_couette.value = 0.0
    assert np.all(orders > 1.8), orders
    rep = st.problem.solve()
    st.restore(state)
    # the last residual (1.2e-12, measured) is at the round-off of the thick flanks' rows
    # (test_ehl_oring.test_newton_quadratic): residuals below 1e-9 of the first are dropped
    assert rep.iterations <= 12 and rep.rates(floor=1e-9)[-1] > 1.8, rep.residuals


def _interior_row_bound(film):
    """√N ‖R_int‖₂ ≥ |Σ R_int| (Cauchy–Schwarz): the film's Reynolds rows at the current
    state with the end nodes left out (N interior nodes, every rank)."""
    from dolfinx import fem
    from mpi4py import MPI
    from ufl import TestFunction

    R = fem.assemble_vector(fem.form(film._reynolds(TestFunction(film.Q))[0],
                                     entity_maps=film.entity_maps() or None))
    R.scatter_reverse(la.InsertMode.add)
    n = film.Q.dofmap.index_map.size_local
    r = R.array[:n].copy()
    ends = film._boundary_dofs(film.Q, None)
    r[ends[ends < n]] = 0.0
    comm = film.sub.comm
    N = comm.allreduce(n, op=MPI.SUM) - 2
    return math.sqrt(N) * math.sqrt(comm.allreduce(float(r @ r), op=MPI.SUM))


@pytest.mark.mpi
@pytest.mark.parametrize("scheme", ["euler", "bdf2"])
def test_film_content_changes_by_the_net_flux_of_each_step(scheme):
    """Mass conservation of the transient JFO seal (issue 31): over each step the oil in
    the film changes by the flux in at the sealed end minus the flux out at the air
    end, the scheme's difference of the contents against the fluxes at t_{n+1}:
    (C_{n+1} − C_n)/Δt (backward Euler), (3C_{n+1} − 4C_n + C_{n−1})/(2Δt) (BDF2
    after its backward-Euler start).  The fluxes come from the rows of the end nodes
    (``consistent_fluxes``), the contents from the histories; the two sides differ by
    the sum of the interior rows, zero at convergence: asserted within its
    Cauchy–Schwarz bound √N ‖R_int‖ of the converged state (the solver's tolerance;
    measured differences 3e-9 of fluxes near 14 mm³/s).  Before this test the fluxes
    of a revolved film missed the weight 2πr_S of the Couette flux and a transient
    film the surface's motion.  Smooth rod, density 2, the outstroke's first steps
    (U from 400 to 323 mm/s: the oil in the film grows by 1 % per 10 ms)."""
    v = values(stroke="cycle", scheme=scheme)
    st = cycle_stepper(v)
    film = st.seal.film
    st.layer.record(0.0, air_end(st.seal)[0], U0)
    dt = v["period"] / v["cycle_steps"]
    C = [film.content()]
    for k in range(4):
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
