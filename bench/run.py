"""Run every benchmark and write ``docs/benchmarks.md`` with the machine and date.

Each ``bench/bench_*.py`` module exposes ``run(quick: bool) -> str`` returning a Markdown
section (heading level 2) with its measured table. Modules run in name order, one at a time
(so they do not compete for the two cores), each in a fresh interpreter.

``--update`` re-measures some sections only: each section the named modules return replaces
the section of the same heading in the existing report (new headings are appended at the
end), the rest is kept, and the header names the sections,
date and commit of this run beside the date of the full run.
"""

from __future__ import annotations

import argparse
import datetime as dt
import os
import platform
import re
import subprocess
import sys
import tempfile
from pathlib import Path


def _machine() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    mem_gib = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30
    return (
        f"{cpu}, {os.cpu_count()} cores, {mem_gib:.0f} GiB, {platform.system()} "
        f"{platform.release()}, Python {platform.python_version()}"
    )


def _commit() -> str:
    try:
        out = subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"],  # noqa: S607
            capture_output=True,
            text=True,
            check=False,
        )
    except OSError:
        return "unknown"
    return out.stdout.strip() or "unknown"


def _section(name: str, *, quick: bool) -> str:
    """``bench.<name>.run(quick)`` in a fresh interpreter: its Markdown section.

    Each module starts from the same state (no heap, caches or collector generations
    left by the modules before it; a late module measured ~20 % slower in one process).
    The section comes back through a file: references print to stdout themselves.
    """
    if not re.fullmatch(r"bench_\w+", name):
        raise SystemExit(f"not a benchmark module name: {name!r}")
    code = (
        "import sys\n"
        "from pathlib import Path\n"
        f"from bench import {name} as module\n"
        "Path(sys.argv[2]).write_text(module.run(quick=sys.argv[1] == '1'), encoding='utf-8')\n"
    )
    with tempfile.TemporaryDirectory(prefix="bench-") as tmp:
        out = Path(tmp) / "section.md"
        subprocess.run(  # noqa: S603 - this interpreter running our own module
            [sys.executable, "-c", code, "1" if quick else "0", str(out)],
            check=True,
            cwd=Path(__file__).resolve().parents[1],
        )
        return out.read_text(encoding="utf-8")


def _split(text: str) -> tuple[str, list[tuple[str, str]]]:
    """The text before the first level-2 heading, and (heading, section) pairs."""
    parts = re.split(r"(?m)^(?=## )", text)
    return parts[0], [(part.splitlines()[0], part) for part in parts[1:]]


def _updated(report: str, new_text: str, today: str) -> str:
    """``report`` with the sections of ``new_text`` replaced by heading (see the docstring)."""
    header, old = _split(report)
    _, new = _split(new_text)
    fresh = dict(new)
    placed = [(h, fresh.pop(h, s)) for h, s in old]
    placed += list(fresh.items())
    names = ", ".join(f'"{h.removeprefix("## ")}"' for h, _ in new)
    note = (
        f"Re-measured on {today}, commit `{_commit()}`, these modules alone "
        f"(`bench.run --update`): {names}.\n\n"
    )
    header = re.sub(r"(?m)^Re-measured on .*\n\n", "", header)
    first, _, rest = header.partition("\n\n")
    header = f"{first}\n\n{note}{rest}"
    return header + "".join(s.rstrip() + "\n\n" for _, s in placed).rstrip() + "\n"


def main(argv: list[str] | None = None) -> int:
    """Run the benchmarks named on the command line (all by default) and write the report."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", type=Path, default=Path("docs/benchmarks.md"))
    parser.add_argument("--quick", action="store_true", help="smaller workloads (smoke run)")
    parser.add_argument(
        "--update",
        action="store_true",
        help="replace only the sections these modules write in the existing report",
    )
    parser.add_argument("only", nargs="*", help="bench module names, e.g. bench_replay")
    args = parser.parse_args(argv)
    here = Path(__file__).parent
    names = args.only or sorted(p.stem for p in here.glob("bench_*.py"))
    sections = []
    for name in names:
        print(f"running {name} ...", file=sys.stderr, flush=True)
        sections.append(_section(name, quick=args.quick).rstrip() + "\n")
    today = dt.datetime.now(tz=dt.UTC).date().isoformat()
    if args.update:
        args.out.write_text(_updated(args.out.read_text(), "\n".join(sections), today))
        print(f"updated {args.out}", file=sys.stderr)
        return 0
    header = (
        "# Benchmarks\n\n"
        f"Measured by `make bench` on {today}, commit `{_commit()}`.\n\n"
        f"Machine: {_machine()}.\n\n"
        "Every number below comes from that one run; engines and their reference "
        "implementations ran side by side in the same run where a reference exists (in the "
        "same process, or for ad-rss-map-integration in its own interpreter). "
        "Before/after measurements and analyses of past speed work: "
        "[speed history](speed-history.md) (kept by hand; this file is rewritten whole).\n\n"
    )
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(header + "\n".join(sections))
    print(f"wrote {args.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
