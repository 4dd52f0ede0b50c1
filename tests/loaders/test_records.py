import numpy as np
import pytest

from loaders.records import ActorTable, ObjectClass


def test_from_columns_marks_non_finite_rows_invalid_and_freezes_arrays():
    table = ActorTable.from_columns(
        ids=["a", "b"],
        object_class=[ObjectClass.CAR, ObjectClass.PEDESTRIAN],
        x_m=[0.0, np.nan],
        y_m=[1.0, 2.0],
        yaw_rad=[0.0, 0.0],
        vx_mps=[3.0, 0.0],
        vy_mps=[4.0, 0.0],
        length_m=[4.5, 0.5],
        width_m=[1.9, 0.5],
    )
    assert table.valid.tolist() == [True, False]
    assert table.speed_mps[0] == pytest.approx(5.0)
    with pytest.raises(ValueError, match="read-only"):
        table.x_m[0] = 1.0


def test_mismatched_lengths_are_rejected():
    with pytest.raises(ValueError, match="rows"):
        ActorTable.from_columns(
            ids=["a"],
            object_class=[1, 1],
            x_m=[0.0],
            y_m=[0.0],
            yaw_rad=[0.0],
            vx_mps=[0.0],
            vy_mps=[0.0],
            length_m=[1.0],
            width_m=[1.0],
        )


def test_empty_table_has_no_rows():
    assert len(ActorTable.empty()) == 0
