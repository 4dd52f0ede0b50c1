"""Loader error messages stay one printable line whatever a damaged file puts in them."""

from __future__ import annotations

from loaders.errors import MAX_DETAIL_CHARS, CorruptLogError


def test_multi_line_library_detail_becomes_one_line_and_is_cut() -> None:
    definition = "Could not parse:\n" + "MSG: pkg/Type\nfloat64 x\n" * 100
    err = CorruptLogError("/logs/drive.mcap", definition, topic="/objects", t_ns=5, offset=9)
    text = str(err)
    assert "\n" not in text
    assert text.startswith("/logs/drive.mcap, topic /objects, t=5 ns, offset 9: ")
    assert "Could not parse: MSG: pkg/Type float64 x" in text
    detail = text.split("corrupted: ", 1)[1]
    assert len(detail) == MAX_DETAIL_CHARS
    assert detail.endswith("...")
    assert err.detail == definition  # the field keeps what was given


def test_topic_with_control_characters_is_escaped() -> None:
    err = CorruptLogError("/logs/drive.mcap", "bad", topic="/\x00a\nb")
    assert str(err) == "/logs/drive.mcap, topic /\\x00a\\nb: log is truncated or corrupted: bad"


def test_long_value_is_cut() -> None:
    err = CorruptLogError("/x.bag", "bad row", value="v" * 1000)
    assert "\n" not in str(err)
    assert len(str(err)) < 400
