"""``rss.compiled``: the mypyc-compiled scene modules give the scenes of the sources, bit for bit.

The comparison runs scene creation in two fresh interpreters on the same seeded frames of
the urban-intersection sample map (intersections, junction lanes, opposite lanes): one
from the sources (``RSS_WORKBENCH_PURE_PYTHON=1``) and one with the compiled build. Without
a build (no C compiler) the comparison is skipped with the reason; under ``CI=true``
``make`` must have built it, so it runs.
"""

from __future__ import annotations

import json
import os
import sys
import sysconfig
from pathlib import Path

import pytest

from bench.child import run_json
from rss import compiled
from tests.conftest import running_in_ci

ROOT = Path(__file__).resolve().parents[3]

_SCRIPT = """
import hashlib, json
from pathlib import Path
from rss import compiled
compiled.activate()
from bench.bench_scene import _drives
from loaders.maps.lanelet2 import read_lanelet2
from bench.child import run_json
from rss.params import SceneSettings
from rss.scene import SceneMemo, create_scene, prepare
from rss.scene.chunked import match_frames
from rss.scene.create import scene_boxes
from workbench.engines.rss.adapter import lane_graph_from_map

prep = prepare(lane_graph_from_map(read_lanelet2(Path("sample_logs/urban_intersection.osm"))))
digest = hashlib.sha256()
memo = SceneMemo()
count = 0
for drive in _drives(prep, 3, 12):
    matches = match_frames(prep, [scene_boxes(e, o) for e, o in drive])
    for (ego, objects), m in zip(drive, matches):
        scene = create_scene(prep, ego, objects, SceneSettings(), matches=m, memo=memo)
        digest.update(repr(scene).encode())
        count += len(scene.constellations)
import rss.scene.pairs as pairs
print(json.dumps({"status": compiled.status(), "module": pairs.__file__,
                  "sha256": digest.hexdigest(), "constellations": count}))
"""


def _run(*, pure: bool) -> dict[str, object]:
    env = dict(os.environ)
    env.pop(compiled.PURE_ENV, None)
    if pure:
        env[compiled.PURE_ENV] = "1"
    result: dict[str, object] = run_json(_SCRIPT, env=env)
    return result


def test_compiled_scenes_equal_the_sources() -> None:
    reason = compiled.stale_reason()
    if reason is not None and os.environ.get(compiled.PURE_ENV) is None:
        if running_in_ci():
            pytest.fail(f"compiled scene modules unusable under CI=true: {reason}")
        pytest.skip(f"compiled scene modules unusable: {reason}")
    pure, fast = _run(pure=True), _run(pure=False)
    assert pure["status"] == [False, f"{compiled.PURE_ENV} is set"]
    assert fast["status"] == [True, ""]
    assert str(pure["module"]).endswith("pairs.py")
    assert str(fast["module"]).endswith(sysconfig.get_config_var("EXT_SUFFIX"))
    assert isinstance(pure["constellations"], int)
    assert pure["constellations"] > 50  # the frames do exercise scene creation
    assert fast["sha256"] == pure["sha256"]


def _manifest(build: Path, **changes: object) -> None:
    manifest: dict[str, object] = {
        "modules": list(compiled.MODULES),
        "sha256": compiled.source_digests(),
        "ext_suffix": sysconfig.get_config_var("EXT_SUFFIX"),
    }
    manifest.update(changes)
    build.mkdir(parents=True, exist_ok=True)
    (build / "manifest.json").write_text(json.dumps(manifest))


def test_stale_builds_are_not_used(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(compiled.PURE_ENV, raising=False)
    assert str(compiled.stale_reason(tmp_path / "none")).startswith("not built")
    _manifest(tmp_path / "fresh")
    assert compiled.stale_reason(tmp_path / "fresh") is None
    edited = dict(compiled.source_digests(), **{"rss.scene.pairs": "0" * 64})
    _manifest(tmp_path / "edited", sha256=edited)
    assert compiled.stale_reason(tmp_path / "edited") == (
        "sources changed since the build: rss.scene.pairs"
    )
    _manifest(tmp_path / "other", ext_suffix=".cpython-99-x.so")
    assert "another interpreter" in str(compiled.stale_reason(tmp_path / "other"))
    _manifest(tmp_path / "fewer", modules=list(compiled.MODULES[:-1]))
    assert compiled.stale_reason(tmp_path / "fewer") == "built for another module list"
    monkeypatch.setenv(compiled.PURE_ENV, "1")
    assert compiled.stale_reason(tmp_path / "fresh") == f"{compiled.PURE_ENV} is set"


def test_a_stale_build_installs_no_import_hook(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv(compiled.PURE_ENV, raising=False)
    monkeypatch.setattr(compiled, "_STATE", {"active": False, "reason": "not requested"})
    edited = dict(compiled.source_digests(), **{"rss.scene.routes": ""})
    _manifest(tmp_path, sha256=edited)
    hooks = list(sys.meta_path)
    assert not compiled.activate(tmp_path)
    assert sys.meta_path == hooks
    assert compiled.status() == (False, "sources changed since the build: rss.scene.routes")
    _manifest(tmp_path)  # fresh now, but the process has decided
    assert not compiled.activate(tmp_path)
    assert sys.meta_path == hooks


def test_a_late_call_switches_nothing_on(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Modules imported from their sources before the call keep the process pure."""
    monkeypatch.delenv(compiled.PURE_ENV, raising=False)
    monkeypatch.setattr(compiled, "_STATE", {"active": False, "reason": "not requested"})
    monkeypatch.setitem(sys.modules, "rss.scene.pairs", sys.modules.get("rss.scene.pairs"))
    _manifest(tmp_path)
    hooks = list(sys.meta_path)
    assert not compiled.activate(tmp_path)
    assert sys.meta_path == hooks
    active, reason = compiled.status()
    assert not active
    assert reason.endswith(" already imported from the sources")
    assert "rss.scene.pairs" in reason.split(" already")[0].split(", ")
