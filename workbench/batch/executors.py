"""Where a batch's tasks run: one small submit/gather seam over three engines.

| ``--cluster`` | engine | extra |
|---|---|---|
| (none) | a local process pool, ``--jobs N`` workers | — |
| ``tcp://HOST:PORT`` | a running Dask distributed scheduler | ``[dask]`` |
| ``dask-local:N`` | a ``LocalCluster``: N single-threaded processes on 127.0.0.1 | ``[dask]`` |
| ``ray://HOST:PORT`` | a running Ray cluster (Ray Client) | ``[ray]`` |
| ``ray-local:N`` | a local Ray instance with N CPUs (on 127.0.0.1) | ``[ray]`` |

Every pool hands out ``concurrent.futures.Future`` objects (Dask's ``get_executor``, Ray's
``ObjectRef.future()``), so the batch loop is the same for all. A future that fails did so
because its worker was lost (the task itself never raises): the loop calls
:meth:`Pool.recover` and submits the log again.
"""

from __future__ import annotations

import contextlib
import logging
import multiprocessing
import os
import time
from concurrent.futures import BrokenExecutor, Future, ProcessPoolExecutor
from typing import TYPE_CHECKING, Any, Protocol

from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from collections.abc import Callable, Iterator

__all__ = ["BatchError", "Pool", "ProcessPool", "open_pool", "parse_cluster"]


class BatchError(WorkbenchError):
    """A batch cannot start or finish: bad ``--cluster``, missing extra, unreachable cluster."""


class Pool(Protocol):
    """The seam: submit one task per log, get a ``concurrent.futures.Future``."""

    #: What the pool is, for the summary and ``batch.json`` (e.g. ``process pool, 2 workers``).
    name: str
    #: How many tasks run at once.
    workers: int

    def submit(self, fn: Callable[[Any], Any], arg: Any) -> Future[Any]:
        """Run ``fn(arg)`` on a worker."""
        ...

    def recover(self) -> None:
        """Make :meth:`submit` work again after a worker was lost."""
        ...


class ProcessPool:
    """The default: a local ``ProcessPoolExecutor`` (forkserver), rebuilt when a worker dies."""

    def __init__(self, jobs: int) -> None:
        """Start ``jobs`` worker processes."""
        self.workers = jobs
        self.name = f"process pool, {jobs} worker{'s' if jobs != 1 else ''}"
        self._executor = self._start()

    def _start(self) -> ProcessPoolExecutor:
        return ProcessPoolExecutor(
            self.workers, mp_context=multiprocessing.get_context("forkserver")
        )

    def submit(self, fn: Callable[[Any], Any], arg: Any) -> Future[Any]:
        """Run ``fn(arg)`` in a worker process."""
        return self._executor.submit(fn, arg)

    def recover(self) -> None:
        """A killed worker breaks the whole pool: start a fresh one (once per break)."""
        try:
            self._executor.submit(int).result()
        except BrokenExecutor:
            self._executor.shutdown(wait=False, cancel_futures=True)
            self._executor = self._start()

    def close(self) -> None:
        """Stop the workers."""
        self._executor.shutdown(wait=True, cancel_futures=True)


class _ExecutorPool:
    """A ``concurrent.futures.Executor`` someone else keeps alive (Dask's client executor)."""

    def __init__(self, executor: Any, name: str, workers: int) -> None:
        self._executor = executor
        self.name = name
        self.workers = workers

    def submit(self, fn: Callable[[Any], Any], arg: Any) -> Future[Any]:
        return self._executor.submit(fn, arg)  # type: ignore[no-any-return]

    def recover(self) -> None:
        """The scheduler reschedules a lost worker's tasks itself."""


class _RayPool:
    """Ray tasks as futures (``ObjectRef.future()``); Ray retries a lost worker's tasks."""

    def __init__(self, ray: Any, name: str) -> None:
        self._remote: dict[Callable[[Any], Any], Any] = {}
        self._ray = ray
        self.name = name
        self.workers = max(1, int(ray.cluster_resources().get("CPU", 1)))

    def submit(self, fn: Callable[[Any], Any], arg: Any) -> Future[Any]:
        if fn not in self._remote:
            self._remote[fn] = self._ray.remote(max_retries=3, num_cpus=1)(fn)
        return self._remote[fn].remote(arg).future()  # type: ignore[no-any-return]

    def recover(self) -> None:
        """Ray resubmits a lost worker's tasks itself."""


def parse_cluster(cluster: str) -> tuple[str, str]:
    """``(kind, where)`` of a ``--cluster`` value.

    ``kind`` is ``dask``, ``dask-local``, ``ray`` or ``ray-local``; ``where`` the address or
    the worker count.

    Raises:
        BatchError: Not one of the accepted forms.
    """
    for prefix, kind in (
        ("tcp://", "dask"),
        ("dask-local:", "dask-local"),
        ("ray://", "ray"),
        ("ray-local:", "ray-local"),
    ):
        if cluster.startswith(prefix):
            where = cluster.removeprefix(prefix) if kind.endswith("-local") else cluster
            if kind.endswith("-local") and not (where.isdigit() and int(where) > 0):
                break
            return kind, where
    msg = (
        f"--cluster {cluster!r}: expected tcp://HOST:PORT, dask-local:N, ray://HOST:PORT"
        " or ray-local:N (N > 0)"
    )
    raise BatchError(msg)


