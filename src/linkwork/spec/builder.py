"""Build a mechanism description in Python.

The builder writes the same plain data a YAML file holds and validates it
by the same pass, so a file and a builder script give equal specs::

    b = MechanismBuilder("four-bar", units={"length": "mm"})
    b.frame(points={"O": (0, 0), "D": (300, 0)})
    b.link("crank", ends=("O", "A"), length=100)
    b.link("coupler", ends=("A", "B"), length=350)
    b.link("rocker", ends=("D", "B"), length=250)
    b.revolute("O", "frame", "crank").revolute("A", "crank", "coupler")
    b.revolute("B", "coupler", "rocker").revolute("D", "frame", "rocker")
    b.drive("O", speed="60 rpm").hint("B", 280, 240)
    spec = b.build()
"""

from __future__ import annotations

import copy
from typing import Any

from linkwork.spec.reader import from_dict
from linkwork.spec.schema import Spec


def _plain(value: Any) -> Any:
    if isinstance(value, tuple | list):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if hasattr(value, "tolist") and callable(value.tolist):  # numpy arrays and scalars
        return value.tolist()
    return value


def _some(**fields: Any) -> dict[str, Any]:
    return {k: _plain(v) for k, v in fields.items() if v is not None}


class MechanismBuilder:
    """Collects links, joints, drives and hints; :meth:`build` validates them.

    Every value may be a number (in the declared ``units``) or a string with
    a unit, exactly as in a file.

    Parameters
    ----------
    name : str or None, default None
        The mechanism's name (the file's ``name:``).
    units : dict of str to str or None, default None
        The units of bare numbers by kind, as the file's ``units:`` (``{"length": "mm"}``); SI where not given.
    description : str or None, default None
        A sentence on what the mechanism is.
    gravity : float or str or None, default None
        The acceleration of gravity along -y (a number in the declared units, or ``"9.81 m/s^2"``); None: the
        file's default, 9.81 m/s^2.

    Examples
    --------
    A four-bar in millimetres, the same description as a file gives:

    >>> import linkwork as lw
    >>> b = lw.MechanismBuilder("four-bar", units={"length": "mm"})
    >>> b = b.frame(points={"O": (0, 0), "D": (300, 0)})
    >>> b = b.link("crank", ends=("O", "A"), length=100).link("coupler", ends=("A", "B"), length=350)
    >>> b = b.link("rocker", ends=("D", "B"), length=250)
    >>> b = b.revolute("O", "frame", "crank").revolute("A", "crank", "coupler")
    >>> b = b.revolute("B", "coupler", "rocker").revolute("D", "frame", "rocker")
    >>> spec = b.drive("O", speed="60 rpm").hint("B", 280, 240).build()
    >>> lw.compile(spec).structure.formula
    'I(0,1) -> II(2,3)'
    """

    def __init__(
        self,
        name: str | None = None,
        *,
        units: dict[str, str] | None = None,
        description: str | None = None,
        gravity: float | str | None = None,
    ) -> None:
        self._data: dict[str, Any] = _some(name=name, description=description, units=units, gravity=gravity)
        self._data.update(links={}, joints={}, drives=[])

    def frame(self, points: dict[str, Any] | None = None, *, mass: Any = None, com: Any = None) -> MechanismBuilder:
        """Frame points (global coordinates), and the frame's mass and centre of mass."""
        frame = self._data.setdefault("frame", {})
        frame.setdefault("points", {}).update(_plain(points or {}))
        frame.update(_some(mass=mass, com=com))
        return self

    def link(
        self,
        name: str,
        *,
        ends: tuple[str, str] | None = None,
        length: Any = None,
        points: dict[str, Any] | None = None,
        mass: Any = None,
        com: Any = None,
        inertia: Any = None,
        inertia_about: str | None = None,
    ) -> MechanismBuilder:
        """A moving link; see :class:`~linkwork.spec.schema.Link`."""
        self._data["links"][name] = _some(
            ends=ends, length=length, points=points, mass=mass, com=com, inertia=inertia, inertia_about=inertia_about
        )
        return self

    def revolute(self, name: str, *links: str, point: str | None = None) -> MechanismBuilder:
        """A revolute pair (a compound hinge with three or more links)."""
        self._data["joints"][name] = _some(type="revolute", links=list(links), point=point)
        return self

    def prismatic(
        self, name: str, guide: str, slider: str, *, through: Any, axis: Any, point: str | None = None
    ) -> MechanismBuilder:
        """A prismatic pair: ``slider`` moves along a line of ``guide``."""
        self._data["joints"][name] = _some(
            type="prismatic", links=[guide, slider], point=point, through=through, axis=axis
        )
        return self

    def pin_in_slot(
        self, name: str, slot: str, pin: str, *, through: Any, axis: Any, point: str | None = None
    ) -> MechanismBuilder:
        """A pin of link ``pin`` moving in a straight slot of link ``slot`` (a higher pair)."""
        self._data["joints"][name] = _some(
            type="pin-in-slot", links=[slot, pin], point=point, through=through, axis=axis
        )
        return self

    def drive(
        self,
        joint: str,
        *,
        speed: Any = None,
        direction: str | None = None,
        angle: Any = None,
        position: Any = None,
    ) -> MechanismBuilder:
        """Drive a joint; ``angle``/``position`` is its value in the assembly pose."""
        self._data["drives"].append(
            _some(joint=joint, speed=speed, direction=direction, angle=angle, position=position)
        )
        return self

    def hint(self, point: str, x: Any, y: Any) -> MechanismBuilder:
        """Approximate global position of a moving point in the assembly pose."""
        self._data.setdefault("hints", {})[point] = _plain([x, y])
        return self

    def force(
        self, name: str, at: str, *, force: Any = None, magnitude: Any = None, direction: Any = None, angle: Any = None
    ) -> MechanismBuilder:
        """A force at the point ``at`` (``link.point``): ``force=(Fx, Fy)``, or ``magnitude`` along
        ``direction`` (a table with ``angle``); see :class:`~linkwork.spec.schema.Load`."""
        self._data.setdefault("loads", {})[name] = _some(
            type="force", at=at, force=force, magnitude=magnitude, direction=direction, angle=angle
        )
        return self

    def moment(self, name: str, on: str, moment: Any, *, angle: Any = None) -> MechanismBuilder:
        """A moment on the link ``on``, constant or a table against the crank ``angle``."""
        self._data.setdefault("loads", {})[name] = _some(type="moment", on=on, moment=moment, angle=angle)
        return self

    def process(
        self, name: str, tools: list[str], *, axis: Any, workpiece: Any, penetration: Any, force: Any
    ) -> MechanismBuilder:
        """A technological load of a workpiece on one or two tools; see :class:`~linkwork.spec.schema.Load`."""
        self._data.setdefault("loads", {})[name] = _some(
            type="process", tools=tools, axis=axis, workpiece=workpiece, penetration=penetration, force=force
        )
        return self

    def spring(
        self, name: str, between: tuple[str, str], stiffness: Any, *, free_length: Any = None, preload: Any = None
    ) -> MechanismBuilder:
        """A linear spring between two points (``link.point``, a frame point by its name), with its
        ``free_length`` or its ``preload`` (tension in the assembly pose)."""
        self._data.setdefault("loads", {})[name] = _some(
            type="spring", between=list(between), stiffness=stiffness, free_length=free_length, preload=preload
        )
        return self

    def damper(self, name: str, between: tuple[str, str], damping: Any) -> MechanismBuilder:
        """A linear damper between two points: a force ``damping`` times the rate of change of their distance."""
        self._data.setdefault("loads", {})[name] = _some(type="damper", between=list(between), damping=damping)
        return self

    def torsion_spring(self, name: str, joint: str, stiffness: Any, free_angle: Any) -> MechanismBuilder:
        """A torsion spring in a revolute ``joint``, free at the relative turn ``free_angle`` of its links."""
        self._data.setdefault("loads", {})[name] = _some(
            type="torsion_spring", joint=joint, stiffness=stiffness, free_angle=free_angle
        )
        return self

    def machine(
        self,
        motor: dict[str, Any],
        *,
        gear: dict[str, Any] | None = None,
        flywheel: dict[str, Any] | None = None,
        delta: float | None = None,
    ) -> MechanismBuilder:
        """The drive for machine dynamics: ``motor`` (``type`` and its fields), ``gear`` (``ratio``,
        ``efficiency``), ``flywheel`` (``inertia``, ``on``); see :class:`~linkwork.spec.schema.Machine`."""
        self._data["machine"] = _some(motor=motor, gear=gear, flywheel=flywheel, delta=delta)
        return self

    def drawing(self, positions: list[int]) -> MechanismBuilder:
        """The positions (0 to 11) whose plans are drawn; see :class:`~linkwork.spec.schema.Drawing`."""
        self._data["drawing"] = {"positions": list(positions)}
        return self

    def to_dict(self) -> dict[str, Any]:
        """The plain data, as it would stand in a YAML file."""
        return copy.deepcopy(self._data)

    def build(self) -> Spec:
        """Validate and return the spec; raises SpecError listing every problem."""
        return from_dict(self.to_dict())
