"""Shared matplotlib set-up of the plots (Agg backend, imported lazily)."""

__all__ = ["pyplot"]


def pyplot():
    """Return ``matplotlib.pyplot`` with the non-interactive Agg backend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt
