"""Taylor tests of assembled Jacobians, for tribofx's own tests and for users' forms.

Public DOLFINx/tribofx API only.  A researcher who writes a new law or form checks
its tangent with the same call the test suite uses::

    from tribofx.testing import owned_arrays, taylor_orders
    rng = np.random.default_rng(0)                   # a direction per unknown
    d = [1e-6 * rng.standard_normal(len(f.x.array)) for f in problem.u]
    orders, remainders = taylor_orders(problem, owned_arrays(problem, d))
    assert min(orders) > 1.8

For a direction d, the remainder r(ε) = ‖R(x + ε d) − R(x) − ε J(x) d‖ must decay
like ε² when J is the exact derivative of R; the observed orders
log₂(r(ε)/r(ε/2)) are returned with the remainders relative to the linear term
ε₀‖J d‖.

* :func:`taylor_orders` — a :class:`tribofx.problem.Problem` at its current
  unknowns, through its own ``assemble()`` and ``residual_at(x)`` (so every
  component's ``refresh`` — e.g. the kernel projection onto a meshed
  countersurface — runs at each perturbed state, as in Newton's iteration).
  The directions are Functions or the owned arrays of the problem's own layout,
  so a :class:`tribofx.reduced.ReducedProblem` with replicated unknowns (owned
  by rank 0) is tested on several ranks too;
* :func:`form_taylor_orders` — one bare residual form of one field;
* :func:`border_taylor_orders` — the border of a bordered Newton system
  (:class:`tribofx.bordered.Border`: ∂R/∂δ, ∂G/∂x, ∂G/∂δ).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from petsc4py import PETSc

from .reports import convergence_orders

if TYPE_CHECKING:
    import numpy.typing as npt
    import ufl
    from dolfinx import fem

    from .bordered import Border
    from .interfaces.film import Film
    from .problem import Problem

    #: a direction: one entry per unknown, its owned array or a ``fem.Function``
    Direction = Sequence[npt.NDArray[np.float64]] | Sequence[fem.Function]
    #: (observed orders, relative remainders) of a Taylor test
    Orders = tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]

__all__ = ["block_taylor_orders", "block_vector", "border_taylor_orders", "exact_tangent",
           "form_taylor_orders", "newton_is_quadratic", "oil_books",
           "owned_arrays", "penalty_film_directions", "residual_floor", "smooth_direction",
           "taylor_orders"]


def _replicated(problem: Problem, f: fem.Function) -> bool:
    return f.function_space.mesh.comm.size == 1 and problem.snes.comm.size > 1


def owned_arrays(problem: Problem, functions: Sequence[fem.Function | npt.NDArray[np.float64]]
                 | None = None) -> list[npt.NDArray[np.float64]]:
    """Owned entries of each unknown (a replicated unknown is owned by rank 0)."""
    out = []
    for ui, f in zip(problem.u, functions or problem.u):
        V = ui.function_space
        if _replicated(problem, ui):
            n = len(ui.x.array) if problem.snes.comm.rank == 0 else 0
        else:
            n = V.dofmap.index_map.size_local * V.dofmap.index_map_bs
        out.append(np.asarray(f.x.array[:n] if hasattr(f, "x") else f[:n]))
    return out


def smooth_direction(f: fem.Function, scale: float, seed: int) -> fem.Function:
    """Return a smooth random direction in the space of ``f`` (x and y enter).

    Each component is scale·sin(c₀ + 2c₁x + 3c₂y) with c uniform in [−1, 1]³: of size
    ``scale`` everywhere, so a Taylor step stays within one branch of a semismooth
    law where a random nodal direction would cross its kinks.
    """
    from dolfinx import fem

    d = fem.Function(f.function_space)
    rng = np.random.default_rng(seed)
    c = rng.uniform(-1, 1, (f.function_space.value_size, 3))
    d.interpolate(lambda x: scale * np.array([np.sin(ci[0] + 2 * ci[1] * x[0] + 3 * ci[2] * x[1])
                                              for ci in c]))
    return d


def penalty_film_directions(problem: Problem, p: fem.Function, seed: int, scale: float = 1e-7,
                            p_scale: float = 1e-4) -> list[npt.NDArray[np.float64]]:
    """Owned random directions of every unknown; the film pressure ``p`` off its kink.

    A penalty film's ε⁻¹ min(p, 0) has a kink at p = 0 (semismooth), where no
    tangent is exact: p (a Function among ``problem.u``) is moved only where
    p > 0.01 p_max, by ``p_scale``; the other unknowns everywhere by ``scale``.
    """
    rng = np.random.default_rng(seed)
    dirs = [scale * rng.standard_normal(len(f.x.array)) for f in problem.u]
    k = [i for i, f in enumerate(problem.u) if f is p][0]
    a = p.x.array
    dirs[k] = np.where(a > 0.01 * a.max(), p_scale * rng.standard_normal(len(a)), 0.0)
    return owned_arrays(problem, dirs)


def block_vector(problem: Problem, arrays: Sequence[npt.NDArray[np.float64]]) -> PETSc.Vec:
    """PETSc vector of the problem's layout from the owned arrays of each unknown."""
    # petsc4py's stub: SNES.getFunction returns (Vec, (function, args, kwargs))
    x = problem.snes.getFunction()[0].duplicate()  # type: ignore[index]
    x.setArray(np.concatenate(arrays))
    return x


