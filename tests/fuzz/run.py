"""``make fuzz``: every fuzz target for a bounded time, one process each, resumable.

::

    python -m tests.fuzz.run [TARGET ...] --seconds 600 --out out/fuzz
    python -m tests.fuzz.run --minimize TARGET FINDING     # into tests/fuzz/corpus/TARGET/

Per target, in ``OUT/<target>/``: ``seeds/`` (rewritten each run from the samples),
``corpus/`` (kept: the next run resumes from it), ``assets/``, the findings libFuzzer writes
(``crash-*``, ``timeout-*``, ``oom-*``; each minimized into ``minimized/``) and
``log.txt``. ``OUT/summary.json`` gains one
record per target run (seconds, executions, corpus, findings); a finding makes the exit
code 1 after every target ran. Findings are minimized with ``--minimize`` and kept as
regression inputs in ``tests/fuzz/corpus/<target>/``, which ``tests/fuzz/test_corpus.py``
runs in ``make test``.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import re
import subprocess
import sys
import time
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from tests.fuzz.minimize import failure, minimize
from tests.fuzz.seeds import write_assets, write_seeds
from tests.fuzz.targets import TARGETS

__all__ = ["CORPUS", "main"]

#: The committed regression inputs, one folder per target.
CORPUS = Path(__file__).resolve().parent / "corpus"
#: Seconds spent minimizing each finding after a target's run.
MINIMIZE_S = 60.0
_FINDINGS = ("crash-", "timeout-", "oom-", "leak-")
_STAT = re.compile(r"^stat::(\w+):\s+(\d+)", re.MULTILINE)
_DONE = re.compile(r"Done (\d+) runs in (\d+) second")


def _findings(directory: Path) -> set[Path]:
    return {p for p in directory.iterdir() if p.name.startswith(_FINDINGS)}


def _fuzz_one(name: str, seconds: int, out: Path) -> dict[str, Any]:
    directory = out / name
    directory.mkdir(parents=True, exist_ok=True)
    write_seeds(name, directory / "seeds")
    if TARGETS[name].storage:
        write_assets(directory / "assets")
    before = _findings(directory)
    command = [
        sys.executable,
        "-m",
        "tests.fuzz.engine",
        name,
        f"--seconds={seconds}",
        f"--dir={directory}",
        f"--also={CORPUS / name}",
    ]
    started = time.monotonic()
    with (directory / "log.txt").open("w") as log:
        code = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT, check=False).returncode  # noqa: S603
    wall_s = time.monotonic() - started
    text = (directory / "log.txt").read_text(errors="replace")
    stats = {key: int(value) for key, value in _STAT.findall(text)}
    done = _DONE.search(text)
    new = sorted(_findings(directory) - before)
    assets = directory / "assets" if TARGETS[name].storage else None
    return {
        "target": name,
        "date": datetime.now(UTC).isoformat(timespec="seconds"),
        "seconds_asked": seconds,
        "seconds_run": round(wall_s, 1),  # with seeds, start-up and minimizing
        "seconds_fuzzed": int(done[2]) if done else None,  # libFuzzer's own count
        "executions": stats.get("number_of_executed_units", int(done[1]) if done else 0),
        "new_units": stats.get("new_units_added", 0),
        "corpus_files": sum(1 for _ in (directory / "corpus").iterdir()),
        "peak_rss_mb": stats.get("peak_rss_mb", 0),
        "exit_code": code,
        "findings": [_describe(name, path, assets) for path in new],
    }


def _describe(name: str, path: Path, assets: Path | None) -> dict[str, str]:
    """The finding's error and its minimized input (``minimized/`` beside it)."""
    data = path.read_bytes()
    how = failure(TARGETS[name], data, assets)
    if how is None:
        return {"file": str(path), "error": "does not fail when re-run (a timeout or an oom?)"}
    small = minimize(TARGETS[name], data, assets, budget_s=MINIMIZE_S)
    kept = path.parent / "minimized" / _regression_name(name, small)
    kept.parent.mkdir(exist_ok=True)
    kept.write_bytes(small)
    return {"file": str(path), "error": f"{how[0]} at {how[1]}: {how[2]}", "minimized": str(kept)}


def _regression_name(name: str, data: bytes) -> str:
    suffix = Path(TARGETS[name].file_name).suffix
    return f"{hashlib.sha1(data).hexdigest()[:12]}{suffix}"  # noqa: S324 - a name, not security


def _record(out: Path, run: dict[str, Any]) -> None:
    summary = out / "summary.json"
    runs = json.loads(summary.read_text()) if summary.is_file() else []
    runs.append(run)
    summary.write_text(json.dumps(runs, indent=1) + "\n")


def _keep(name: str, finding: Path, out: Path) -> Path:
    assets = None
    if TARGETS[name].storage:
        assets = write_assets(out / name / "assets")
    data = minimize(TARGETS[name], finding.read_bytes(), assets)
    kept = CORPUS / name / _regression_name(name, data)
    kept.parent.mkdir(parents=True, exist_ok=True)
    kept.write_bytes(data)
    return kept


def _say(line: str) -> None:
    sys.stdout.write(line + "\n")
    sys.stdout.flush()


def main(argv: list[str] | None = None) -> int:
    """Fuzz the targets (all when none is named) or minimize one finding; the exit code."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("targets", nargs="*", help=f"any of {', '.join(TARGETS)}")
    parser.add_argument("--seconds", type=int, default=600, help="per target")
    parser.add_argument("--out", type=Path, default=Path("out/fuzz"))
    parser.add_argument("--minimize", nargs=2, metavar=("TARGET", "FINDING"))
    args = parser.parse_args(argv)
    if args.minimize:
        name, finding = args.minimize
        kept = _keep(name, Path(finding), args.out)
        _say(f"{name}: {Path(finding).stat().st_size} -> {kept.stat().st_size} bytes: {kept}")
        return 0
    unknown = sorted(set(args.targets) - set(TARGETS))
    if unknown:
        parser.error(f"unknown target(s) {', '.join(unknown)}; known: {', '.join(TARGETS)}")
    found = 0
    for name in args.targets or list(TARGETS):
        run = _fuzz_one(name, args.seconds, args.out)
        _record(args.out, run)
        found += len(run["findings"])
        _say(
            f"{name:24s} {run['seconds_run']:7.1f} s {run['executions']:9d} runs "
            f"corpus {run['corpus_files']:5d} findings {len(run['findings'])}"
        )
        for item in run["findings"]:
            _say(f"  {item['file']}: {item['error']}")
            if "minimized" in item:
                _say(f"    minimized: {item['minimized']}")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
