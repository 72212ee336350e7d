"""A companion or settings file named that cannot be reached says why (files.unreachable), as
every command's robot paths do (docs/attacks.md, session 8, second wave): a link loop or a
path through a file was said "does not exist" (``--controllers``, ``--srdf``, ``--spec``) or
"does not exist or is not a file" (``--config``)."""

from __future__ import annotations

from pathlib import Path

import pytest

from urdftool.description.inputs import CompanionPaths
from urdftool.errors import SettingsError
from urdftool.lint.settings import check_companions, settings_file


@pytest.fixture
def places(tmp_path) -> dict[str, Path]:
    (tmp_path / "one").symlink_to(tmp_path / "two")
    (tmp_path / "two").symlink_to(tmp_path / "one")
    (tmp_path / "file.yaml").write_text("a: 1\n")
    return {"a link loop": (tmp_path / "one", "too many levels of symbolic links"),
            "below a file": (tmp_path / "file.yaml" / "x.yaml", "a part of it is a file")}


@pytest.mark.parametrize("where", ["a link loop", "below a file"])
@pytest.mark.parametrize("option", ["controllers", "srdf", "spec"])
def test_a_companion_named_that_cannot_be_reached_says_why(places, where, option):
    path, why = places[where]
    named = CompanionPaths(**{option: (path,) if option == "controllers" else path})
    with pytest.raises(SettingsError, match=why):
        check_companions(named)


@pytest.mark.parametrize("where", ["a link loop", "below a file"])
def test_a_settings_file_named_that_cannot_be_reached_says_why(places, where):
    path, why = places[where]
    with pytest.raises(SettingsError, match=why):
        settings_file(path)