def _need(module: str, extra: str, cluster: str) -> Any:
    import importlib  # noqa: PLC0415

    try:
        return importlib.import_module(module)
    except ImportError as err:
        msg = (
            f"--cluster {cluster}: {module} is not installed (pip install 'rss-workbench[{extra}]')"
        )
        raise BatchError(msg) from err


@contextlib.contextmanager
def _dask(kind: str, where: str, cluster: str) -> Iterator[Pool]:
    distributed = _need("distributed", "dask", cluster)
    with contextlib.ExitStack() as stack:
        try:
            if kind == "dask-local":
                local = distributed.LocalCluster(
                    n_workers=int(where),
                    threads_per_worker=1,
                    processes=True,
                    dashboard_address=None,
                    host="127.0.0.1",
                    silence_logs=logging.ERROR,
                )
                stack.enter_context(local)
                client = stack.enter_context(distributed.Client(local))
            else:
                client = stack.enter_context(distributed.Client(where, timeout="20s"))
        except OSError as err:
            raise BatchError(f"--cluster {cluster}: cannot reach the scheduler ({err})") from err
        workers = sum(client.nthreads().values()) or 1
        executor = client.get_executor(pure=False, retries=3)
        yield _ExecutorPool(executor, f"dask {cluster}, {workers} worker thread(s)", workers)


def _ray_token_available() -> bool:
    """Whether a Ray authentication token is set or saved (``RAY_AUTH_TOKEN[_PATH]``, ~/.ray)."""
    from pathlib import Path  # noqa: PLC0415

    if os.environ.get("RAY_AUTH_TOKEN"):
        return True
    saved = os.environ.get("RAY_AUTH_TOKEN_PATH") or str(Path.home() / ".ray" / "auth_token")
    return Path(saved).is_file()


#: Ray Client connections tried before a batch gives up, and the pause between them [s].
RAY_CLIENT_ATTEMPTS, RAY_CLIENT_PAUSE_S = 3, 2.0


def _ray_client_connect(ray: Any, address: str) -> None:
    """``ray.init(address)`` through Ray Client, tried again when the server side fails.

    The head's client proxy starts one server process per client; on a busy head that
    start can fail ("Starting Ray client server failed", a ``ConnectionError``) and succeed
    a moment later. Other errors, and the last attempt's, go to the caller.
    """
    for attempt in range(1, RAY_CLIENT_ATTEMPTS + 1):
        try:
            ray.init(address=address, log_to_driver=False, logging_level=logging.WARNING)
        except ConnectionError:
            if attempt == RAY_CLIENT_ATTEMPTS:
                raise
            ray.shutdown()
            time.sleep(RAY_CLIENT_PAUSE_S)
        else:
            return


@contextlib.contextmanager
def _ray(kind: str, where: str, cluster: str) -> Iterator[Pool]:
    os.environ.setdefault("RAY_USAGE_STATS_ENABLED", "0")
    if kind == "ray-local":
        # Ray's single-machine mode (as on macOS): every address is 127.0.0.1, not the
        # machine's network address.
        os.environ.setdefault("RAY_ENABLE_WINDOWS_OR_OSX_CLUSTER", "0")
    elif "RAY_AUTH_MODE" not in os.environ and _ray_token_available():
        # A cluster started by `ray start` has token authentication on and writes the token
        # to ~/.ray/auth_token; a Ray Client sends it only in token mode.
        os.environ["RAY_AUTH_MODE"] = "token"
    ray = _need("ray", "ray", cluster)
    try:
        if kind == "ray-local":
            ray.init(
                address="local",
                num_cpus=int(where),
                include_dashboard=False,
                log_to_driver=False,
                logging_level=logging.WARNING,
            )
        else:
            _ray_client_connect(ray, where)
    except (ConnectionError, RuntimeError, ValueError) as err:
        detail = " ".join(str(err).split())
        raise BatchError(f"--cluster {cluster}: cannot start or reach Ray ({detail})") from err
    try:
        yield _RayPool(ray, f"ray {cluster}")
    finally:
        ray.shutdown()


@contextlib.contextmanager
def open_pool(cluster: str | None, jobs: int | None) -> Iterator[Pool]:
    """The pool ``--cluster`` / ``--jobs`` describe, closed on exit.

    Args:
        cluster: ``--cluster`` value; ``None``: a local process pool.
        jobs: Local worker processes (``None``: the CPU count).

    Raises:
        BatchError: Bad ``--cluster``, missing extra, unreachable cluster.
    """
    if cluster is None:
        local = ProcessPool(jobs or os.cpu_count() or 1)
        try:
            yield local
        finally:
            local.close()
        return
    kind, where = parse_cluster(cluster)
    opener = _dask if kind.startswith("dask") else _ray
    with opener(kind, where, cluster) as pool:
        yield pool
