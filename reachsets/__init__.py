"""Rule-based reachable-set supervisor (pure: numpy/shapely in, verdicts out).

Entry point: ``evaluate_frames(inputs, params, state) -> (results, state)`` over consecutive
frames with the rule memory as explicit state; see ``docs/reachsets.md``.
"""

from reachsets.adapter import reach_inputs_from_arrays
from reachsets.engine import AppliedPatch, Collision, ReachResult, RuleState, evaluate_frames
from reachsets.errors import InputShapeError, ParamsError, ReachSetError, ZoneFileError
from reachsets.inputs import (
    EgoTrajectory,
    ObjectStates,
    ReachInputs,
    RightOfWayRule,
    RoadLane,
    RoadLayout,
    TrackBounds,
    Zone,
    ZoneKind,
    ZoneMap,
)
from reachsets.params import F1Params, ReachMethod, ReachParams, RoadRuleParams, RoboraceParams
from reachsets.rules_roborace import zones_from_json

__all__ = [
    "AppliedPatch",
    "Collision",
    "EgoTrajectory",
    "F1Params",
    "InputShapeError",
    "ObjectStates",
    "ParamsError",
    "ReachInputs",
    "ReachMethod",
    "ReachParams",
    "ReachResult",
    "ReachSetError",
    "RightOfWayRule",
    "RoadLane",
    "RoadLayout",
    "RoadRuleParams",
    "RoboraceParams",
    "RuleState",
    "TrackBounds",
    "Zone",
    "ZoneFileError",
    "ZoneKind",
    "ZoneMap",
    "evaluate_frames",
    "reach_inputs_from_arrays",
    "zones_from_json",
]
