"""Build the compiled twins of ``rss.compiled.MODULES`` into ``build/compiled/`` (mypyc).

Run by ``make`` (any target that evaluates scenes). Without a C compiler or mypyc the build
is skipped with a message and everything runs from the sources. The new build replaces the
old one only when complete, with a manifest of the sources' sha256 (``rss/compiled.py``).
"""

from __future__ import annotations

import json
import os
import shutil
import sys
import sysconfig
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from rss.compiled import BUILD_DIR, GROUP, MODULES, source_digests  # noqa: E402


def _compiler() -> str | None:
    cc = (sysconfig.get_config_var("CC") or "cc").split()[0]
    return shutil.which(cc)


def main() -> int:
    """Build, or say why not (exit 0 either way unless the compiler itself fails)."""
    try:
        from mypyc.build import mypycify  # noqa: PLC0415 - optional build tool
        from setuptools import setup  # noqa: PLC0415
    except ImportError as exc:
        print(f"build_compiled: skipped ({exc}); scene creation runs from the sources")
        return 0
    if _compiler() is None:
        print("build_compiled: skipped (no C compiler); scene creation runs from the sources")
        return 0
    digests = source_digests()
    sources = [m.replace(".", "/") + ".py" for m in MODULES]
    print(f"build_compiled: compiling {len(sources)} modules with mypyc (about a minute)")
    os.chdir(ROOT)
    with tempfile.TemporaryDirectory(prefix="rss-compiled-") as tmp:
        work = Path(tmp)
        extensions = mypycify(
            sources, opt_level="3", group_name=GROUP, target_dir=str(work / "c"), verbose=False
        )
        setup(
            name=GROUP,
            ext_modules=extensions,
            script_args=[
                "--quiet",
                "build_ext",
                "--build-lib",
                str(work / "lib"),
                "--build-temp",
                str(work / "tmp"),
                "--parallel",
                str(os.cpu_count() or 1),
            ],
        )
        manifest = {
            "modules": list(MODULES),
            "sha256": digests,
            "ext_suffix": sysconfig.get_config_var("EXT_SUFFIX"),
            "python": sys.version.split()[0],
        }
        (work / "lib" / "manifest.json").write_text(json.dumps(manifest, indent=1) + "\n")
        staged = BUILD_DIR.with_name(BUILD_DIR.name + ".new")
        shutil.rmtree(staged, ignore_errors=True)
        staged.parent.mkdir(parents=True, exist_ok=True)
        shutil.copytree(work / "lib", staged)
    shutil.rmtree(BUILD_DIR, ignore_errors=True)
    staged.rename(BUILD_DIR)
    print(f"build_compiled: {BUILD_DIR.relative_to(ROOT)} ready")
    return 0


if __name__ == "__main__":
    sys.exit(main())
