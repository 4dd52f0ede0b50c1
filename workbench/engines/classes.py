"""The one map from the loaders' object classes to the RSS engines' types and dynamics.

``loaders.records.ObjectClass`` is what a log says an object is; ``rss.params.ObjectClass``
names the dynamics table it is checked with (same names); ``rss.model.ObjectType`` is the
ad-rss object type (pedestrian, bicycle, or other vehicle for every motor vehicle and
unknown objects).
"""

from __future__ import annotations

from loaders.records import ObjectClass as FrameClass
from rss.model import ObjectType
from rss.params import ObjectClass

__all__ = ["ADRSS_TYPES", "adrss_type", "dynamics_class"]

#: ad-rss object type of each loader class that is not an "other vehicle".
ADRSS_TYPES = {FrameClass.PEDESTRIAN: ObjectType.Pedestrian, FrameClass.BICYCLE: ObjectType.Bicycle}


def adrss_type(object_class: FrameClass) -> ObjectType:
    """ad-rss object type of a loader class (pedestrian, bicycle, else other vehicle)."""
    return ADRSS_TYPES.get(object_class, ObjectType.OtherVehicle)


def dynamics_class(object_class: FrameClass) -> ObjectClass:
    """The ``--rss-params`` table whose dynamics an object of this class is checked with."""
    return ObjectClass(object_class.label)
