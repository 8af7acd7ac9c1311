"""Benchmark of the closest-point projection: C++ kernel vs NumPy brute-force twin.

Usage: .venv/bin/python benchmarks/bench_projection.py [results.json] [--quick]
"""

from __future__ import annotations

import json
import platform
import sys
import time
from pathlib import Path

import numpy as np

from tribofx.projection import closest_point_projection
from tribofx.projection_ref import closest_point_projection_ref

__all__ = ["main", "perturbed_surface"]


def perturbed_surface(nx: int, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """Triangulated z = f(x, y) + noise on [0, 1]^2: (nx+1)^2 nodes, 2 nx^2 triangles."""
    u = np.linspace(0.0, 1.0, nx + 1)
    X, Y = np.meshgrid(u, u, indexing="xy")
    X = X + rng.uniform(-0.2, 0.2, X.shape) / nx
    Y = Y + rng.uniform(-0.2, 0.2, Y.shape) / nx
    Z = 0.1 * np.sin(4 * X) * np.cos(3 * Y) + 0.2 / nx * rng.standard_normal(X.shape)
    nodes = np.c_[X.ravel(), Y.ravel(), Z.ravel()]
    i, j = np.meshgrid(np.arange(nx), np.arange(nx), indexing="xy")
    a = (j * (nx + 1) + i).ravel()
    b, c, d = a + 1, a + nx + 1, a + nx + 2
    facets = np.concatenate([np.c_[a, b, d], np.c_[a, d, c]]).astype(np.int32)
    return nodes, facets


def main(argv: list[str]) -> dict:
    quick = "--quick" in argv
    args = [a for a in argv if not a.startswith("--")]
    out = Path(args[0]) if args else Path(__file__).parent / "results" / "projection.json"
    rng = np.random.default_rng(2025)
    nx = 60 if quick else 224
    n_cpp = 20_000 if quick else 200_000
    n_ref = 50 if quick else 200  # brute force over ~100k facets: ~0.5 s per point
    nodes, facets = perturbed_surface(nx, rng)
    # Points around the surface: most close to it (contact), some further away
    xy = rng.uniform(0.0, 1.0, (n_cpp, 2))
    z = 0.1 * np.sin(4 * xy[:, 0]) * np.cos(3 * xy[:, 1])
    near = rng.random(n_cpp) < 0.8
    z += np.where(near, 0.01, 0.1) * rng.standard_normal(n_cpp)
    points = np.c_[xy, z]

    closest_point_projection(points[:100], nodes, facets, "triangle")  # warm-up
    t0 = time.perf_counter()
    res = closest_point_projection(points, nodes, facets, "triangle")
    t_cpp = time.perf_counter() - t0

    rates = {}
    for name, sel in (("near", near), ("far", ~near)):
        t0 = time.perf_counter()
        closest_point_projection(points[sel], nodes, facets, "triangle")
        rates[name] = sel.sum() / (time.perf_counter() - t0)

    sample = points[:n_ref]
    t0 = time.perf_counter()
    ref = closest_point_projection_ref(sample, nodes, facets, "triangle")
    t_ref = time.perf_counter() - t0
    agree = bool(np.array_equal(ref.facet, res.facet[:n_ref])) and bool(
        np.allclose(ref.x_bar, res.x_bar[:n_ref], rtol=0, atol=1e-12)
    )

    cpp_rate = n_cpp / t_cpp
    ref_rate = n_ref / t_ref
    result = {
        "num_facets": int(len(facets)),
        "cell_type": "triangle",
        "cpp": {
            "num_points": n_cpp,
            "seconds": t_cpp,
            "points_per_second_per_core": cpp_rate,
            "near_points_per_second (80%, sigma=0.01)": rates["near"],
            "far_points_per_second (20%, sigma=0.1)": rates["far"],
        },
        "numpy_bruteforce": {
            "num_points": n_ref,
            "seconds": t_ref,
            "points_per_second_per_core": ref_rate,
        },
        "speedup": cpp_rate / ref_rate,
        "results_agree_on_sample": agree,
        "inside_fraction": float(res.inside.mean()),
        "machine": platform.processor() or platform.machine(),
        "python": platform.python_version(),
    }
    print(f"surface: {len(facets)} triangles")
    print(f"C++ kernel : {n_cpp} points in {t_cpp:.3f} s -> {cpp_rate:,.0f} points/s/core")
    print(f"  near points (|z - f| ~ 0.01): {rates['near']:,.0f} points/s/core")
    print(f"  far points  (|z - f| ~ 0.1) : {rates['far']:,.0f} points/s/core")
    print(f"NumPy twin : {n_ref} points in {t_ref:.3f} s -> {ref_rate:,.1f} points/s/core")
    print(f"speed-up   : {cpp_rate / ref_rate:,.0f}x   (sample results agree: {agree})")
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(result, indent=2) + "\n")
    print(f"wrote {out}")
    return result


if __name__ == "__main__":
    main(sys.argv[1:])
