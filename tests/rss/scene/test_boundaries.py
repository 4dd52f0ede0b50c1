from rss.model import ConstellationType, ObjectType
from rss.params import DEFAULT_EGO_DYNAMICS, SceneSettings
from rss.scene import create_scene, prepare
from rss.scene.boundaries import LEFT_BOUNDARY_ID, RIGHT_BOUNDARY_ID
from rss.structured.engine import check_frame
from rss.structured.stacking import stack_constellations

from .synthetic import WIDTH, ego, objects, straight_road


def _boundaries(y: float):
    prep = prepare(straight_road(3))
    scene = create_scene(prep, ego(50.0, y), objects(), SceneSettings(), road_boundaries=True)
    result, _ = check_frame(stack_constellations(scene.constellations), DEFAULT_EGO_DYNAMICS)
    return scene, result


def test_two_boundary_objects_span_the_road():
    scene, result = _boundaries(0.0)
    ids = [c.other.object_id for c in scene.constellations]
    assert ids == [LEFT_BOUNDARY_ID, RIGHT_BOUNDARY_ID]
    for c in scene.constellations:
        assert c.constellation_type == ConstellationType.SameDirection
        assert c.other.object_type == ObjectType.ArtificialObject
        assert len(c.ego_road[0].lanes) == 3
    assert not result.dangerous.any()


def test_ego_at_the_right_edge_is_dangerous_towards_the_right_boundary():
    right_edge = -1.5 * WIDTH
    _, result = _boundaries(right_edge + 1.0 + 0.05)  # 5 cm from the edge
    assert result.dangerous.tolist() == [False, True]
