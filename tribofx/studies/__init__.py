"""Studies over the cases: wear schemes against Δt, their stability, EHL mesh convergence.

A study drives a case's model; no case imports a study.  A study that ``tribofx
run`` starts (``wear-pin --set study=dt``) is a module with ``run(params, record,
progress, verbose)`` and ``progress_total(params)``, found by :func:`study_of`.

* :mod:`.wear_dt_study`: the Fig. 4 error of explicit, implicit and BDF2 wear against Δt.
* :mod:`.wear_stability`: the explicit scheme's critical step on the ball on a flat.
* :mod:`.ehl_convergence`: the film's convergence under mesh refinement (cylinder on a layer).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from . import wear_dt_study

if TYPE_CHECKING:
    from types import ModuleType

    from ..params import CaseParams

__all__ = ["study_of"]

# (case, value of its ``study`` parameter) -> the study module that runs it
_RUNNABLE = {("wear-pin", "dt"): wear_dt_study}


def study_of(case: str, values: CaseParams) -> ModuleType | None:
    """Return the study ``tribofx run case`` runs for ``values`` (None: the case runs itself)."""
    return _RUNNABLE.get((case, values.as_dict().get("study", "none")))
