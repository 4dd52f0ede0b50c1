"""No code outside the engines' folders knows an engine by name.

What is checked, precisely: in every Python module of ``workbench/`` outside
``workbench/engines/`` and of ``loaders/``,

* no string constant (docstrings excepted: they are documentation) equals a built-in
  engine's name, one of its option flags (``--reach-method``) or their record keys
  (``reach_method``);
* no identifier (a name, an attribute or a keyword argument) equals an option's record
  key (``rss_profile=...``, ``request.reach_method``);
* no module imports an engine's folder (``workbench.engines.rss``).

The engines' own code (``workbench/engines/`` and the pure ``rss`` and ``reachsets``
packages), the docs, the tests and the benchmark and tool scripts (users of the CLI, as the
docs are) may name engines. The one exception is listed in :data:`ALLOWED` with its reason.
Text that merely contains a name (``"rss-workbench"``, the distribution) is not an engine
identifier and is not flagged.
"""

from __future__ import annotations

import ast
from pathlib import Path

from workbench.engines.options import declared
from workbench.engines.registry import BUILTIN, engine

ROOT = Path(__file__).resolve().parents[3]
#: (module path, constant): ``workbench conformance rss`` names the conformance suite of the
#: pure ``rss`` library (DESIGN.md's pinned interface), not the engine; ``workbench
#: conformance reachsets`` likewise the pure ``reachsets`` library's (its ``--log``
#: conversion is the engine's ``case_document``, taken from the registry).
ALLOWED = {("workbench/cli/conformance.py", "rss"), ("workbench/cli/conformance.py", "reachsets")}


def _builtin_names() -> set[str]:
    return {module.rsplit(".", 1)[1] for module in BUILTIN}


def _option_words() -> tuple[set[str], set[str]]:
    flags, keys = set(), set()
    for name in _builtin_names():
        for d in declared(engine(name)):
            flags.add(d.meta.flag)
            keys.add(d.key)
    return flags, keys


def _docstrings(tree: ast.Module) -> set[int]:
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
                found.add(id(body[0].value))
    return found


def _sources() -> list[Path]:
    paths = [*(ROOT / "workbench").rglob("*.py"), *(ROOT / "loaders").rglob("*.py")]
    engines = ROOT / "workbench" / "engines"
    return sorted(p for p in paths if engines not in p.parents)


def _findings(rel: str, text: str, names: set[str], flags: set[str], keys: set[str]) -> list[str]:
    tree = ast.parse(text)
    docs = _docstrings(tree)
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docs:
            if node.value in names | flags | keys and (rel, node.value) not in ALLOWED:
                out.append(f"{rel}:{node.lineno}: {node.value!r}")
        elif isinstance(node, ast.Name | ast.Attribute | ast.keyword | ast.arg):
            word = (
                getattr(node, "id", None)
                or getattr(node, "attr", None)
                or getattr(node, "arg", None)
            )
            if word in keys:
                out.append(f"{rel}:{getattr(node, 'lineno', 0)}: identifier {word}")
        elif isinstance(node, ast.ImportFrom | ast.Import):
            modules = [node.module or ""] if isinstance(node, ast.ImportFrom) else []
            modules += [a.name for a in node.names] if isinstance(node, ast.Import) else []
            out.extend(
                f"{rel}:{node.lineno}: imports {m}"
                for m in modules
                if any(
                    m == f"workbench.engines.{n}" or m.startswith(f"workbench.engines.{n}.")
                    for n in names
                )
            )
    return out


def test_the_check_sees_the_engines_and_their_options() -> None:
    flags, keys = _option_words()
    assert _builtin_names() == {"rss", "unstructured", "reachsets"}
    assert {"--reach-method", "--rss-profile"} <= flags
    assert {"reach_method", "rss_profile"} <= keys
    assert len(_sources()) > 100


def test_no_engine_is_named_outside_the_engines() -> None:
    names = _builtin_names()
    flags, keys = _option_words()
    found = [
        f
        for path in _sources()
        for f in _findings(
            path.relative_to(ROOT).as_posix(), path.read_text(encoding="utf-8"), names, flags, keys
        )
    ]
    assert found == []


def test_the_check_finds_a_name_where_one_is_used() -> None:
    """The check is not vacuous: each kind of use in a module is found, docstrings are not."""
    names = _builtin_names()
    flags, keys = _option_words()
    text = (
        '"""A docstring naming rss is fine."""\n'
        "from workbench.engines.rss.options import RssOptions\n"
        "X = ('rss', '--reach-method', 'rss-workbench')\n"
        "f(rss_profile=1)\n"
    )
    found = _findings("workbench/probe.py", text, names, flags, keys)
    assert [f.split(": ", 1)[1] for f in found] == [
        "imports workbench.engines.rss.options",
        "'rss'",
        "'--reach-method'",
        "identifier rss_profile",
    ]
