"""The reach-set engine's options: method, rules and the ego trajectory it rates.

In a ``--settings`` file: ``[reachsets] method = "bound"``, ``rules = "reference"``,
``trajectory = "planned"``.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

from reachsets.params import ReachMethod
from workbench.engines.options import option

__all__ = ["ReachOptions", "ReachRules", "ReachTrajectory"]


class ReachRules(enum.StrEnum):
    """``--reach-rules`` values."""

    public_road = "public-road"
    reference = "reference"

    @property
    def setting(self) -> str:
        """The runner's ``rules`` value (``public_road`` or ``reference``)."""
        return self.value.replace("-", "_")


class ReachTrajectory(enum.StrEnum):
    """``--reach-trajectory`` values."""

    auto = "auto"
    planned = "planned"
    braking = "braking"


def _rules_setting(rules: ReachRules) -> str:
    return rules.setting


@dataclass(frozen=True, slots=True)
class ReachOptions:
    """What the reach-set engine reads besides the drive.

    Attributes:
        method: Reachable-set method of the other road users.
        rules: ``public-road`` (the reference's rules plus the lane rules, the default for
            recorded drives) or ``reference``.
        trajectory: ``auto`` (the log's emergency trajectory when it has one, else braking
            from the ego's state), ``planned`` or ``braking``.
    """

    method: ReachMethod = option(
        ReachMethod.TURN, flag="--reach-method", help="Reachable-set method."
    )
    rules: ReachRules = option(
        ReachRules.public_road,
        flag="--reach-rules",
        help=(
            "Reach-set rules: public-road adds the lane rules (keep lane unless observably"
            " changing, no cut-in at the ego); reference = the TrajectorySupervisor's rules only."
        ),
        record=_rules_setting,
    )
    trajectory: ReachTrajectory = option(
        ReachTrajectory.auto,
        flag="--reach-trajectory",
        help=(
            "Ego trajectory the reach sets rate: auto = the log's emergency trajectory, else"
            " braking from the ego's state along its path; planned = the log's plan;"
            " braking = always the stop."
        ),
    )
