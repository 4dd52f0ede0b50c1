"""Reading XML documents (maps, CommonRoad scenarios) with every parser failure typed."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path
from typing import TYPE_CHECKING, Literal

from loaders.errors import MapError

if TYPE_CHECKING:
    from collections.abc import Iterator

    from loaders.errors import LoaderError

__all__ = ["iter_xml", "read_xml_root", "xml_failure"]

#: What expat raises besides ``ParseError``: an unknown (``LookupError``) or a multi-byte
#: (``ValueError``) encoding named by the XML declaration.
_DECODING = (LookupError, ValueError)


def xml_failure(err: Exception) -> str:
    """One line on why the parser stopped (``ParseError`` or a declared-encoding error)."""
    if isinstance(err, ET.ParseError):
        line, col = err.position
        return f"malformed XML at line {line}, column {col}"
    return f"undecodable XML: {err}"


def read_xml_root(source: Path | bytes, name: str | None) -> tuple[ET.Element, str]:
    """Parse an XML map document.

    Args:
        source: Path of the file, or its bytes.
        name: Label for the map and its errors; defaults to the path, or ``<bytes>``.

    Returns:
        The root element and the label.

    Raises:
        MapError: If the file cannot be opened or the XML is malformed (with line and
            column) or names an encoding the parser cannot read.
    """
    label = name or (str(source) if isinstance(source, Path) else "<bytes>")
    try:
        data = source.read_bytes() if isinstance(source, Path) else source
        # expat refuses external entities and limits entity expansion; maps are local files.
        root = ET.fromstring(data)  # noqa: S314
    except OSError as err:
        raise MapError(label, f"cannot open: {err.strerror}") from err
    except (ET.ParseError, *_DECODING) as err:
        raise MapError(label, xml_failure(err)) from err
    return root, label


def iter_xml(
    path: Path, events: tuple[Literal["start", "end"], ...], error: type[LoaderError]
) -> Iterator[tuple[str, ET.Element]]:
    """``ET.iterparse`` whose parser failures are ``error(path, ...)``.

    Errors raised by the caller's own handling of an event pass through unchanged.

    Raises:
        LoaderError: ``error`` naming the file, line and column, or the bad encoding.
    """
    events_iter = ET.iterparse(path, events=events)  # noqa: S314 - expat refuses external entities
    while True:
        try:
            item = next(events_iter)
        except StopIteration:
            return
        except (ET.ParseError, *_DECODING) as err:
            raise error(path, xml_failure(err)) from err
        yield item
