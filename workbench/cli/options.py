"""Option types and help texts shared by the command modules (parsing only)."""

from __future__ import annotations

import enum
from typing import Annotated

import typer

__all__ = ["EGO_TOPIC_HELP", "ReachMethodOption", "RssProfileOption"]

#: Help of ``--ego-topic`` (info, evaluate, replay).
EGO_TOPIC_HELP = "Ego topic of a ROS/MCAP log (over the profile and the detected one)."

#: ``--rss-profile NAME`` (info, evaluate, replay, demo); ``None`` = ``auto``.
#: (``--profile`` already names the loaders' TOML topic profile on these commands.)
RssProfileOption = Annotated[
    str | None,
    typer.Option(
        "--rss-profile",
        help=(
            "RSS parameter profile: adrss-5.0, carla, highway, or auto (default: highway on "
            "roads with speed limits >= 70 km/h, else adrss-5.0; docs/rss.md)."
        ),
    ),
]


class ReachMethodOption(enum.StrEnum):
    """``--reach-method`` values."""

    simple = "simple"
    turn = "turn"
    bound = "bound"
