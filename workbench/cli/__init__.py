"""The ``workbench`` command line (thin: parsing and validation only)."""
