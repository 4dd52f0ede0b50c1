"""Enum codes of the compiled small-frame path as ``Final`` ints, one source for all.

The row-by-row modules (:mod:`rss.structured.small`, ``small_merge``, ``small_output``,
``scalar_extract``, ``scalar_checks``) compare plain ints with the codes of the model's and
the states' enums. mypyc inlines a ``Final`` int literal imported from another compiled
module as a C constant, where an enum member would be a Python attribute look-up per use;
so the codes are written here once as literals, and
``tests/rss/structured/test_codes.py`` checks each against its enum member.
"""

from __future__ import annotations

from typing import Final

# ConstellationType
NOT_RELEVANT: Final = 0
SAME_DIRECTION: Final = 1
OPPOSITE_DIRECTION: Final = 2
EGO_PRIORITY: Final = 3
OBJECT_PRIORITY: Final = 4
UNSTRUCTURED: Final = 6

# ObjectType
INVALID_OBJECT: Final = 0
EGO_VEHICLE: Final = 1

# LaneDrivingDirection
POSITIVE: Final = 1
NEGATIVE: Final = 2

# RoadSegmentType
INTERSECTION_SEGMENT: Final = 1

# LongitudinalPosition (and LateralPosition: Overlap is 2 in both)
IN_FRONT: Final = 0
OVERLAP_FRONT: Final = 1
OVERLAP: Final = 2
OVERLAP_BACK: Final = 3
AT_BACK: Final = 4

# LateralPosition
AT_LEFT: Final = 0
OVERLAP_LEFT: Final = 1
OVERLAP_RIGHT: Final = 3
AT_RIGHT: Final = 4

# LongitudinalResponse (LateralResponse: 0 none, 1 BrakeMin)
BRAKE_MIN_CORRECT: Final = 1
BRAKE_MIN: Final = 2
LAT_BRAKE_MIN: Final = 1

# RssStateEvaluator
E_OD_CORRECT: Final = 1
E_OD: Final = 2
E_SD_EGO_FRONT: Final = 3
E_SD_OTHER_FRONT: Final = 4
E_LAT: Final = 5
E_I_EGO_STOPS: Final = 6
E_I_OTHER_STOPS: Final = 7
E_I_EGO_FRONT: Final = 8
E_I_OTHER_FRONT: Final = 9
E_I_OVERLAP: Final = 10

# IntersectionState
I_NONE: Final = 0
I_ABLE_TO_BRAKE: Final = 1
I_SAFE_DISTANCE: Final = 2
I_NO_TIME_OVERLAP: Final = 3
