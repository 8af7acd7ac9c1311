"""Solution paths of the coated layer under a rigid cylinder (chapter §8.2): load and speed.

:class:`CylinderPaths` is a base class of
:class:`tribofx.cases.ehl.EHLCylinderLayerCase`: the load W reached by the cylinder
position (a secant on 1/W, nearly linear in the position of a rigid film, held by
:class:`tribofx.held_response.HeldResponse` while an outer continuation marches
the load with step cutting), and the speed continuation at the final load (a
geometric march in U with the penalty, SUPG and tolerance scales following U).
"""

from ..continuation import ConstantParameter, Continuation
from ..held_response import HeldResponse
from ..references import rigid_clearance

__all__ = ["CylinderPaths"]


class CylinderPaths:
    """Solution paths of the coated layer under a rigid cylinder (chapter §8.2): load and speed."""

    @classmethod
    def load_control(cls, run, v, on_step=None, verbose=False, record=None, on_accept=None):
        """Load control by the cylinder position: (outer load march, inner position search).

        The inner secant on 1/W (linear in s for a rigid film, s = 2.45 μUR/W, the
        first update) finds the position s at which the film carries the held
        load; the outer march steps
        the load with step cutting.  ``on_step()`` runs at every converged load,
        then ``on_accept()`` (a checkpoint); ``record`` receives the Newton
        iterations of the trials of each load.
        """
        _, film, problem = run
        inner = Continuation(problem, ConstantParameter(film.counterpart.offset, 1),
                             response=lambda: -1 / film.force()[1], rtol=1e-6, max_trials=30,
                             verbose=verbose)
        held = HeldResponse(inner, 0.0, transform=lambda W: 1 / W, slope=cls.slope(run, v))

        def response():
            if on_step is not None:
                on_step()
            if on_accept is not None:
                on_accept()
            return held.target

        return Continuation(held, held, response=response, record=record), inner

    @staticmethod
    def slope(run, v):
        """d(1/W)/ds = 1/(2.45 μUR) of the rigid film at the current speed (1/(N·mm⁻¹·mm))."""
        U = run[0].velocity.value
        return lambda W: 1 / rigid_clearance(1.0, v["mu"], U[0], v["R"])

    @classmethod
    def set_speed(cls, run, v, U):
        """Sliding speed U (mm/s) with the penalty, SUPG and tolerance scales that follow it."""
        layer, film, _ = run
        layer.velocity.value[0] = U
        h_r, p_s, eps = cls.scales(v, U=U)
        film.set_scales(p_c=p_s, eps=eps, film_scale=h_r, speed_scale=U)

    @classmethod
    def speed_sweep(cls, run, v, inner, W, speeds, on_speed=None, record=None, start=0,
                    increments=None, on_accept=None):
        """Continuation in the sliding speed at the load W (N/mm) reached last by ``inner``.

        Each speed of ``speeds[start:]`` (mm/s) is reached by a geometric march (a
        failed step is cut in log U) with the load held by the cylinder position;
        penalty, SUPG and tolerance scales follow U.  ``on_speed()`` runs after
        every converged speed step, then ``on_accept(j, march)`` (j: the index of
        the speed marched to).  ``increments``: those of an interrupted march to
        ``speeds[start]`` (a resumed run).
        """
        layer = run[0]
        held = HeldResponse(inner, W, transform=lambda W: 1 / W,
                            slope=cls.slope(run, v))
        at = {"j": start}

        def response():
            if on_speed is not None:
                on_speed()
            if on_accept is not None:
                on_accept(at["j"], sweep)

        sweep = Continuation(held, ConstantParameter(
            layer.velocity, 0, on_set=lambda U: cls.set_speed(run, v, U)),
            response=response, record=record)
        for j in range(start, len(speeds)):
            at["j"] = j
            sweep.march(speeds[j], predictor=False, geometric=True,
                        increments=increments if j == start else None)
