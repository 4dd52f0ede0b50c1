"""Narrowed nearest-segment windows (``rss.scene.segment_cells``) give the same results."""

from __future__ import annotations

import dataclasses
import itertools

import numpy as np
import pytest
import shapely

from loaders.maps.opendrive import read_opendrive
from rss.scene import BoxArrays, border_index, match_boxes, prepare
from rss.scene import segment_cells as segment_cells_module
from rss.scene.admap_nearest import nearest_in_windows, segment_window, segments
from rss.scene.polylines import Polylines, polylines
from rss.scene.segment_cells import narrowed, segment_cells
from workbench.engines.rss.adapter import lane_graph_from_map


def _arc(centre: tuple[float, float], radius: float, step_deg: float) -> np.ndarray:
    angles = np.radians(np.arange(0.0, 180.0 + 1e-9, step_deg))
    out: np.ndarray = np.c_[
        centre[0] + radius * np.cos(angles), centre[1] + radius * np.sin(angles)
    ]
    return out


def _lines(rng: np.random.Generator) -> Polylines:
    """Arcs (chords all equally far from the centre), a V, a U-turn, zig-zags, a repeated
    vertex and a single segment."""
    out = [
        _arc((0.0, 0.0), 10.0, 7.5),
        _arc((40.0, 0.0), 4.0, 20.0)[::-1],
        np.array([[-1.0, 31.0], [0.0, 30.0], [1.0, 31.0]]),
        np.array([[20.0, 20.0], [30.0, 20.0], [31.0, 21.0], [30.0, 22.0], [20.0, 22.0]]),
        np.array([[50.0, 30.0], [55.0, 30.0], [55.0, 30.0], [60.0, 33.0]]),
        np.array([[-30.0, -10.0], [-10.0, -10.0]]),
    ]
    for _ in range(4):
        steps = rng.normal(0.0, 2.0, (int(rng.integers(2, 14)), 2)) + np.array([1.5, 0.0])
        start = rng.uniform(-40.0, 40.0, 2)
        out.append(np.vstack([start, start + np.cumsum(steps, axis=0)]))
    return polylines(np.array([shapely.LineString(line) for line in out], dtype=object))


