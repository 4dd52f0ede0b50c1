"""Review labels: the SQLite label store and its ASAM OpenLABEL import/export."""

from workbench.annotations.errors import StoreCorruptError, StoreError, StoreLockedError
from workbench.annotations.paths import default_reviewer, default_store_path
from workbench.annotations.schema import SCHEMA_VERSION, VERDICTS, ReviewVerdict
from workbench.annotations.store import Label, LabelStore

__all__ = [
    "SCHEMA_VERSION",
    "VERDICTS",
    "Label",
    "LabelStore",
    "ReviewVerdict",
    "StoreCorruptError",
    "StoreError",
    "StoreLockedError",
    "default_reviewer",
    "default_store_path",
]
