"""Option types and help texts shared by the command modules (parsing only)."""

from __future__ import annotations

import enum
from typing import Annotated

import typer

__all__ = [
    "EGO_TOPIC_HELP",
    "REACH_RULES_HELP",
    "REACH_TRAJECTORY_HELP",
    "GrpcPortOption",
    "ReachMethodOption",
    "ReachRulesOption",
    "ReachTrajectoryOption",
    "RssProfileOption",
    "WebPortOption",
]

#: Help of ``--ego-topic`` (info, evaluate, replay).
EGO_TOPIC_HELP = "Ego topic of a ROS/MCAP log (over the profile and the detected one)."

#: ``--grpc-port`` / ``--web-port`` of a served viewer (replay, review).
GrpcPortOption = Annotated[int, typer.Option("--grpc-port", help="--serve: gRPC port.")]
WebPortOption = Annotated[int, typer.Option("--web-port", help="--serve: web page port.")]

#: ``--rss-profile NAME`` (info, evaluate, replay, demo); ``None`` = ``auto``.
#: (``--profile`` already names the loaders' TOML topic profile on these commands.)
RssProfileOption = Annotated[
    str | None,
    typer.Option(
        "--rss-profile",
        help=(
            "RSS parameter profile: adrss-5.0, carla, highway, urban, or auto (default: "
            "highway on roads with speed limits >= 70 km/h, urban on other maps; docs/rss.md)."
        ),
    ),
]


class ReachMethodOption(enum.StrEnum):
    """``--reach-method`` values."""

    simple = "simple"
    turn = "turn"
    bound = "bound"


#: Help of ``--reach-rules``.
REACH_RULES_HELP = (
    "Reach-set rules: public-road adds the lane rules (keep lane unless observably changing,"
    " no cut-in at the ego); reference = the TrajectorySupervisor's rules only."
)
#: Help of ``--reach-trajectory``.
REACH_TRAJECTORY_HELP = (
    "Ego trajectory the reach sets rate: auto = the log's emergency trajectory, else braking"
    " from the ego's state along its path; planned = the log's plan; braking = always the stop."
)


class ReachRulesOption(enum.StrEnum):
    """``--reach-rules`` values (``value`` is the engine setting)."""

    public_road = "public-road"
    reference = "reference"

    @property
    def setting(self) -> str:
        """The ``EngineSettings.reach_rules`` value."""
        return self.value.replace("-", "_")


class ReachTrajectoryOption(enum.StrEnum):
    """``--reach-trajectory`` values."""

    auto = "auto"
    planned = "planned"
    braking = "braking"
