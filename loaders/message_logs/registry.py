"""Which message types we decode, for which role, and how much we prefer each.

Type names are normalised to ``package/Type`` (ROS, without the ``/msg/`` infix) or the
schema name (``foxglove.SceneUpdate``, ``workbench.EgoState``). A decoder is looked up once
per topic and cached by the drive.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from loaders.message_logs.decoders import (
    foxglove,
    mcap_json,
    osi,
    ros_boxes,
    ros_ego,
    ros_objects,
    ros_plan,
    ros_radar,
)

if TYPE_CHECKING:
    from collections.abc import Callable

    from loaders.message_logs.samples import (
        EgoSample,
        EgoWithObjects,
        ObjectColumns,
        PlanSample,
    )

__all__ = ["FAMILIES", "ROLES", "MessageFamily", "family_of", "normalize_msgtype"]

#: Role names in display order.
ROLES: tuple[str, ...] = ("ego", "objects", "plan")


@dataclass(frozen=True, slots=True)
class MessageFamily:
    """A decodable message type.

    Attributes:
        role: ``ego``, ``objects`` or ``plan``.
        rank: Preference within the role when several topics qualify (lower wins).
        decode: Decoded message object → sample; None for the stateful ego families
            (``tf2_msgs/TFMessage``, ``sensor_msgs/NavSatFix``) whose decoders are built per
            read by ``loaders.message_logs.ego_streams``.
        carries_objects: An ego family whose messages also hold the object list (ASAM OSI
            ground truth): its topic is the drive's object topic too, unless a profile
            names object topics.
    """

    role: str
    rank: int
    decode: Callable[[Any], EgoSample | EgoWithObjects | ObjectColumns | PlanSample] | None
    carries_objects: bool = False


FAMILIES: dict[str, MessageFamily] = {
    "nav_msgs/Odometry": MessageFamily("ego", 0, ros_ego.decode_odometry),
    "foxglove.Odometry": MessageFamily("ego", 0, foxglove.decode_foxglove_odometry),
    "workbench.EgoState": MessageFamily("ego", 0, mcap_json.decode_json_ego),
    osi.OSI_GROUND_TRUTH: MessageFamily("ego", 0, osi.decode_ground_truth, carries_objects=True),
    osi.OSI_SENSOR_VIEW: MessageFamily("ego", 0, osi.decode_sensor_view, carries_objects=True),
    "geometry_msgs/PoseStamped": MessageFamily("ego", 1, ros_ego.decode_pose_stamped),
    "geometry_msgs/PoseWithCovarianceStamped": MessageFamily(
        "ego", 1, ros_ego.decode_pose_with_covariance
    ),
    "foxglove.PoseInFrame": MessageFamily("ego", 1, foxglove.decode_foxglove_pose_in_frame),
    "foxglove.FrameTransform": MessageFamily("ego", 2, foxglove.decode_foxglove_frame_transform),
    "tf2_msgs/TFMessage": MessageFamily("ego", 2, None),
    "sensor_msgs/NavSatFix": MessageFamily("ego", 3, None),
    "derived_object_msgs/ObjectArray": MessageFamily(
        "objects", 0, ros_objects.decode_carla_objects
    ),
    **{
        f"{package}/{kind}Objects": MessageFamily(
            "objects", rank, ros_objects.decode_autoware_objects
        )
        for package in ("autoware_perception_msgs", "autoware_auto_perception_msgs")
        for kind, rank in (("Tracked", 0), ("Predicted", 1), ("Detected", 2))
    },
    "autoware_msgs/DetectedObjectArray": MessageFamily(
        "objects", 1, ros_objects.decode_autoware_ai_objects
    ),
    "radar_msgs/RadarTracks": MessageFamily("objects", 2, ros_radar.decode_radar_tracks),
    "workbench.ObjectList": MessageFamily("objects", 0, mcap_json.decode_json_objects),
    "vision_msgs/Detection3DArray": MessageFamily("objects", 2, ros_objects.decode_detection3d),
    "foxglove.SceneUpdate": MessageFamily("objects", 2, foxglove.decode_scene_update),
    "jsk_recognition_msgs/BoundingBoxArray": MessageFamily(
        "objects", 2, ros_boxes.decode_jsk_boxes
    ),
    "visualization_msgs/MarkerArray": MessageFamily("objects", 3, ros_boxes.decode_marker_array),
    **{
        f"{package}/Trajectory": MessageFamily("plan", 0, ros_plan.decode_trajectory)
        for package in ("autoware_planning_msgs", "autoware_auto_planning_msgs")
    },
    "workbench.Plan": MessageFamily("plan", 0, mcap_json.decode_json_plan),
    "nav_msgs/Path": MessageFamily("plan", 1, ros_plan.decode_path),
}


def normalize_msgtype(msgtype: str) -> str:
    """``nav_msgs/msg/Odometry`` → ``nav_msgs/Odometry``; other names unchanged."""
    return msgtype.replace("/msg/", "/")


def family_of(msgtype: str) -> MessageFamily | None:
    """The family decoding ``msgtype`` (any spelling), or None."""
    return FAMILIES.get(normalize_msgtype(msgtype))
