"""Review labels: the SQLite label store and its ASAM OpenLABEL import/export."""

from workbench.annotations.errors import StoreCorruptError, StoreError, StoreLockedError
from workbench.annotations.paths import default_store_path
from workbench.annotations.schema import SCHEMA_VERSION, VERDICTS
from workbench.annotations.store import Label, LabelStore

__all__ = [
    "SCHEMA_VERSION",
    "VERDICTS",
    "Label",
    "LabelStore",
    "StoreCorruptError",
    "StoreError",
    "StoreLockedError",
    "default_store_path",
]
