"""The one map from the loaders' object classes to the RSS engines' types and dynamics.

``loaders.records.ObjectClass`` is the one object class: what a log says an object is.
The pure engines cannot import the loaders (import-linter layers), so they have their own
keys: ``rss.params.ObjectClass`` names the dynamics table an object is checked with (the
object classes plus ``ego``), ``rss.model.ObjectType`` is the ad-rss object type
(pedestrian, bicycle, or other vehicle for every motor vehicle and unknown objects). This
module is the one place that joins them, by explicit tables (a test checks that every
object class has its entry), never by name.
"""

from __future__ import annotations

from loaders.records import ObjectClass as FrameClass
from rss.model import ObjectType
from rss.params import ObjectClass

__all__ = ["ADRSS_TYPES", "DYNAMICS_CLASSES", "adrss_type", "dynamics_class"]

#: ad-rss object type of each loader class that is not an "other vehicle".
ADRSS_TYPES = {FrameClass.PEDESTRIAN: ObjectType.Pedestrian, FrameClass.BICYCLE: ObjectType.Bicycle}


def adrss_type(object_class: FrameClass) -> ObjectType:
    """ad-rss object type of a loader class (pedestrian, bicycle, else other vehicle)."""
    return ADRSS_TYPES.get(object_class, ObjectType.OtherVehicle)


#: The ``--rss-params`` dynamics table of each object class.
DYNAMICS_CLASSES = {
    FrameClass.UNKNOWN: ObjectClass.UNKNOWN,
    FrameClass.CAR: ObjectClass.CAR,
    FrameClass.TRUCK: ObjectClass.TRUCK,
    FrameClass.BUS: ObjectClass.BUS,
    FrameClass.MOTORCYCLE: ObjectClass.MOTORCYCLE,
    FrameClass.BICYCLE: ObjectClass.BICYCLE,
    FrameClass.PEDESTRIAN: ObjectClass.PEDESTRIAN,
}


def dynamics_class(object_class: FrameClass) -> ObjectClass:
    """The ``--rss-params`` table whose dynamics an object of this class is checked with."""
    return DYNAMICS_CLASSES[object_class]
