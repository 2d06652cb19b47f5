"""Mechanism descriptions: the file format, loading, validation and the builder."""

from linkwork.spec.builder import MechanismBuilder
from linkwork.spec.reader import from_dict, load, loads
from linkwork.spec.schema import Drive, Frame, Joint, Link, Spec, Units

__all__ = ["Drive", "Frame", "Joint", "Link", "MechanismBuilder", "Spec", "Units", "from_dict", "load", "loads"]
