"""Interfaces on a body's boundary: contact, lubricating film, wear.

Each interface owns its unknowns on a facet submesh, its residual contributions
(built only by :mod:`tribofx.forms`), the data it refreshes before each assembly
and its outputs; it follows the component protocol of :mod:`tribofx.problem`.
"""

from .contact import Contact
from .film import Film, RigidFilm
from .wear import Wear

__all__ = ["Contact", "Film", "RigidFilm", "Wear"]
