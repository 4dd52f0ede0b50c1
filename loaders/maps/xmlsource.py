"""Reading an XML map document from a path or from bytes, with errors as ``MapError``."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

from loaders.errors import MapError

__all__ = ["read_xml_root"]


def read_xml_root(source: Path | bytes, name: str | None) -> tuple[ET.Element, str]:
    """Parse an XML map document.

    Args:
        source: Path of the file, or its bytes.
        name: Label for the map and its errors; defaults to the path, or ``<bytes>``.

    Returns:
        The root element and the label.

    Raises:
        MapError: If the file cannot be opened or the XML is malformed (with line and
            column).
    """
    label = name or (str(source) if isinstance(source, Path) else "<bytes>")
    try:
        data = source.read_bytes() if isinstance(source, Path) else source
        # expat refuses external entities and limits entity expansion; maps are local files.
        root = ET.fromstring(data)  # noqa: S314
    except OSError as err:
        raise MapError(label, f"cannot open: {err.strerror}") from err
    except ET.ParseError as err:
        line, col = err.position
        raise MapError(label, f"malformed XML at line {line}, column {col}") from err
    return root, label
