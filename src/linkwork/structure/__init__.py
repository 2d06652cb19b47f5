"""Structure: the compiled model, Assur groups, assembly."""

from linkwork.structure.compile import structural_model
from linkwork.structure.model import AssurGroup, Mechanism, Structure

__all__ = ["AssurGroup", "Mechanism", "Structure", "structural_model"]
