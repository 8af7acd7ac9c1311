"""Registry of runnable cases: ``tribofx run CASE``.

A case is a module of this package named for it (``ehl_ball`` is ``ehl-ball``):
it declares ``name``, ``doc``, ``resumable`` and ``Params`` (a frozen dataclass of
its parameters, :class:`tribofx.params.CaseParams`) and defines
``validate(v)``, ``build(v)``, ``run(v, record, progress, verbose, ...)``,
``progress_total(v)`` (the steps its progress bar counts),
``vtx_fields(model)`` and ``plot(profile, outdir)`` (see
:func:`tribofx.runner.run_case`).  The other modules here are helpers grouped by
subject (``film_setup``, ``slow_time``, ``rough_contact``, ``curved_bodies``,
``user_pin``); no case imports another.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from . import (
    contact_ironing,
    contact_patch,
    contact_two_cylinders,
    ehl_ball,
    ehl_cylinder_layer,
    ehl_oring,
    ehl_squeeze,
    ehl_two_cylinders,
    hertz,
    reynolds_cylinder,
    reynolds_slider,
    stribeck,
    wear_ball_flat,
    wear_ball_halfspace,
    wear_lubricated,
    wear_pin,
    wear_reciprocating,
)

if TYPE_CHECKING:
    from types import ModuleType

__all__ = ["CASES", "get_case"]

CASES = {c.name: c for c in (hertz, reynolds_slider, reynolds_cylinder, ehl_cylinder_layer,
                             wear_pin, wear_ball_halfspace, ehl_ball, wear_ball_flat, ehl_oring,
                             ehl_squeeze, ehl_two_cylinders, contact_two_cylinders,
                             contact_patch, contact_ironing, wear_reciprocating, stribeck,
                             wear_lubricated)}


def get_case(name: str) -> ModuleType:
    """Return the case module called ``name`` or raise :class:`tribofx.params.InputError`."""
    from ..params import InputError

    if name not in CASES:
        raise InputError(f"unknown case {name!r}; available: {', '.join(sorted(CASES))}")
    return CASES[name]
