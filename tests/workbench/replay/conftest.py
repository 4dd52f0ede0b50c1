import pytest
import rerun as rr


@pytest.fixture(autouse=True)
def _isolated_rerun(tmp_path, monkeypatch):
    """Keep Rerun's config/data dirs in tmp and make bad input an error, not a warning."""
    home = tmp_path / "home"
    home.mkdir()
    monkeypatch.setenv("HOME", str(home))
    monkeypatch.setenv("XDG_CONFIG_HOME", str(home / ".config"))
    monkeypatch.setenv("XDG_DATA_HOME", str(home / ".local/share"))
    monkeypatch.setenv("XDG_CACHE_HOME", str(home / ".cache"))
    rr.set_strict_mode(True)
    yield
    rr.set_strict_mode(False)
