"""Reciprocating pin-on-flat, both bodies elastic and worn (§5.1, Fig. 5): ``wear-reciprocating``.

An elastic plane-strain pin (width W, height H, rounded tip of radius R_tip) is
pressed by a constant normal force F (a uniform traction F/W on its top face;
its sides x = ±W/2 held laterally) onto an elastic block (length L, depth D,
top y = 0) whose bottom is moved back and forth along x with amplitude A at
speed V.  Both are neo-Hookean; Coulomb friction μ.  The pin's tip is the
slave surface, the block's top the master
(:class:`~tribofx.interfaces.TwoBodyContact`: every slave node is projected on
the current block surface).

Both surfaces wear (Archard in the dissipation form, eq. 14, nominal
coefficients K_pin and K_block): a :class:`~tribofx.interfaces.Wear` on each
side, the pin's driven by its own dissipation K⁽¹⁾ D⁽¹⁾ (eq. 17), the block's
by K⁽²⁾ D⁽¹⁾ carried to the block nodes the pin rubbed against (eq. 18); both
shape fields evolve (finite shape changes of both bodies, on their initial
meshes).  Time-scale separation (eqs. 21–23): per slow step one fast loading
cycle at the fixed worn shapes — the contact memory erased, the block at −A, a
run-in to the centre, then +A, −2A, +A — accumulates the wear increment of
every node; the average rate over the cycle (Δτ = 4A/V) drives the shape step,
explicit (θ = 0, as in the chapter) or implicit (θ = 1 by a Picard iteration of
cycles); :class:`~tribofx.stepper.Stepper`.  A slow step of Δt stands for
Δt/Δτ cycles; the run covers ``cycles`` cycles, T = cycles·Δτ.

Data: the chapter leaves them to Lengiewicz & Stupkiewicz (2012); chosen here
so that both bodies deform finitely and both wear visibly: W = H = 2 mm,
R_tip = 2 mm (a half-round tip), block 6 × 1.5 mm, E_pin = 20 MPa, E_block =
10 MPa (rubber-like: Hertz half-width 0.59 mm and peak pressure 1.1 MPa, so
strains of about 10 %), ν = 0.3, μ = 0.3, A = 0.5 mm, V = 10 mm/s, F = 1 N/mm,
K_pin = 10⁻⁴ and K_block = 5·10⁻⁵ mm³/(N·mm), 2000 cycles: gross sliding would
dissipate μF·4A = 0.6 N·mm/mm per cycle (the stick phases after each reversal
take about 13 % off), so the pin loses about 0.1 mm² per mm, a flat of about
1.5 mm on its tip, and the block half of that, a groove along the stroke.

Your own pin (``mesh_file``): a 2D gmsh ``.msh`` whose physical groups are the
case's own (:data:`tribofx.meshes.pin.NAMES`): ``contact`` (the tip, the slave
surface), ``top`` (loaded) and ``sides`` (held laterally), read and checked by
:func:`tribofx.meshes.user.read_user_mesh`.  It is moved as
:meth:`tribofx.cases.wear.WearPinCase._user_pin` moves the pin of ``wear-pin``
(its lowest tip point to y = 0, the block's top) and its x extent centred on
x = 0 (the centre of the stroke); it replaces ``W``, ``H``, ``R_tip`` and the
pin's mesh.  What the case takes from W, R_tip and n it then takes from the
mesh: W is the mesh's x extent (the stroke check L ≥ W + 2A + 1 mm), the top
traction is F/ℓ with ℓ the length of ``top`` (so that the pin carries F; ℓ = W
for the case's pin), the element size h = W/n is the mean length of the tip
facets (ρ_N = min(E_pin, E_block)/h and the block's element size 4h/3:
``mesh`` then refines nothing), and Newton's start on load-up is the approach
of :meth:`~tribofx.cases.wear.WearPinCase._user_approach` (the tip's height at
|x| = W/4, so that its middle half starts in contact, plus the pin's
compression F H/(ℓ E_pin)) instead of the Hertz approach of R_tip.  The checks
R_tip ≥ W/2 and tip height < H/2 are those of the built circular tip and do
not apply.  ``pin_width``, ``pin_height``, ``pin_top_length`` and
``contact_element_size`` report what was used (the built pin's W, H, W, W/n
without ``mesh_file``).

Results per slow step and outputs: :mod:`tribofx.cases.wear_reciprocating_run`.
"""

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from ..body import Body
from ..forms.hyperelastic import lame_parameters
from ..interfaces import TwoBodyContact, Wear
from ..meshes.block import NAMES as BLOCK_NAMES
from ..meshes.block import block_mesh
from ..meshes.pin import NAMES as PIN_NAMES
from ..meshes.pin import pin_body, tip_height
from ..meshes.user import read_user_mesh
from ..params import InputError, Param
from ..stepper import ReciprocatingCycle, Stepper
from .slow_time import check_scheme, scheme_params
from .wear import WearPinCase
from .wear_reciprocating_run import ReciprocatingRun

__all__ = ["WearReciprocatingCase"]


