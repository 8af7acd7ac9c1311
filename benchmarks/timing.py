"""Accumulated wall time of wrapped callables, for the benchmarks' splits of an iteration."""

import time

__all__ = ["Timer"]


class Timer:
    """Accumulated wall time of wrapped callables (``total[name]``, s)."""

    def __init__(self):
        self.total = {}

    def wrap(self, name, fn):
        """Return ``fn`` timed under ``name``."""
        def timed(*args, **kw):
            t0 = time.perf_counter()
            try:
                return fn(*args, **kw)
            finally:
                self.total[name] = self.total.get(name, 0.0) + time.perf_counter() - t0
        return timed

    def time_split(self, interface, methods, problem):
        """Time ``methods`` of ``interface`` and the problem's UFL assembly (residual, Jacobian)."""
        for name in methods:
            setattr(interface, name, self.wrap(name, getattr(interface, name)))
        for attr in ("_assemble_residual", "_assemble_jacobian"):
            fn, args, kw = getattr(problem, attr)
            setattr(problem, attr, (self.wrap(attr, fn), args, kw))