def taylor_orders(problem: Problem, direction: Direction, eps0: float = 1e-3,
                  n: int = 4) -> Orders:
    """Orders log₂(r(ε)/r(ε/2)) at the current unknowns along ``direction``.

    ``direction``: one entry per unknown of ``problem.u`` (same order), either
    the owned arrays of :func:`owned_arrays` or ``fem.Function`` objects.
    Returns (orders, remainders relative to ε₀‖J d‖); the unknowns are restored.
    """
    if all(hasattr(d, "x") for d in direction):
        direction = owned_arrays(problem, direction)
    saved = [ui.x.array.copy() for ui in problem.u]
    b0, A = problem.assemble()
    b0 = b0.copy()
    x0 = block_vector(problem, owned_arrays(problem))
    d = block_vector(problem, cast("list[npt.NDArray[np.float64]]", direction))  # arrays by now
    Ad = A.createVecLeft()
    A.mult(d, Ad)
    rem: Any = []   # the remainders: a list, then its array
    for k in range(n):
        eps = eps0 * 2.0**-k
        x = x0.copy()
        x.axpy(eps, d)
        r = problem.residual_at(x)
        r.axpy(-1.0, b0)
        r.axpy(-eps, Ad)
        rem.append(r.norm(PETSc.NormType.NORM_2))  # type: ignore[arg-type]  # (stub: int)
        for v in (x, r):
            v.destroy()
    for ui, a in zip(problem.u, saved):
        ui.x.array[:] = a
    problem.refresh()
    rem = np.array(rem)
    return np.log2(rem[:-1] / rem[1:]), rem / (eps0 * cast(float, Ad.norm()))


def block_taylor_orders(problem: Problem, direction: Direction, eps0: float = 1e-3,
                        n: int = 4) -> dict[str, tuple[npt.NDArray[np.float64],
                                                       npt.NDArray[np.float64], float]]:
    """:func:`taylor_orders` along each unknown's part of ``direction`` alone.

    A combined direction measures the remainder against ‖J d‖, which the stiffest
    block dominates: a wrong column of a multiplier block can hide below it.  Returns
    ``{unknown name: (orders, remainders, floor)}``.  ``floor`` bounds the round-off
    of the relative remainders: a residual row is a sum of terms each at most
    ‖A‖_∞‖x‖_∞ (to first order about the state), so its evaluation errs by
    ~ε_mach ‖A‖_∞‖x‖_∞ per row and √N ε_mach ‖A‖_∞‖x‖_∞ in 2-norm; the difference
    R(x + εd) − R(x) carries two such errors, and 10 more for the summation order.
    A block the residual is linear in shows remainders below ``floor`` instead of
    orders.
    """
    if all(hasattr(d, "x") for d in direction):
        direction = owned_arrays(problem, direction)
    b, A = problem.assemble()
    x = block_vector(problem, owned_arrays(problem))
    # petsc4py's stubs: NormType's members are typed int, and norm() returns a float
    # or (NORM_1_AND_2) a pair
    size = (cast(float, A.norm(PETSc.NormType.NORM_INFINITY))  # type: ignore[arg-type]
            * cast(float, x.norm(PETSc.NormType.NORM_INFINITY))  # type: ignore[arg-type]
            * np.sqrt(x.getSize()))
    x.destroy()
    out = {}
    for k, ui in enumerate(problem.u):
        alone = [d if j == k else np.zeros_like(d)
                 for j, d in enumerate(cast("list[npt.NDArray[np.float64]]", direction))]
        dv = block_vector(problem, alone)
        Ad = A.createVecLeft()
        A.mult(dv, Ad)
        floor = 20 * np.finfo(float).eps * size / (eps0 * max(cast(float, Ad.norm()), 1e-300))
        for v in (dv, Ad):
            v.destroy()
        out[ui.name] = (*taylor_orders(problem, alone, eps0, n), floor)
    return out


