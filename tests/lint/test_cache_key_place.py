"""The cache's signing key is never where the repository being checked is (docs/attacks.md,
session 8): with ``XDG_CACHE_HOME`` relative (the XDG specification says to ignore it) or a
relative ``HOME``, the key was read from the working folder, so a pull request committing
``urdftool/key`` (or ``.cache/urdftool/key``) signed the ``.urdftool_cache`` entries it
committed beside it. ``cache._secret`` takes only absolute places."""

from __future__ import annotations

import pytest

from urdftool.lint import cache

PLANTED = "ab" * 32


@pytest.mark.parametrize("environ", [
    {"XDG_CACHE_HOME": "."},
    {"XDG_CACHE_HOME": "", "HOME": "."},
    {"XDG_CACHE_HOME": "cache", "HOME": "."},
])
def test_a_relative_cache_home_never_takes_a_key_from_the_working_folder(
        tmp_path, monkeypatch, environ):
    for planted in (tmp_path / "urdftool", tmp_path / ".cache" / "urdftool",
                    tmp_path / "cache" / "urdftool"):
        planted.mkdir(parents=True)
        (planted / "key").write_text(PLANTED)
    monkeypatch.chdir(tmp_path)
    for name, value in environ.items():
        monkeypatch.setenv(name, value)
    if "HOME" not in environ:
        monkeypatch.setenv("HOME", str(tmp_path / "home"))
    key = cache._secret()
    assert key != PLANTED.encode()
    if "HOME" not in environ:  # XDG ignored: the key is made under the absolute HOME
        assert key is not None and (tmp_path / "home" / ".cache" / "urdftool" / "key").is_file()
    else:
        assert key is None  # no absolute place: no cache rather than the repository's key
