import pytest

from workbench.engines.base import VerdictSummary
from workbench.sinks.runs import RunMerger

DT = 100


def _feed(pattern: str, gap_ns: int) -> list[tuple[int, int, int]]:
    """'x' hits key 'k', '.' misses; returns (start, end, unsafe frames) per run."""
    merger: RunMerger[str] = RunMerger(gap_ns)
    hit = VerdictSummary(is_safe=False, culprits=("a",), cause="c", margin=1.0)
    for i, ch in enumerate(pattern):
        merger.add(i, i * DT, {"k": hit} if ch == "x" else {})
    return [(r.start_frame, r.end_frame, r.unsafe_frames) for r in merger.runs()]


@pytest.mark.parametrize(
    ("pattern", "gap_ns", "expected"),
    [
        ("xx..xx....x", 0, [(0, 1, 2), (4, 5, 2), (10, 10, 1)]),
        # two safe frames: from the first safe frame (t=2) to the next hit (t=4) is 2 DT
        ("xx..xx....x", 2 * DT, [(0, 5, 4), (10, 10, 1)]),
        ("xx..xx....x", 2 * DT - 1, [(0, 1, 2), (4, 5, 2), (10, 10, 1)]),
        ("xx..xx....x", 5 * DT, [(0, 10, 5)]),
        ("..........", 5 * DT, []),
    ],
)
def test_gap_merging_bridges_short_safe_stretches_only(pattern, gap_ns, expected):
    assert _feed(pattern, gap_ns) == expected


def test_negative_gap_is_rejected():
    with pytest.raises(ValueError, match="gap_ns"):
        RunMerger(-1)
