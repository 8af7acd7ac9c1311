"""The one exception of bad user input, shared by the mesh readers and the core.

Defined here, in the package of the mesh builders, so that ``meshes`` imports
nothing of the core; :mod:`tribofx.params` re-exports it as
``tribofx.params.InputError``, which the CLI turns into exit status 2.
"""

__all__ = ["InputError"]


class InputError(ValueError):
    """Bad user input (unknown case or key, wrong type, value out of range, bad mesh file)."""
