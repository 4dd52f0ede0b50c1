"""Extension point: severity facts an engine's verdicts carry beyond the margin.

The built-in facts (worst margin, unsafe frames, duration) come from every verdict's summary
fields. An engine (or the triage work on responsibility and compliance) adds its own by
registering a collector factory for its engine name::

    class WhoMustAct:
        def add(self, frame, t_ns, verdict, object_id): ...   # every unsafe frame
        def facts(self): return {"must_respond": "ego"}       # once the incident ends

    register_facts("rss", WhoMustAct)

One collector is made per incident and sees that incident's unsafe frames in order (its own
engine's full typed verdicts); its facts land in ``Severity.facts`` and in every output.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Protocol

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping

    from workbench.incidents.model import Fact

__all__ = ["FactCollector", "collectors_for", "register_facts", "unregister_facts"]


class FactCollector(Protocol):
    """Collects severity facts over one incident's unsafe frames."""

    def add(self, frame: int, t_ns: int, verdict: Any, object_id: str) -> None:
        """One unsafe frame of the incident (``verdict``: the engine's own typed verdict)."""
        ...

    def facts(self) -> Mapping[str, Fact]:
        """The facts by name (names unique across the collectors of one engine)."""
        ...


_FACTORIES: dict[str, list[Callable[[], FactCollector]]] = {}


def register_facts(engine: str, factory: Callable[[], FactCollector]) -> None:
    """Make ``factory()`` collect facts of every incident of ``engine``."""
    _FACTORIES.setdefault(engine, []).append(factory)


def unregister_facts(engine: str, factory: Callable[[], FactCollector]) -> None:
    """Remove a factory added by :func:`register_facts` (tests)."""
    _FACTORIES.get(engine, []).remove(factory)


def collectors_for(engine: str, own: Callable[[], FactCollector] | None) -> list[FactCollector]:
    """Fresh collectors for one incident of ``engine``.

    The engine's own (``own``: its spec's ``incident_facts``) first, then the registered ones.
    """
    factories = ([own] if own is not None else []) + _FACTORIES.get(engine, [])
    return [factory() for factory in factories]
