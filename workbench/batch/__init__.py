"""Fleet batches: many drives on a process pool, Dask or Ray, one results directory.

See docs/fleet.md.
"""

from workbench.batch.executors import BatchError, open_pool
from workbench.batch.results import Results, is_results_dir
from workbench.batch.run import BatchSummary, expand_logs, requests_for, run_batch
from workbench.batch.task import evaluate_log

__all__ = [
    "BatchError",
    "BatchSummary",
    "Results",
    "evaluate_log",
    "expand_logs",
    "is_results_dir",
    "open_pool",
    "requests_for",
    "run_batch",
]
