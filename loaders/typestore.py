"""Typestores with the AV message types the ROS core stores lack.

rosbags' stores hold only the ROS core packages. For *writing* sample logs and for reading
old ROS 2 bags that carry no message definitions, we register the CARLA
(``derived_object_msgs``), Autoware (``autoware_perception_msgs``, ``autoware_planning_msgs``,
``autoware_auto_perception_msgs``, ``autoware_auto_planning_msgs``), Autoware.AI
(``autoware_msgs`` objects), ``radar_msgs`` tracks, ``jsk_recognition_msgs`` boxes,
``vision_msgs`` 4.x and (for ROS 1, whose store lacks it) ``tf2_msgs/TFMessage`` types
from the ``.msg`` files in ``loaders/msgs/``. Their field layout follows the upstream
interface definitions; files are named ``<package>__<Type>.msg``. Reading a log never needs
this: ROS 1 bags and MCAP files embed their definitions and rosbags' ``AnyReader`` builds the
types itself.
"""

from __future__ import annotations

import functools
import re
from importlib import resources
from typing import TYPE_CHECKING, Any

from rosbags.typesys import Stores, get_types_from_msg, get_typestore
from rosbags.typesys.base import TypesysError

if TYPE_CHECKING:
    from rosbags.typesys.store import Typestore

__all__ = ["CUSTOM_MSGTYPES", "check_definitions", "typestore"]


def _custom_types() -> dict[str, object]:
    types: dict[str, object] = {}
    for entry in sorted(resources.files("loaders.msgs").iterdir(), key=lambda e: e.name):
        if not entry.name.endswith(".msg"):
            continue
        package, name = entry.name.removesuffix(".msg").split("__")
        types.update(get_types_from_msg(entry.read_text(), f"{package}/msg/{name}"))
    return types


#: Message types we register on top of the ROS core stores.
CUSTOM_MSGTYPES: tuple[str, ...] = tuple(
    sorted(t for t in _custom_types() if not t.startswith(("unique_identifier_msgs/", "tf2_msgs/")))
)


#: A name rosbags can turn into Python: its grammar admits a leading digit, Python does not.
_PYTHON_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def check_definitions(types: dict[str, Any]) -> dict[str, Any]:
    """Refuse message definitions whose names cannot become Python before rosbags compiles them.

    rosbags' ``Typestore.register`` writes the parsed definitions as Python source (one
    dataclass per type) and compiles it. Its msg grammar limits names to letters, digits,
    ``_`` and ``/``, so nothing but names reaches that source; a name starting with a digit
    (``MSG: 2d_msgs/Point``) still makes the source unparsable (``SyntaxError``). This check
    names the offending type or field instead, and keeps anything but well-formed
    identifiers out of the compiled source.

    Args:
        types: ``get_types_from_msg``'s result: type name -> (constants, fields).

    Returns:
        ``types`` unchanged.

    Raises:
        TypesysError: A type, field or constant name is not a Python identifier.
    """
    for name, (consts, fields) in types.items():
        names = [("type", segment) for segment in name.split("/")]
        names += [("field", str(f[0])) for f in fields] + [("constant", str(c[0])) for c in consts]
        for what, value in names:
            if not _PYTHON_NAME.fullmatch(value):
                msg = f"message type {name!r}: {what} name {value!r} is not a Python name"
                raise TypesysError(msg)
    return types


@functools.cache
def typestore(ros_version: int = 2) -> Typestore:
    """Return a typestore (ROS 2 Humble or ROS 1 Noetic) with the AV types registered.

    Args:
        ros_version: 1 for ROS 1 Noetic (bags), 2 for ROS 2 Humble (MCAP, rosbag2).

    Returns:
        A cached typestore; do not register further types on it.
    """
    store = get_typestore(Stores.ROS1_NOETIC if ros_version == 1 else Stores.ROS2_HUMBLE)
    # core types the store already has (UUID, TFMessage in ROS 2) keep the store's definition
    types = {name: t for name, t in _custom_types().items() if name not in store.types}
    store.register(types)  # type: ignore[arg-type]
    return store
