"""Child process of the store tests: writes labels and prints each committed event id.

Usage: python -m tests.workbench.annotations.writer_child STORE PREFIX COUNT
(COUNT 0: write until killed).
"""

from __future__ import annotations

import itertools
import sys
from pathlib import Path

from workbench.annotations import LabelStore


def main() -> None:
    """Write ``COUNT`` labels ``PREFIX-<n>``, printing ``<n> <event id>`` after each commit."""
    store_path, prefix, count = Path(sys.argv[1]), sys.argv[2], int(sys.argv[3])
    numbers = itertools.count() if count == 0 else range(count)
    with LabelStore(store_path, timeout_s=30.0) as store:
        for n in numbers:
            event = store.put(
                "drive", f"{prefix}-{n}", "confirmed", tags=[prefix], note=f"n={n}", reviewer=prefix
            )
            sys.stdout.write(f"{n} {event}\n")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