def _centre_on_axis(msh):
    """Translate a user's pin along x so that its x extent is centred on x = 0.

    The case's own pin is symmetric about x = 0, the centre of the block and of
    the stroke; a user's pin is put there by the midpoint of its extent (its
    sides, held laterally, at x = ±W/2).
    """
    comm, x = msh.comm, msh.geometry.x
    lo = comm.allreduce(float(np.min(x[:, 0], initial=np.inf)), op=MPI.MIN)
    hi = comm.allreduce(float(np.max(x[:, 0], initial=-np.inf)), op=MPI.MAX)
    x[:, 0] -= 0.5 * (lo + hi)


class WearReciprocatingCase(ReciprocatingRun):
    """Case ``wear-reciprocating``; see the module docstring."""

    name = "wear-reciprocating"
    doc = "elastic pin on an elastic block, reciprocating sliding, both worn (§5.1, Fig. 5)"
    params = (
        *scheme_params("explicit", "; implicit ones with the Picard iteration of cycles, "
                       "tol on the cycle-averaged shapes"),
        Param("E_pin", float, 20.0, "MPa", "Young's modulus of the pin", lower=0.0),
        Param("E_block", float, 10.0, "MPa", "Young's modulus of the block", lower=0.0),
        Param("nu", float, 0.3, "-", "Poisson's ratio of both bodies", lower=-1.0, upper=0.5),
        Param("friction", float, 0.3, "-", "Coulomb coefficient μ", lower=0.0),
        Param("K_pin", float, 1e-4, "mm^3/(N*mm)", "nominal wear coefficient of the pin (eq. 14)",
              lower=0.0),
        Param("K_block", float, 5e-5, "mm^3/(N*mm)",
              "nominal wear coefficient of the block (eq. 14)", lower=0.0, closed=True),
        Param("A", float, 0.5, "mm", "amplitude of the reciprocating motion (stroke 2A)",
              lower=0.0),
        Param("V", float, 10.0, "mm/s", "sliding speed", lower=0.0),
        Param("F", float, 1.0, "N/mm", "normal force on the pin per unit thickness", lower=0.0),
        Param("cycles", float, 2000.0, "-", "loading cycles of the run (T = cycles·4A/V)",
              lower=0.0),
        Param("dt", float, 40.0, "s", "slow time step Δt (Δt·V/(4A) cycles per step; "
              "with tol: the first step)", lower=0.0),
        Param("W", float, 2.0, "mm", "pin width", lower=0.0),
        Param("H", float, 2.0, "mm", "pin height", lower=0.0),
        Param("R_tip", float, 2.0, "mm", "tip radius", lower=0.0),
        Param("L", float, 6.0, "mm", "block length", lower=0.0),
        Param("D", float, 1.5, "mm", "block depth", lower=0.0),
        Param("mesh", int, 1, "-", "refinement: pin n × n, n = 10·2^mesh; block at 4/3 the size",
              lower=0, upper=4, closed=True),
        Param("fast_steps", int, 16, "-", "fast sub-steps per cycle (multiple of 4)", lower=4,
              upper=100000, closed=True),
        Param("max_cuts", int, 4, "-", "step halvings allowed per step", lower=0, upper=20,
              closed=True),
        Param("mesh_file", str, "", "-",
              "your own pin: a 2D gmsh .msh with physical groups contact (the tip), top "
              "(loaded by F: traction F/l, l its length) and sides (held laterally); its "
              "lowest tip point moved to y = 0 and its x extent centred on x = 0; replaces "
              "W (its x extent: L >= W + 2A + 1), H, R_tip and the pin's mesh (h = mean tip "
              "facet length: rho_N = min(E)/h, block elements 4h/3)"),
    )

    @staticmethod
    def validate(v):
        """Reject a stroke off the block, a tip lower than the pin and a step above T.

        With ``mesh_file`` the pin's width is known only once the mesh is read:
        :meth:`build` checks the stroke then (:meth:`check_stroke`); the tip
        checks are those of the built circular tip.
        """
        if not v["mesh_file"]:
            if v["R_tip"] < v["W"] / 2:
                raise InputError(f"R_tip = {v['R_tip']} mm must be >= W/2 = {v['W'] / 2} mm")
            if tip_height(v["W"] / 2, v["R_tip"]) >= 0.5 * v["H"]:
                raise InputError("the rounded tip must be lower than half the pin height")
            WearReciprocatingCase.check_stroke(v, v["W"])
        check_scheme(v)
        if v["fast_steps"] % 4:
            raise InputError(f"fast_steps = {v['fast_steps']} must be a multiple of 4")
        if v["dt"] > WearReciprocatingCase.period(v) * v["cycles"]:
            raise InputError(f"time step {v['dt']} s exceeds T = "
                             f"{WearReciprocatingCase.period(v) * v['cycles']} s")

    @staticmethod
    def check_stroke(v, W):
        """Reject a block too short for a pin of width ``W`` (mm) and the stroke 2A.

        The pin must stay on the block with 0.5 mm to spare at either end of the
        stroke: L ≥ W + 2A + 1 mm.
        """
        if v["L"] < W + 2 * v["A"] + 1.0:
            where = f" (W = {W:.6g} mm: the width of the pin in {v['mesh_file']!r})" \
                if v["mesh_file"] else ""
            raise InputError(f"block length L = {v['L']} mm must exceed W + 2A + 1 = "
                             f"{W + 2 * v['A'] + 1.0:.6g} mm{where}")

    @staticmethod
    def period(v):
        """Δτ of one cycle, 4A/V (s)."""
        return 4 * v["A"] / v["V"]

    @classmethod
    def build(cls, v, comm=MPI.COMM_WORLD, checkpoint=None):
        """Pin, block, contact, both wear interfaces, the cycle and the stepper (a dict).

        The dict also holds the pin's geometry as used: ``W`` (width), ``H``
        (height above the lowest tip point), ``top_length`` (ℓ of the traction
        F/ℓ) and ``h`` (tip element size); from the mesh with ``mesh_file``.
        """
        if v["mesh_file"]:
            msh, ft, names = read_user_mesh(v["mesh_file"], comm, 2, tuple(PIN_NAMES))
            W, h = WearPinCase._user_pin(msh, ft, names)
            cls.check_stroke(v, W)
            _centre_on_axis(msh)
            H = comm.allreduce(float(np.max(msh.geometry.x[:, 1], initial=-np.inf)),
                               op=MPI.MAX)
        else:
            n = 10 * 2 ** v["mesh"]
            W, H, h = v["W"], v["H"], v["W"] / n
            msh, ft = pin_body(W, H, v["R_tip"], n, comm)
            names = PIN_NAMES
        mu, lmbda = lame_parameters(v["E_pin"], v["nu"])
        pin = Body(msh, ft, names, "plane_strain", ("neo-hookean", {"mu": mu, "lmbda": lmbda}),
                   shape=True, aux=(v["E_pin"], 0.3), name="pin")
        # the top's length: the traction F/ℓ loads the pin with F whatever its top
        top = comm.allreduce(fem.assemble_scalar(fem.form(
            fem.Constant(msh, 1.0) * pin.ds(pin.tag("top")))), op=MPI.SUM) \
            if v["mesh_file"] else W
        load = fem.Constant(msh, 1.0)
        pin.add_traction("top", load * ufl.as_vector([0.0, -v["F"] / top]))
        pin.add_dirichlet("sides", 0.0, component=0)
        pin.add_shape_dirichlet("sides", 0)
        pin.add_shape_dirichlet("top", 1)
        hb = 4 * h / 3                       # the slave (pin) is the finer surface
        bmsh, bft = block_mesh(comm, (-v["L"] / 2, -v["D"]), (v["L"] / 2, 0.0),
                               round(v["L"] / hb), max(2, round(v["D"] / hb)))
        mu, lmbda = lame_parameters(v["E_block"], v["nu"])
        block = Body(bmsh, bft, BLOCK_NAMES, "plane_strain",
                     ("neo-hookean", {"mu": mu, "lmbda": lmbda}), shape=True,
                     aux=(v["E_block"], 0.3), name="block")
        motion = block.add_dirichlet("bottom", np.zeros(2))
        for name, c in (("bottom", 0), ("bottom", 1), ("sides", 0)):
            block.add_shape_dirichlet(name, c)
        contact = TwoBodyContact(pin, "contact", block, "top",
                                 rho_n=min(v["E_pin"], v["E_block"]) / h, friction=v["friction"])
        theta = 0.0 if v["scheme"] == "explicit" else 1.0
        mu_f, sch = v["friction"], "bdf2" if v["scheme"] == "bdf2" else "theta"
        wear_pin = Wear(contact.wear_surface("slave"), k=v["K_pin"] * mu_f, theta=theta,
                        averaged=True, name="wear_pin", scheme=sch)
        wear_block = Wear(contact.wear_surface("master"), k=v["K_block"] * mu_f, theta=theta,
                          averaged=True, name="wear_block", scheme=sch)

        def drive(position):
            """Move the block's bottom to ``position``; the block translated as predictor."""
            block.u.x.array.reshape(-1, 2)[:, 0] += position - float(motion.value[0])
            motion.value[0] = position

        cycle = ReciprocatingCycle(contact, 2 * v["A"], v["fast_steps"], v["V"], drive=drive,
                                   force=lambda: block.reaction("bottom", 0))
        stepper = Stepper([pin, block, contact, wear_pin, wear_block], [wear_pin, wear_block],
                          cycle=cycle, parameters=[load, motion], max_cuts=v["max_cuts"],
                          checkpoint=checkpoint, name="wear_reciprocating",
                          problem_kw={"max_it": 40})
        return {"pin": pin, "block": block, "contact": contact, "wear_pin": wear_pin,
                "wear_block": wear_block, "stepper": stepper, "load": load, "motion": motion,
                "cycle": cycle, "W": W, "H": H, "top_length": top, "h": h}

