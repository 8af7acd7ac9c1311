"""The past of a transient film: its states at t_n and t_{n−1} and the weights of its rates.

A steady film (chapter §6) has no past.  :meth:`tribofx.interfaces.Film.transient`
gives it a :class:`FilmHistory`, the part that holds what the backward
differences of :mod:`tribofx.forms.squeeze` need:

* the fluid content c = ρ θ h J_S w at the quadrature points of Γ_l (or, for a
  lumped JFO film, at the nodes of each cell: discontinuous P1);
* the trace u_s on Γ_l and the body's displacement u at their nodes;
* the countersurface's rigid translation (if it has one);
* the weights 1/Δt, c₀, c₁ of the rate (c₀ (f − fⁿ) + c₁ (fⁿ − fⁿ⁻¹))/Δt and the
  previous step Δt_prev: backward Euler (``scheme=IMPLICIT``, c₀ = 1, c₁ = 0) or
  variable-step BDF2 (``scheme=BDF2``, :func:`tribofx.forms.wear.bdf2_coefficients`,
  started by one backward-Euler step).

Between steps (before the first) 1/Δt is 0, so the rates vanish and a steady
solve gives the initial state.  Every field here is part of the film's state
(:meth:`fields`): a checkpoint or a restored trial step takes them along.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import basix.ufl
import numpy as np
from dolfinx import fem

from ..forms import wear as wf
from ..scheme import Scheme

if TYPE_CHECKING:
    from dolfinx import mesh as dmesh

__all__ = ["FilmHistory"]


class FilmHistory:
    """States t_n, t_{n−1} of a transient film and the weights of its backward differences.

    Args:
        scheme: the implicit :class:`tribofx.scheme.Scheme` of the rates (euler or bdf2).
        content_space: the space of the content c (quadrature or discontinuous P1).
        trace_space: the space of the trace u_s on Γ_l.
        body_space: the body's displacement space.
        offset: the countersurface's rigid translation (a ``fem.Constant``), or None.
        bulk_mesh, sub_mesh: the body's mesh (the weights live there) and Γ_l's
            submesh (the translation's history lives there).
        name: the film's name (the names of the fields).
    """

    def __init__(self, scheme: Scheme | str, content_space: fem.FunctionSpace,
                 trace_space: fem.FunctionSpace, body_space: fem.FunctionSpace,
                 offset: fem.Constant | None, bulk_mesh: dmesh.Mesh, sub_mesh: dmesh.Mesh,
                 name: str) -> None:
        self.scheme = Scheme.of(scheme)
        pair = ("n", "nm1")
        self.content = [fem.Function(content_space, name=f"{name}_content_{k}") for k in pair]
        self.trace = [fem.Function(trace_space, name=f"{name}_trace_{k}") for k in pair]
        self.displacement = [fem.Function(body_space, name=f"{name}_body_u_{k}") for k in pair]
        gdim = bulk_mesh.geometry.dim
        self.offset = offset
        self.offset_history = [fem.Constant(sub_mesh, np.zeros(gdim)) for _ in pair]
        self.weights = [fem.Constant(bulk_mesh, 0.0) for _ in range(3)]   # 1/Δt, c₀, c₁
        self.dt_prev = fem.Constant(bulk_mesh, 0.0)

    def fields(self) -> list[fem.Function | fem.Constant]:
        """Return the histories, the weights and Δt_prev: the part of the film's state it holds."""
        return (self.content + self.trace + self.displacement + list(self.weights)
                + [self.dt_prev] + self.offset_history)

    def advance(self, dt: float, trace: fem.Function, displacement: fem.Function,
                content: fem.Expression) -> None:
        """Move the histories on (t_{n−1} ← t_n ← the converged state) and weight a step Δt.

        ``trace`` and ``displacement``: the converged u_s and u; ``content``: the
        ``fem.Expression`` of the converged content.  BDF2 with ω = Δt/Δt_prev; the
        first step, and every step of backward Euler, has c₀ = 1, c₁ = 0.
        """
        for (f_n, f_nm1), live in ((self.content, None), (self.trace, trace),
                                   (self.displacement, displacement)):
            f_nm1.x.array[:] = f_n.x.array
            if live is None:
                f_n.interpolate(content)
            else:
                f_n.x.array[:] = live.x.array
            f_n.x.scatter_forward()
        if self.offset is not None:
            self.offset_history[1].value[:] = self.offset_history[0].value
            self.offset_history[0].value[:] = self.offset.value
        prev = float(self.dt_prev.value)
        c0, c1 = (1.0, 0.0) if not self.scheme.bdf2 or prev <= 0 \
            else wf.bdf2_coefficients(dt / prev)
        for c, v in zip(self.weights, (1.0 / dt, c0, c1)):
            c.value = v  # type: ignore[assignment]  # dolfinx types it NDArray
        self.dt_prev.value = float(dt)  # type: ignore[assignment]  # (a float works)


def content_space(sub: dmesh.Mesh, degree: int, lumped: bool) -> fem.FunctionSpace:
    """Space of a transient film's content: Gauss points of ``degree``, or DG1 when lumped."""
    if lumped:
        return fem.functionspace(sub, ("DG", 1))
    return fem.functionspace(sub, basix.ufl.quadrature_element(sub.basix_cell(), (),
                                                               degree=degree))