def residual_floor(problem: Problem, samples: int = 3, seed: int = 0) -> float:
    """Round-off floor of ‖R‖ (2-norm) at the current state of ``problem``.

    The largest ‖R‖ over ``samples`` perturbations of every unknown by one ulp
    (x ← x(1 ± ε), random signs): the residual's own evaluation error, which
    depends on the CPU's floating-point rounding and on the sums' order.  A Newton
    residual within a few times this floor says nothing about the order of
    convergence.  The state is restored.
    """
    rng = np.random.default_rng(seed)
    saved = [u.x.array.copy() for u in problem.u]
    worst = 0.0
    try:
        for _ in range(samples):
            for u, a in zip(problem.u, saved):
                u.x.array[:] = a * (1 + np.finfo(float).eps * rng.choice((-1.0, 1.0), a.shape))
                u.x.scatter_forward()
            worst = max(worst, cast(float, problem.assemble()[0].norm()))   # its own b
    finally:
        for u, a in zip(problem.u, saved):
            u.x.array[:] = a
    return worst


def exact_tangent(orders: Sequence[float] | npt.NDArray[np.float64],
                  remainders: Sequence[float] | npt.NDArray[np.float64], floor: float,
                  min_order: float = 1.8) -> bool:
    """Whether a Taylor test shows an exact tangent.

    Second order (every observed order above ``min_order``, 1.8: the ε-range where
    round-off starts to show), or remainders at round-off (below ``floor``) that do
    not decay at first order — a wrong tangent column leaves r(ε) ∝ ε, orders 1 to
    within 0.2 however small r is; round-off leaves erratic orders — or remainders
    a million times below ``floor`` (the residual's own evaluation error): a block
    in which the residual is linear leaves only the rounding of ε J d, which may
    decay like ε (measured: 3e-16 → 3e-17 at orders 1.04, 0.89, 1.05 for the 3D
    two-body squeeze's pressure block on 2 ranks), and a wrong column that small
    is below anything the residual resolves.
    """
    orders = np.asarray(orders)
    if orders.min() > min_order:
        return True
    if np.max(remainders) < 1e-6 * floor:
        return True
    first_order = np.all(np.abs(orders - 1.0) < 0.2)
    return bool(np.max(remainders) < floor and not first_order)


def newton_is_quadratic(residuals: Sequence[float], floor: float,
                        factor: float = 10.0) -> bool:
    """Whether a Newton residual history converges quadratically down to its round-off.

    The residuals below ``factor`` × ``floor`` (:func:`residual_floor`, the residual's
    own evaluation error) are dropped: they say nothing about the order.  Of the rest,
    every observed order log(r_{k+1}/r_k)/log(r_k/r_{k−1}) must exceed 1.5, the middle
    between a linearly convergent iteration (an inexact tangent: order 1, r_{k+1}/r_k
    constant) and a quadratic one (order 2): each step is nearer the quadratic rate
    than the linear one in the logarithm of its contraction.  At least one order
    must remain (three residuals above the floor).
    """
    r = np.asarray(residuals, dtype=float)
    orders = convergence_orders(r[r > factor * floor], floor=0.0)
    return bool(orders.size and np.all(orders > 1.5))


