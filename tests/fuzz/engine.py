"""The coverage-guided fuzzer of one target: atheris (libFuzzer) in this process.

Run by ``tests.fuzz.run`` (``make fuzz``) in the side venv that has ``atheris``::

    python -m tests.fuzz.engine TARGET --seconds N --dir out/fuzz/TARGET [--also DIR ...]

``DIR/corpus`` is the target's growing corpus (new coverage is written there, so a later run
resumes from it), ``DIR/seeds`` and every ``--also`` directory are read as further inputs,
``DIR/assets`` holds what the target's inputs lie beside, and a finding is written to
``DIR/crash-<sha1>`` (``timeout-``, ``oom-``). The target's packages are imported under
atheris' instrumentation, so nothing here imports them before :func:`main` does.
"""

from __future__ import annotations

import argparse
import logging
import shutil
import sys
import tempfile
import warnings
from pathlib import Path

from tests.fuzz.targets import TARGETS, run_input

#: Seconds one input may take before libFuzzer reports it as a ``timeout-`` finding.
INPUT_TIMEOUT_S = 30


def _arguments(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("target", choices=sorted(TARGETS))
    parser.add_argument("--seconds", type=int, required=True)
    parser.add_argument("--dir", type=Path, required=True)
    parser.add_argument("--also", type=Path, action="append", default=[])
    return parser.parse_args(argv)


def main(argv: list[str] | None = None) -> None:
    """Fuzz one target for ``--seconds``; libFuzzer exits the process (non-zero on a finding)."""
    import atheris  # noqa: PLC0415 - only the side venv has it

    args = _arguments(sys.argv[1:] if argv is None else argv)
    target = TARGETS[args.target]
    logging.disable(logging.CRITICAL)  # loaders log per bad message: keep the run's log short
    warnings.simplefilter("ignore")
    assets = args.dir / "assets"
    scratch = Path(tempfile.mkdtemp(prefix=f"fuzz-{target.name}-", dir=_scratch_root()))
    counter = iter(range(sys.maxsize))
    with atheris.instrument_imports(include=list(target.instrument)):
        # Reading the seeds imports every module their paths reach (some load on demand).
        for seed in sorted((args.dir / "seeds").glob("seed-*")):
            directory = scratch / f"warm-{seed.name}"
            directory.mkdir()
            run_input(target, seed.read_bytes(), directory, assets if assets.is_dir() else None)

    def one(data: bytes) -> None:
        directory = scratch / str(next(counter))
        directory.mkdir()
        try:
            run_input(target, data, directory, assets if assets.is_dir() else None)
        finally:
            shutil.rmtree(directory, ignore_errors=True)

    corpus = args.dir / "corpus"
    corpus.mkdir(parents=True, exist_ok=True)
    inputs = [corpus, args.dir / "seeds", *(d for d in args.also if d.is_dir())]
    libfuzzer = [
        sys.argv[0],
        *(str(d) for d in inputs),
        f"-max_total_time={args.seconds}",
        f"-timeout={INPUT_TIMEOUT_S}",
        "-rss_limit_mb=4096",
        "-print_final_stats=1",
        f"-artifact_prefix={args.dir}/",
    ]
    atheris.Setup(libfuzzer, one)
    atheris.Fuzz()


def _scratch_root() -> str | None:
    shm = Path("/dev/shm")  # noqa: S108 - RAM-backed scratch for one input's files
    return str(shm) if shm.is_dir() else None


if __name__ == "__main__":
    main()
