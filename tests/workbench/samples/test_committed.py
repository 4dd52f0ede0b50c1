"""The committed ``sample_logs/`` match the generator, and generation is deterministic.

Determinism includes machine independence: the bytes must not depend on numpy's SIMD
dispatch (which CPU features its kernels use) nor on last-bit noise in the trajectory math
(see ``workbench/samples/quantise.py`` and docs/samples.md).
"""

from __future__ import annotations

import dataclasses
import importlib
import json
import os
import subprocess
import sys
from typing import TYPE_CHECKING

import numpy as np
import pytest

from tests.workbench.samples.conftest import SAMPLE_DIR, sample_hashes
from workbench.samples.generate import SCENARIOS, generate_scenario
from workbench.samples.motion import Motion, Track

if TYPE_CHECKING:
    from workbench.samples.scenario import Scenario

_REPO = SAMPLE_DIR.parent
#: Generate every sample in a child process and print the SIMD features still enabled.
_CHILD = """
import json, sys
from pathlib import Path
from numpy._core import _multiarray_umath as umath
from workbench.samples.generate import generate
generate(Path(sys.argv[1]))
print(json.dumps([f for f in umath.__cpu_dispatch__ if umath.__cpu_features__.get(f)]))
"""


def test_generation_is_byte_identical(tmp_path):
    scenario = SCENARIOS["parking_lot"]
    generate_scenario(scenario(), tmp_path / "a")
    generate_scenario(scenario(), tmp_path / "b")
    first, second = sample_hashes(tmp_path / "a"), sample_hashes(tmp_path / "b")
    assert first
    assert first == second


def test_committed_samples_are_up_to_date(generated):
    committed = sample_hashes(SAMPLE_DIR)
    fresh = sample_hashes(generated)
    assert sorted(committed) == sorted(fresh), "run `make samples` and commit sample_logs/"
    stale = [name for name, digest in fresh.items() if committed[name] != digest]
    assert not stale, f"stale samples (run `make samples`): {stale}"


def test_samples_with_simd_dispatch_restricted_to_the_baseline_equal_the_committed(tmp_path):
    umath = importlib.import_module("numpy._core._multiarray_umath")
    dispatched = [f for f in umath.__cpu_dispatch__ if umath.__cpu_features__.get(f)]
    # Features already disabled for this run (e.g. the whole suite under a restriction) stay so.
    disabled = sorted({*dispatched, *os.environ.get("NPY_DISABLE_CPU_FEATURES", "").split()})
    env = {
        **os.environ,
        "NPY_DISABLE_CPU_FEATURES": " ".join(disabled),
        "PYTHONPATH": os.pathsep.join([str(_REPO), os.environ.get("PYTHONPATH", "")]),
    }
    child = subprocess.run(  # noqa: S603 - our own interpreter and inline script
        [sys.executable, "-c", _CHILD, str(tmp_path)],
        cwd=_REPO,
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )
    still_enabled = json.loads(child.stdout.strip().splitlines()[-1])
    assert still_enabled == [], f"restriction did not take effect: {still_enabled}"
    assert sample_hashes(tmp_path) == sample_hashes(SAMPLE_DIR)


def _nudged(track: Track, direction: float) -> Track:
    """``track`` with x, y, yaw and speed moved by one ulp; derivatives recomputed from them."""
    m = track.motion
    x, y, yaw, speed = (
        np.nextafter(a, direction * np.inf) for a in (m.x_m, m.y_m, m.yaw_rad, m.speed_mps)
    )
    motion = Motion(x, y, yaw, speed, m.lane_change)
    size = (track.length_m, track.width_m, track.height_m)
    rebuilt = Track.of(track.id, track.object_class, size, motion, track.lanes)
    return dataclasses.replace(rebuilt, visible=track.visible, confidence=track.confidence)


@pytest.mark.parametrize("direction", [1.0, -1.0])
@pytest.mark.parametrize("name", list(SCENARIOS))
def test_last_bit_noise_in_the_trajectories_does_not_change_the_files(tmp_path, name, direction):
    sc: Scenario = SCENARIOS[name]()
    noisy = dataclasses.replace(
        sc,
        ego=_nudged(sc.ego, direction),
        actors=tuple(_nudged(tr, direction) for tr in sc.actors),
    )
    generate_scenario(noisy, tmp_path)
    fresh = sample_hashes(tmp_path)
    assert fresh == sample_hashes(SAMPLE_DIR, (f"{name}.", f"{name}_"))


def test_samples_total_size_below_5mb():
    total = sum(p.stat().st_size for p in SAMPLE_DIR.rglob("*") if p.is_file())
    assert total < 5 * 1024 * 1024