def _points(rng: np.random.Generator, lines: Polylines, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Rows ``(which, points)``: near random vertices and segment middles, and ties."""
    vertex = rng.integers(0, len(lines.xy_m), n)
    which = np.searchsorted(lines.start, vertex, side="right") - 1
    points = lines.xy_m[vertex] + rng.normal(0.0, 2.5, (n, 2))
    # ties: arc centres (equally far from every chord), the V's axis, the U's middle, and
    # points 0.2-2 mm off the axis (within and beyond the 1 mm tie tolerance)
    ties = np.array([[0.0, 0.0], [40.0, 0.0], [0.0, 31.5], [0.0, 33.0], [25.0, 21.0]])
    tie_line = np.array([0, 1, 2, 2, 3])
    off = np.array([[0.0, 0.0], [2e-4, 0.0], [-6e-4, 0.0], [9e-4, 0.0], [1.2e-3, 0.0], [2e-3, 0]])
    tie_points = (ties[:, None, :] + off[None]).reshape(-1, 2)
    tie_which = np.repeat(tie_line, len(off))
    # points on cell corners (the grid's float edges)
    corner = np.floor(points[:50] * 2.0) / 2.0
    return (
        np.concatenate([which, tie_which, which[:50]]),
        np.concatenate([points, tie_points, corner]),
    )


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_narrowed_windows_give_bit_identical_nearest_points(seed: int) -> None:
    rng = np.random.default_rng(seed)
    lines = _lines(rng)
    steps = segments(lines)
    cells = segment_cells(lines)
    which, points = _points(rng, lines, 4000)
    backwards = rng.random(len(which)) < 0.5
    near = rng.uniform(0.0, 1.0, len(which)) * lines.length_m[which]
    for reach in (None, 2.0, 6.0):  # the whole line, and windows along it
        first, last = segment_window(lines, which, None if reach is None else near, reach or 0.0)
        lo, hi = narrowed(cells, which, points, first, last)
        assert np.all((lo >= first) & (hi <= last) & (lo <= hi))
        s, feet = nearest_in_windows(steps, points, backwards, first, last)
        s_n, feet_n = nearest_in_windows(steps, points, backwards, lo, hi)
        np.testing.assert_array_equal(s_n, s)
        np.testing.assert_array_equal(feet_n, feet)
    # the windows shrink: most rows of lines of several segments keep one or two segments
    multi = (lines.start[which + 1] - lines.start[which]) > 2
    first, last = segment_window(lines, which)
    lo, hi = narrowed(cells, which, points, first, last)
    assert np.mean((hi - lo + 1)[multi]) < 0.5 * np.mean((last - first + 1)[multi])


def test_ties_keep_admaps_first_segment() -> None:
    """On the arc's centre every chord is a tie: the whole arc stays a candidate."""
    lines = _lines(np.random.default_rng(0))
    cells = segment_cells(lines)
    which = np.zeros(2, dtype=np.int64)
    points = np.zeros((2, 2))
    first, last = segment_window(lines, which)
    lo, hi = narrowed(cells, which, points, first, last)
    np.testing.assert_array_equal(lo, first)
    np.testing.assert_array_equal(hi, last)
    s, _ = nearest_in_windows(segments(lines), points, np.array([False, True]), lo, hi)
    assert s[0] < lines.segment_m[0]  # ours: the first chord
    assert s[1] > lines.length_m[0] - lines.segment_m[0]  # reversed: the last chord


def test_tie_tolerance_survives_cells_finer_than_a_millimetre() -> None:
    """With cells of 0.2 mm the 1 mm tie tolerance alone keeps the second arm of a V."""
    v = shapely.LineString([(-0.02, 0.02), (0.0, 0.0), (0.02, 0.02)])
    lines = polylines(np.array([v], dtype=object))
    cells = segment_cells(lines, cell_m=2e-4, band_m=0.01)
    dx = np.array([0.0, 3e-4, 6e-4, 1.5e-3, 2e-3, -6e-4])  # arm distances differ by dx * sqrt(2)
    points = np.c_[dx, np.full(len(dx), 0.005)]
    which = np.zeros(len(dx), dtype=np.int64)
    first, last = segment_window(lines, which)
    lo, hi = narrowed(cells, which, points, first, last)
    np.testing.assert_array_equal(hi - lo + 1, [2, 2, 2, 1, 1, 2])
    for backwards in (np.zeros(len(dx), dtype=np.bool_), np.ones(len(dx), dtype=np.bool_)):
        ref = nearest_in_windows(segments(lines), points, backwards, first, last)
        got = nearest_in_windows(segments(lines), points, backwards, lo, hi)
        np.testing.assert_array_equal(got[0], ref[0])
        np.testing.assert_array_equal(got[1], ref[1])


def test_points_off_the_grid_keep_their_window() -> None:
    lines = _lines(np.random.default_rng(0))
    cells = segment_cells(lines)
    which = np.zeros(3, dtype=np.int64)
    points = np.array([[1e4, 0.0], [np.nan, 0.0], [-1e4, -1e4]])
    first, last = segment_window(lines, which)
    lo, hi = narrowed(cells, which, points, first, last)
    np.testing.assert_array_equal(lo, first)
    np.testing.assert_array_equal(hi, last)


_FIELDS = ("origin_m", "y_first", "rows", "row_base", "x_first", "width", "offset", "first", "last")


@pytest.mark.parametrize("seed", [0, 1])
def test_pieces_of_bounded_memory_lay_out_the_same_cells(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Small pieces (consecutive lines together, a long line in bands of rows) give the
    cells of one piece, field for field."""
    base = _lines(np.random.default_rng(seed))
    wiggle = np.c_[np.arange(0.0, 800.0, 7.0), 30.0 * np.sin(np.arange(0.0, 800.0, 7.0) / 90.0)]
    diagonal = np.c_[np.arange(0.0, 300.0, 11.0), np.arange(0.0, 300.0, 11.0) + 60.0]
    lines = polylines(
        np.array(
            [
                *(
                    shapely.LineString(base.xy_m[a:b])
                    for a, b in itertools.pairwise(base.start.tolist())
                ),
                shapely.LineString(wiggle),
                shapely.LineString(diagonal),
            ],
            dtype=object,
        )
    )
    whole = segment_cells(lines)
    banded = segment_cells_module._cells_of_lines
    bands: list[tuple[int, int]] = []

    def counted(*args: object) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        if len(args) > 6:  # the rows of a band
            bands.append(args[6])  # type: ignore[arg-type]
        return banded(*args)  # type: ignore[arg-type]

    monkeypatch.setattr(segment_cells_module, "_cells_of_lines", counted)
    for pairs in (1 << 12, 1 << 15):
        monkeypatch.setattr(segment_cells_module, "_BLOCK_PAIRS", pairs)
        pieces = segment_cells(lines)
        assert pieces.cell_m == whole.cell_m
        for name in _FIELDS:
            np.testing.assert_array_equal(getattr(pieces, name), getattr(whole, name), name)
    assert len(bands) > 10  # the long lines were cut into bands of rows


def test_single_segment_lines_get_no_cells() -> None:
    lines = polylines(np.array([shapely.LineString([(0, 0), (5, 0)])], dtype=object))
    cells = segment_cells(lines)
    assert len(cells.first) == 0
    which, points = np.zeros(1, dtype=np.int64), np.array([[1.0, 1.0]])
    first, last = segment_window(lines, which)
    lo, hi = narrowed(cells, which, points, first, last)
    np.testing.assert_array_equal(lo, first)
    np.testing.assert_array_equal(hi, last)


@pytest.mark.external
def test_town01_matching_is_the_same_without_cells(external_dir, monkeypatch) -> None:
    """Random boxes (size, heading, off the lanes) on Town01: cells change no bit."""
    prep = prepare(lane_graph_from_map(read_opendrive(external_dir / "maps" / "Town01.xodr")))
    rng = np.random.default_rng(5)
    n = 600
    lanes = rng.integers(0, len(prep.graph), n)
    centre = np.array(
        [prep.graph.centre_m[k][rng.integers(len(prep.graph.centre_m[k]))] for k in lanes]
    )
    centre += rng.normal(0.0, 2.0, (n, 2))
    boxes = BoxArrays(
        x_m=centre[:, 0],
        y_m=centre[:, 1],
        yaw_rad=rng.uniform(-np.pi, np.pi, n),
        length_m=rng.uniform(0.3, 12.0, n),
        width_m=rng.uniform(0.3, 3.0, n),
    )
    ours = match_boxes(prep, boxes)
    assert len(prep.border_index.cells.first) > 0
    monkeypatch.setattr(border_index, "narrowed", lambda _cells, _which, _points, *window: window)
    reference = match_boxes(prep, boxes)
    assert len(ours.box) > n  # boxes do touch lanes, some several
    for field in dataclasses.fields(ours):
        a, b = getattr(ours, field.name), getattr(reference, field.name)
        np.testing.assert_array_equal(np.asarray(a), np.asarray(b), err_msg=field.name)
