"""The slow-time parameters of the wear cases: the scheme and its error control.

Every wear case (``wear-pin``, ``wear-ball-flat``, ``wear-ball-halfspace``,
``wear-reciprocating``, ``wear-lubricated``) takes ``scheme`` (explicit θ = 0,
implicit θ = 1, or the second-order BDF2 of :mod:`tribofx.bdf2`) and ``tol``, the
error control of :class:`tribofx.step_control.ErrorControl` (mm; 0: the fixed
step ``dt``, else ``dt`` is the first step) with ``tol_per``: ``unit_step`` (the
steps' estimates add up to tol) or ``step`` (each step's estimate within tol), and
``controller``: the step-size rule, elementary (``i``) or Gustafsson's PI (``pi``).
:func:`step_controller` turns them into the step controller of the run.
"""

from ..params import InputError, Param
from ..step_control import ERROR_MEASURES, STEP_RULES, ErrorControl, FixedStep

__all__ = ["SCHEMES", "check_scheme", "scheme_params", "step_controller"]

SCHEMES = ("explicit", "implicit", "bdf2")


def scheme_params(default="implicit", note="", filtered=False):
    """Return ``scheme``, ``tol``, ``tol_per`` and ``controller`` (``note`` ends scheme's help).

    ``filtered``: also ``error_filter`` (a case whose wear step is one monolithic
    Newton problem, :func:`tribofx.error_filter.filtered_defect`).
    """
    extra = (Param("error_filter", bool, False, "-",
                   "tol: filter each step's estimate through the step's implicit operator "
                   "(the error wear damps within the step is not charged)"),) if filtered else ()
    return (Param("scheme", str, default, "-",
                  "slow-time scheme: explicit (θ=0), implicit (θ=1) or bdf2 (second order, "
                  f"started by one implicit step){note}", choices=SCHEMES),
            Param("tol", float, 0.0, "mm",
                  "scheme=bdf2: error control, each step's estimate held at tol·Δt/T so "
                  "that they add up to tol (tol_per=step: at tol; dt: the first step); 0: "
                  "the fixed step dt",
                  lower=0.0, closed=True),
            Param("tol_per", str, "unit_step", "-",
                  "tol per unit_step (the steps' estimates add up to tol over T) or per "
                  "step (each step's estimate within tol, as ODE codes: for wear that "
                  "damps its own errors, e.g. wear-ball-flat)", choices=ERROR_MEASURES),
            Param("controller", str, "i", "-",
                  "tol: the step-size rule, elementary i (the last estimate) or pi "
                  "(Gustafsson's proportional-integral rule: the last two)",
                  choices=STEP_RULES), *extra)


def step_controller(v, dt):
    """Return the step controller of a run: the fixed step ``dt`` (s), or error control.

    Error control (``tol`` > 0) starts at ``dt``.
    """
    if not v["tol"]:
        return FixedStep(dt)
    return ErrorControl(dt, v["tol"], per=v["tol_per"], rule=v["controller"],
                        filtered=bool(v.get("error_filter", False)))


def check_scheme(v):
    """One-line error for tol > 0 without bdf2, or a filter or PI controller without tol."""
    if v["tol"] > 0 and v["scheme"] != "bdf2":
        raise InputError("tol > 0 (error control) needs scheme=bdf2")
    if v.get("error_filter") and not v["tol"] > 0:
        raise InputError("error_filter filters the estimates of the error control: set tol > 0")
    if v["controller"] != "i" and not v["tol"] > 0:
        raise InputError("controller chooses the steps of the error control: set tol > 0")
