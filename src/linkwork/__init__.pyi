"""The types of the package's names (loaded lazily by ``__init__.py``), for type checkers and IDEs."""

from linkwork.api import balance as balance
from linkwork.api import bolt_speed as bolt_speed
from linkwork.api import compile as compile
from linkwork.api import dynamics as dynamics
from linkwork.api import forces as forces
from linkwork.api import impact as impact
from linkwork.api import kinematics as kinematics
from linkwork.api import parameters as parameters
from linkwork.api import reduced as reduced
from linkwork.api import simulate as simulate
from linkwork.api import simulate_blows as simulate_blows
from linkwork.api import size as size
from linkwork.design import optimize as optimize
from linkwork.design import sweep as sweep
from linkwork.examples import load_example as example
from linkwork.examples import resolve as load
from linkwork.impulse import rocker_impact as rocker_impact
from linkwork.kinetostatics.reaction_forces import Forces as Forces
from linkwork.kinetostatics.reaction_forces import forces_of as forces_of
from linkwork.motion.kinematic_analysis import Kinematics as Kinematics
from linkwork.spec.builder import MechanismBuilder as MechanismBuilder
from linkwork.spec.reader import from_dict as from_dict
from linkwork.spec.reader import loads as loads
from linkwork.spec.schema import Spec as Spec
from linkwork.structure.model import AssurGroup as AssurGroup
from linkwork.structure.model import Mechanism as Mechanism
from linkwork.structure.model import Structure as Structure
from linkwork.synthesis import synthesize as synthesize

__version__: str
__all__ = [
    "__version__",
    "load",
    "loads",
    "from_dict",
    "Spec",
    "MechanismBuilder",
    "compile",
    "Mechanism",
    "Structure",
    "AssurGroup",
    "example",
    "kinematics",
    "Kinematics",
    "parameters",
    "forces",
    "forces_of",
    "Forces",
    "bolt_speed",
    "balance",
    "size",
    "reduced",
    "dynamics",
    "simulate",
    "rocker_impact",
    "impact",
    "simulate_blows",
    "sweep",
    "optimize",
    "synthesize",
]

def __dir__() -> list[str]: ...
