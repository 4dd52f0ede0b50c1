"""Every committed fuzz input through its entry point: only typed errors may come out.

``tests/fuzz/corpus/<target>/`` holds the minimized inputs of the fuzzer's findings (see
``docs/fuzzing.md``); each must now read or fail with the target's typed error, one line
naming the file. The seeds the fuzzer starts from must read without any error, so that the
fuzzer is known to reach the loaders at all.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.fuzz.seeds import SEEDS, write_assets, write_seeds
from tests.fuzz.targets import TARGETS, run_input

CORPUS = Path(__file__).resolve().parent / "corpus"
_CASES = sorted(
    (target.name, path.name)
    for target in CORPUS.iterdir()
    if target.is_dir()
    for path in target.iterdir()
    if path.is_file()
)


@pytest.fixture(scope="module")
def assets(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The storage file the ``rosbag2-sqlite3`` inputs lie beside."""
    return write_assets(tmp_path_factory.mktemp("assets"))


def test_corpus_folders_name_targets() -> None:
    folders = {p.name for p in CORPUS.iterdir() if p.is_dir()}
    assert folders <= set(TARGETS), folders - set(TARGETS)
    assert _CASES, "no regression input committed"


def test_every_target_has_seeds() -> None:
    assert set(SEEDS) == set(TARGETS)


@pytest.mark.parametrize(("target", "name"), _CASES)
def test_regression_input_fails_typed_or_reads(
    target: str, name: str, assets: Path, tmp_path: Path
) -> None:
    outcome = run_input(TARGETS[target], (CORPUS / target / name).read_bytes(), tmp_path, assets)
    assert outcome.startswith(("ok: ", "typed: "))
    assert "\n" not in outcome


@pytest.mark.parametrize("target", sorted(TARGETS))
def test_seeds_read_without_error(target: str, assets: Path, tmp_path: Path) -> None:
    seeds = write_seeds(target, tmp_path / "seeds")
    assert seeds
    for k, seed in enumerate(seeds):
        directory = tmp_path / f"run{k}"
        directory.mkdir()
        outcome = run_input(TARGETS[target], seed.read_bytes(), directory, assets)
        assert outcome.startswith("ok: "), (seed.name, outcome)
        assert int(outcome.removeprefix("ok: ")) > 0, seed.name
