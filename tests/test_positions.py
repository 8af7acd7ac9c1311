"""Sub-element positions of extremes (``tribofx.positions``) against fields with a known extreme.

References: the vertex of a quadratic (exact: the 1D parabola and the 2D
least-squares quadratic reproduce quadratics, so only round-off remains), and
a cubic field f = (x−x₀)² + 2(y−y₀)² + ½(x−x₀)³ whose minimum is (x₀, y₀)
exactly (∇f = 0 there, H = diag(2, 4) > 0): the fit error is O(h²) (the cubic
remainder projected on the linear terms of a patch of radius ∝ h), against
O(h) for the node, so halving h divides the mean error by about 4 — the test
asks for an observed order above 1.5 (O(h) would give 1).

The zig-zag indicator (:func:`tribofx.positions.oscillation_indicator`)
against two profiles whose value is known in closed form: a nodal zig-zag
h̄(1 + δ(−1)^i) (second differences 4δh̄, so δ exactly), and the parabola
h = 1 + x² on a grid of spacing Δx (every second difference 2Δx², so
Δx²/(2 mean h) exactly, which vanishes with refinement); only the loaded zone
p > threshold counts.
"""

import numpy as np
import pytest

from tribofx.positions import oscillation_indicator, parabolic_vertex, paraboloid_vertex


def _scattered(h, rng, extent=1.0):
    """Jittered grid of spacing h on [−extent, extent]² (jitter ±h/3)."""
    g = np.arange(-extent, extent + h / 2, h)
    X, Y = np.meshgrid(g, g, indexing="ij")
    xy = np.column_stack([X.ravel(), Y.ravel()])
    return xy + rng.uniform(-h / 3, h / 3, xy.shape)


@pytest.mark.parametrize("kind,sign", [("min", 1.0), ("max", -1.0)])
def test_paraboloid_vertex_exact_for_a_quadratic(kind, sign):
    rng = np.random.default_rng(1)
    xy = _scattered(0.1, rng)
    x0, y0 = 0.0371, -0.0232
    H = np.array([[3.0, 0.8], [0.8, 1.5]])
    d = xy - [x0, y0]
    f = sign * (0.7 + 0.5 * np.einsum("ni,ij,nj->n", d, H, d))
    p = paraboloid_vertex(xy, f, kind)
    assert np.hypot(p[0] - x0, p[1] - y0) < 1e-12


def test_paraboloid_vertex_second_order():
    rng = np.random.default_rng(2)
    err = {}
    for h in (0.08, 0.04):
        e, e_node = [], []
        for _ in range(20):
            x0, y0 = rng.uniform(-0.2, 0.2, 2)
            xy = _scattered(h, rng, extent=0.5)
            dx, dy = xy[:, 0] - x0, xy[:, 1] - y0
            f = dx**2 + 2 * dy**2 + 0.5 * dx**3
            p = paraboloid_vertex(xy, f, "min")
            e.append(np.hypot(p[0] - x0, p[1] - y0))
            i = int(np.argmin(f))
            e_node.append(np.hypot(*(xy[i] - [x0, y0])))
        err[h] = (np.mean(e), np.mean(e_node))
    (e1, _), (e2, n2) = err[0.08], err[0.04]
    print("mean error fit / node:", err)
    assert np.log2(e1 / e2) > 1.5
    assert e2 < n2      # better than the node at the finer spacing


def test_parabolic_vertex_exact_for_a_parabola():
    x = np.sort(np.random.default_rng(3).uniform(0, 1, 15))
    f = -(x - 0.4321) ** 2
    assert parabolic_vertex(x, f, "max") == pytest.approx(0.4321, abs=1e-12)


def test_degenerate_patch_returns_the_node():
    xy = np.column_stack([np.linspace(0, 1, 10), np.zeros(10)])   # a line: rank deficient
    f = (xy[:, 0] - 0.33) ** 2
    i = int(np.argmin(f))
    assert paraboloid_vertex(xy, f, "min") == (xy[i, 0], 0.0)


@pytest.mark.parametrize("delta", [0.02, 0.3])
def test_oscillation_indicator_of_a_zigzag_is_its_amplitude(delta):
    i = np.arange(40)
    h = 2e-3 * (1 + delta * (-1.0) ** i)
    p = np.ones_like(h)
    assert oscillation_indicator(h, p, 0.5) == pytest.approx(delta, rel=1e-12)


def test_oscillation_indicator_of_a_smooth_film_vanishes_with_refinement():
    for dx in (0.1, 0.05, 0.025):
        x = np.arange(-1.0, 1.0 + dx / 2, dx)
        h, p = 1 + x**2, 1 - x**2          # the zone p > 0.75: |x| < 1/2
        zone = p > 0.75
        expected = dx**2 / (2 * np.mean(h[zone]))
        assert oscillation_indicator(h, p, 0.75) == pytest.approx(expected, rel=1e-9)
    # a zone of fewer than three nodes has no second difference
    assert oscillation_indicator(h, p, 0.9999) == 0.0

