"""Apply the ad-rss-map-integration 5.0.0 wheel work-around (reference notes §8.4).

The wheel vendors its own copies of libad_map_access and libad_rss; loading both copies next
to the ``ad_map_access``/``ad_rss`` wheels' copies registers the same spdlog logger twice and
fails. Replacing the two vendored files by relative symlinks to the base wheels' copies makes
the dynamic loader reuse the objects already loaded. Run with the oracle venv's interpreter.
"""

from __future__ import annotations

import sysconfig
from pathlib import Path


def main() -> int:
    """Link the vendored libraries; idempotent."""
    site = Path(sysconfig.get_paths()["purelib"])
    vendored = site / "ad_rss_map_integration.libs"
    for stem, base in (("libad_map_access-", "ad_map_access.libs"), ("libad_rss-", "ad_rss.libs")):
        (target,) = sorted((site / base).glob(f"{stem}*.so"))
        for lib in vendored.glob(f"{stem}*.so"):
            lib.unlink()
            lib.symlink_to(Path("..") / base / target.name)
            print(f"{lib.name} -> ../{base}/{target.name}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
