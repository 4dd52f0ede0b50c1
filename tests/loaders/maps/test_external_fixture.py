import pytest

from tests.conftest import EXTERNAL_DIR, require_external_dir, running_in_ci


def test_missing_external_dir_skips_locally(tmp_path):
    with pytest.raises(pytest.skip.Exception, match="external test data not found"):
        require_external_dir(tmp_path / "absent", ci=False)


def test_missing_external_dir_fails_in_ci(tmp_path):
    with pytest.raises(pytest.fail.Exception, match="CI=true"):
        require_external_dir(tmp_path / "absent", ci=True)


def test_present_dir_is_returned(tmp_path):
    assert require_external_dir(tmp_path, ci=True) == tmp_path


def test_ci_flag(monkeypatch):
    monkeypatch.setenv("CI", "true")
    assert running_in_ci()
    monkeypatch.setenv("CI", "")
    assert not running_in_ci()


def test_external_dir_is_the_sibling_shared_folder():
    assert EXTERNAL_DIR.parts[-2:] == ("shared", "external")
