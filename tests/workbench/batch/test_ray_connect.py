"""Ray Client connections are tried again when the head fails to start its client server."""

from __future__ import annotations

from typing import Any

import pytest

from workbench.batch import executors


class _FakeRay:
    """``ray.init`` failing the first ``failures`` times, as a busy head's client proxy does."""

    def __init__(self, failures: int) -> None:
        self.failures = failures
        self.calls: list[str] = []

    def init(self, address: str, **_: Any) -> None:
        self.calls.append(f"init {address}")
        if self.failures > 0:
            self.failures -= 1
            raise ConnectionError("Starting Ray client server failed")

    def shutdown(self) -> None:
        self.calls.append("shutdown")


@pytest.fixture(autouse=True)
def _no_pause(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(executors, "RAY_CLIENT_PAUSE_S", 0.0)


def test_a_failed_start_of_the_client_server_is_tried_again() -> None:
    ray = _FakeRay(failures=executors.RAY_CLIENT_ATTEMPTS - 1)
    executors._ray_client_connect(ray, "ray://127.0.0.1:1")
    inits = [c for c in ray.calls if c.startswith("init")]
    assert len(inits) == executors.RAY_CLIENT_ATTEMPTS
    assert ray.calls.count("shutdown") == executors.RAY_CLIENT_ATTEMPTS - 1


def test_the_last_failure_goes_to_the_caller() -> None:
    ray = _FakeRay(failures=executors.RAY_CLIENT_ATTEMPTS)
    with pytest.raises(ConnectionError, match="client server failed"):
        executors._ray_client_connect(ray, "ray://127.0.0.1:1")
    assert len([c for c in ray.calls if c.startswith("init")]) == executors.RAY_CLIENT_ATTEMPTS
