"""Where a review queue (one drive's or a fleet's) resumes: ``resume_row``."""

from __future__ import annotations

import pytest

from workbench.review.session import resume_row


@pytest.mark.parametrize(
    ("done", "row"),
    [
        ([], 0),
        ([False], 0),
        ([True], 0),
        ([True, True, True], 2),
        ([True, False, True], 1),
        ([False, False], 0),
        ([True, True, False], 2),
    ],
)
def test_first_row_not_labelled_else_the_last(done: list[bool], row: int) -> None:
    assert resume_row(iter(done)) == row
