"""Structure: the compiled model, Assur groups, assembly."""

from linkwork.structure.compile import compile
from linkwork.structure.model import AssurGroup, Mechanism, Structure

__all__ = ["AssurGroup", "Mechanism", "Structure", "compile"]
