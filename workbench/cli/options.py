"""Option types and help texts shared by the command modules (parsing only).

The engines' options are not declared here: :func:`engine_parameters` generates them from
the registered engines' specs (:mod:`workbench.engines.options`) each time typer builds a
command, so an engine registered at run time has its options in every command's ``--help``.
"""

from __future__ import annotations

import enum
import inspect
from pathlib import Path
from typing import Annotated, Any, cast

import typer

__all__ = [
    "DRIVE_PARAMETERS",
    "EGO_SIZE_PARAMETER",
    "EGO_TOPIC_HELP",
    "EgoIdOption",
    "EgoSizeOption",
    "EgoTopicOption",
    "GrpcPortOption",
    "LogArgument",
    "MapOption",
    "ProfileOption",
    "SettingsOption",
    "WebPortOption",
    "engine_parameters",
    "engines_parameter",
    "keyword",
]

#: Help of ``--ego-topic`` (info, evaluate, replay).
EGO_TOPIC_HELP = "Ego topic of a ROS/MCAP log (over the profile and the detected one)."

#: ``--grpc-port`` / ``--web-port`` of a served viewer (replay, review).
GrpcPortOption = Annotated[int, typer.Option("--grpc-port", help="--serve: gRPC port.")]
WebPortOption = Annotated[int, typer.Option("--web-port", help="--serve: web page port.")]

LogArgument = Annotated[
    Path, typer.Argument(help="Drive: .mcap, .bag, rosbag2 dir or .db3, .osi, .xml, .saa/.scn.")
]
MapOption = Annotated[
    Path | None, typer.Option("--map", help="Lane map file (Lanelet2, CommonRoad, OpenDRIVE).")
]
ProfileOption = Annotated[
    Path | None, typer.Option("--profile", help="TOML profile overriding topic roles.")
]
EgoIdOption = Annotated[
    str | None, typer.Option("--ego-id", help="CommonRoad: obstacle id promoted to ego.")
]
EgoTopicOption = Annotated[str | None, typer.Option("--ego-topic", help=EGO_TOPIC_HELP)]
EgoSizeOption = Annotated[
    str | None,
    typer.Option(
        "--ego-size",
        help=(
            "Ego length,width[,height] in m for every engine and the viewer (default: the "
            "log's, else 4.5,2.0,1.5)."
        ),
    ),
]
SettingsOption = Annotated[
    Path | None,
    typer.Option(
        "--settings",
        help="TOML with one table per engine, named as in `workbench engines`, holding that "
        "engine's options by name (README, engine options); options given on the command line win.",
    ),
]


def keyword(name: str, annotation: Any, default: object) -> inspect.Parameter:
    """A keyword-only parameter of a generated command signature."""
    return inspect.Parameter(
        name, inspect.Parameter.KEYWORD_ONLY, default=default, annotation=annotation
    )


def engines_parameter(default: str | None, help_text: str) -> inspect.Parameter:
    """``--engines`` with this command's default."""
    option = Annotated[str | None, typer.Option("--engines", help=help_text)]
    return keyword("engines", option, default)


#: The options of one drive's loader (no engine's own).
DRIVE_PARAMETERS = (
    keyword("map_path", MapOption, None),
    keyword("profile", ProfileOption, None),
    keyword("ego_id", EgoIdOption, None),
    keyword("ego_topic", EgoTopicOption, None),
)
#: ``--ego-size``: the ego's size of every engine and the viewer (every drive).
EGO_SIZE_PARAMETER = keyword("ego_size", EgoSizeOption, None)


def _default_text(value: object) -> str:
    return value.value if isinstance(value, enum.Enum) else str(value)


def engine_parameters() -> list[inspect.Parameter]:
    """``--settings`` and one option per distinct flag of the registered engines' options.

    Every generated option defaults to ``None`` ("not given"), so a value of the settings
    file applies unless the command line gives one; its help names the engines reading it
    and their default.
    """
    from workbench.engines.registry import cli_options  # noqa: PLC0415

    params = [keyword("settings", SettingsOption, None)]
    for key, (declared, engines) in cli_options().items():
        default = declared.default
        shown = "none" if default is None else _default_text(default)
        text = f"{declared.meta.help} (engines {', '.join(engines)}; default: {shown})"
        # a type built at run time: the engine's own value type, or None when not given
        option = cast("Any", Annotated)[
            declared.kind | None, typer.Option(declared.meta.flag, help=text)
        ]
        params.append(keyword(key, option, None))
    return params
