import hashlib
import os

import pytest

from workbench.errors import WorkbenchError
from workbench.incidents import content, drive_content_hash


def test_file_hash_is_sha256_of_its_bytes_streamed_in_chunks(tmp_path, monkeypatch):
    monkeypatch.setattr(content, "CHUNK_BYTES", 7)
    data = bytes(range(256)) * 10
    log = tmp_path / "drive.mcap"
    log.write_bytes(data)
    assert drive_content_hash(log) == hashlib.sha256(data).hexdigest()


def test_same_bytes_same_hash_whatever_the_name_and_a_change_is_seen(tmp_path):
    a = tmp_path / "a.mcap"
    b = tmp_path / "b.mcap"
    a.write_bytes(b"drive")
    b.write_bytes(b"drive")
    assert drive_content_hash(a) == drive_content_hash(b)
    a.write_bytes(b"drive, edited")
    os.utime(a, ns=(1, 1))
    assert drive_content_hash(a) == hashlib.sha256(b"drive, edited").hexdigest()


def test_directory_hash_covers_names_and_contents(tmp_path):
    bag = tmp_path / "bag"
    bag.mkdir()
    (bag / "metadata.yaml").write_text("x")
    (bag / "bag_0.db3").write_bytes(b"y")
    expected = hashlib.sha256(b"bag_0.db3\0y" + b"metadata.yaml\0x").hexdigest()
    assert drive_content_hash(bag) == expected


def test_missing_file_is_a_one_line_error(tmp_path):
    with pytest.raises(WorkbenchError, match="cannot hash"):
        drive_content_hash(tmp_path / "gone.mcap")
