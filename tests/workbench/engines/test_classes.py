"""The one join of the loaders' object classes with the RSS engines' keys."""

from __future__ import annotations

from loaders.records import ObjectClass as FrameClass
from rss.model import ObjectType
from rss.params import ObjectClass
from workbench.engines.classes import DYNAMICS_CLASSES, adrss_type, dynamics_class


def test_every_object_class_has_its_own_dynamics_table_and_an_adrss_type():
    assert set(DYNAMICS_CLASSES) == set(FrameClass)
    tables = [dynamics_class(c) for c in FrameClass]
    assert len(set(tables)) == len(tables)
    assert ObjectClass.EGO not in tables
    assert set(tables) | {ObjectClass.EGO} == set(ObjectClass)
    assert all(adrss_type(c) is not ObjectType.EgoVehicle for c in FrameClass)
    assert adrss_type(FrameClass.PEDESTRIAN) is ObjectType.Pedestrian
