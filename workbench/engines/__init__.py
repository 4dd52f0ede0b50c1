"""Engines as plugins: one folder and one :class:`EngineSpec` each, one registry for all."""

from workbench.engines.base import (
    BoundRunner,
    EngineRunner,
    EngineSink,
    EngineSpec,
    Verdict,
    VerdictSummary,
    summarise,
)
from workbench.engines.registry import build_runners, engine, names, parse_engines, register

__all__ = [
    "BoundRunner",
    "EngineRunner",
    "EngineSink",
    "EngineSpec",
    "Verdict",
    "VerdictSummary",
    "build_runners",
    "engine",
    "names",
    "parse_engines",
    "register",
    "summarise",
]
