"""``TfChain``: composition up to map, fallback to odom, unrelated frames, loops."""

from __future__ import annotations

import math
from types import SimpleNamespace

import pytest

from loaders.message_logs.decoders.ros_tf import TfChain, TfFrames


def _tr(
    parent: str, child: str, x: float, y: float, yaw: float, *, t_ns: int = 0
) -> SimpleNamespace:
    stamp = SimpleNamespace(sec=t_ns // 10**9, nanosec=t_ns % 10**9)
    return SimpleNamespace(
        header=SimpleNamespace(stamp=stamp, frame_id=parent),
        child_frame_id=child,
        transform=SimpleNamespace(
            translation=SimpleNamespace(x=x, y=y, z=0.0),
            rotation=SimpleNamespace(x=0.0, y=0.0, z=math.sin(yaw / 2), w=math.cos(yaw / 2)),
        ),
    )


def _msg(*transforms: SimpleNamespace) -> SimpleNamespace:
    return SimpleNamespace(transforms=list(transforms))


def test_chain_composes_map_odom_base_link() -> None:
    chain = TfChain()
    assert chain.decode(_msg(_tr("map", "odom", 10.0, 0.0, math.pi / 2))) is None
    sample = chain.decode(_msg(_tr("odom", "base_link", 1.0, 0.0, 0.1, t_ns=5)))
    assert sample is not None
    assert (sample.x_m, sample.y_m) == pytest.approx((10.0, 1.0))
    assert sample.yaw_rad == pytest.approx(math.pi / 2 + 0.1)
    assert sample.stamp_ns == 5


def test_chain_falls_back_to_odom_and_ignores_other_frames() -> None:
    chain = TfChain(TfFrames(vehicle_frame="ego"))
    assert chain.decode(_msg(_tr("/ego", "/lidar", 1.0, 0.0, 0.0))) is None
    sample = chain.decode(_msg(_tr("/odom", "/ego", 2.0, 3.0, 0.0)))
    assert sample is not None
    assert (sample.x_m, sample.y_m) == pytest.approx((2.0, 3.0))


def test_chain_without_a_fixed_frame_or_with_a_loop_gives_nothing() -> None:
    chain = TfChain()
    assert chain.decode(_msg(_tr("world", "base_link", 1.0, 0.0, 0.0))) is None
    chain.add_static([_tr("base_link", "world", 0.0, 0.0, 0.0)])
    assert chain.decode(_msg(_tr("world", "base_link", 1.0, 0.0, 0.0))) is None