def form_taylor_orders(R: ufl.Form, u: fem.Function, du: fem.Function, eps0: float = 1e-3,
                       n: int = 4) -> Orders:
    """Orders and relative remainders of one bare residual form ``R`` in ``u`` along ``du``.

    J = ``ufl.derivative(R, u)``, both assembled by DOLFINx (no component, no
    boundary condition); ``u`` is restored.
    """
    import ufl
    from dolfinx import fem
    from dolfinx.fem import petsc as fem_petsc

    base = u.x.array.copy()
    form_R = fem.form(R)
    A = fem_petsc.assemble_matrix(fem.form(ufl.derivative(R, u)))
    A.assemble()

    def residual() -> PETSc.Vec:
        b = fem_petsc.assemble_vector(form_R)
        b.ghostUpdate(addv=PETSc.InsertMode.ADD,  # type: ignore[arg-type]
                      mode=PETSc.ScatterMode.REVERSE)  # type: ignore[arg-type]
        return b

    b0 = residual()
    d = fem_petsc.create_vector(du.function_space)
    d.array[:] = du.x.array[:len(d.array)]
    Ad = A.createVecLeft()
    A.mult(d, Ad)
    rem: Any = []   # the remainders: a list, then its array
    for k in range(n):
        eps = eps0 * 2.0**-k
        u.x.array[:] = base + eps * du.x.array
        r = residual()
        r.axpy(-1.0, b0)
        r.axpy(-eps, Ad)
        rem.append(r.norm())
        r.destroy()
    u.x.array[:] = base
    rem = np.array(rem)
    return np.log2(rem[:-1] / rem[1:]), rem / (eps0 * cast(float, Ad.norm()))


def border_taylor_orders(border: Border, direction: Direction, eps0: float = 1e-3,
                         n: int = 4) -> dict[str, Orders]:
    """Taylor orders of a :class:`tribofx.bordered.Border`'s b, c and d at the current state.

    b = ∂R/∂δ and d = ∂G/∂δ along δ (steps ε·``eps0`` in the parameter's units),
    c = ∂G/∂x along ``direction`` (as for :func:`taylor_orders`), with the
    remainders ‖R(x, δ + ε) − R − ε b‖, |G(x, δ + ε) − G − ε d| and
    |G(x + ε dx, δ) − G − ε c·dx|.  Returns ``{"b"|"c"|"d": (orders, remainders
    relative to the linear term at ε₀)}``; unknowns and δ are restored.
    """
    problem, par = border.problem, border.parameter
    if all(hasattr(d, "x") for d in direction):
        direction = owned_arrays(problem, direction)
    saved, delta0 = [ui.x.array.copy() for ui in problem.u], par.get()
    R0 = problem.assemble()[0].copy()
    G0, d = border.value(), border.derivative()
    b, c = border.vectors()
    x0 = block_vector(problem, owned_arrays(problem))
    dx = block_vector(problem, cast("list[npt.NDArray[np.float64]]", direction))  # arrays by now
    cdx = c.dot(dx)
    rem: dict[str, list[float]] = {"b": [], "c": [], "d": []}
    r: Any   # a residual, then the remainders of one kind and their array
    for k in range(n):
        eps = eps0 * 2.0**-k
        par.set(delta0 + eps)
        r = problem.residual_at(x0)
        r.axpy(-1.0, R0)
        r.axpy(-eps, b)
        rem["b"].append(cast(float, r.norm()))
        rem["d"].append(abs(border.value() - G0 - eps * d))
        par.set(delta0)
        x = x0.copy()
        x.axpy(eps, dx)
        problem.residual_at(x).destroy()
        rem["c"].append(abs(border.value() - G0 - eps * cdx))
        for v in (x, r):
            v.destroy()
    scale = {"b": eps0 * cast(float, b.norm()), "c": eps0 * abs(cdx), "d": eps0 * abs(d)}
    for ui, a in zip(problem.u, saved):
        ui.x.array[:] = a
    problem.refresh()
    for v in (R0, b, c, x0, dx):
        v.destroy()
    out = {}
    for key, r in rem.items():
        r = np.array(r)
        with np.errstate(divide="ignore", invalid="ignore"):
            out[key] = (np.log2(r[:-1] / r[1:]), r / max(scale[key], 1e-300))
    return out


def oil_books(film: Film) -> tuple[dict[str, float], float, float]:
    """Return a JFO surface film's books, their imbalance and its bound (mm³/s).

    Returns (books of :meth:`~tribofx.interfaces.reynolds_film.ReynoldsFilm.surface_books`,
    supplied + entered − out − leak, N × atol): the transport rows tested by δp = 1
    are the fluxes through ∂S, so the imbalance is the sum of the N converged nodal
    rows, each below the stopping tolerance atol of a nodal flux.
    """
    books = film.surface_books()
    imbalance = books["supplied"] + books["entered"] - books["out"] - books["leak"]
    bound = film.Q.dofmap.index_map.size_global * film.tolerances()[film.p].atol
    return books, imbalance, bound
