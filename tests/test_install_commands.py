"""Every install command that the README, the docs and urdftool's own hints print works as
written. urdftool is not on PyPI: each command names a checkout (a path, editable or not) or a
git URL, with extras that pyproject.toml declares, in a form pip's own parser accepts (checked
with pip's parser, without the network; a placeholder path such as /path/to/urdftool stands for
this checkout). Hints are built in one place, urdftool.origin.install_command."""

from __future__ import annotations

import ast
import re
import shlex
import tomllib
from pathlib import Path

import pytest

from conftest import ROOT, walked
from urdftool.origin import Origin

EXTRAS = set(tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
             ["optional-dependencies"])
# where pip install commands are shown to people; CHANGELOG.md quotes old ones as history
DOCUMENTS = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
_OPTIONS_WITH_VALUE = {"-r", "--requirement", "-c", "--constraint", "-t", "--target", "--python",
                       "-i", "--index-url", "--extra-index-url", "-f", "--find-links"}


def _commands_in(text: str) -> list[str]:
    """Each ``pip install`` command of a Markdown page: in code spans and code blocks."""
    found = []
    for block in re.findall(r"```[^\n]*\n(.*?)```", text, re.S):
        found += [line for line in block.splitlines() if "pip install" in line]
    prose = re.sub(r"```.*?```", "", text, flags=re.S)
    found += [" ".join(span.split()) for span in re.findall(r"`([^`]*pip\s+install[^`]*)`", prose)]
    commands = []
    for line in found:
        start = line.index("pip install")
        quote = line[start - 1] if start and line[start - 1] in "\"'" else None
        end = line.find(quote, start) if quote else -1  # a command quoted in JSON or YAML
        commands.append(line[start:end if end >= 0 else None])
    return commands


def _requirements(command: str) -> list[tuple[bool, str]]:
    """(editable, requirement) of each requirement a ``pip install ...`` command names."""
    words = shlex.split(command, comments=True)
    words = words[words.index("install") + 1:]
    found, editable, skip = [], False, False
    for word in words:
        if skip:
            skip = False
        elif word in ("&&", "||", ";", "|") or word.startswith("("):
            break
        elif word in ("-e", "--editable"):
            editable = True
        elif word in _OPTIONS_WITH_VALUE:
            skip = True
        elif not word.startswith("-"):
            found.append((editable, word))
            editable = False
    return found


def _accepted(editable: bool, requirement: str, placeholder: bool) -> str | None:
    """What is wrong with ``requirement`` for pip, or None. A path is this checkout's stand-in
    when ``placeholder`` (documents), else it must exist (hints)."""
    from pip._internal.exceptions import InstallationError
    from pip._internal.req.constructors import install_req_from_editable, install_req_from_line

    extras = set(re.findall(r"\[([^\]]*)\]", requirement.split(" @ ")[0])[0].split(",")) \
        if "[" in requirement.split(" @ ")[0] else set()
    extras = {e.strip() for e in extras if e.strip()}
    if extras - EXTRAS:
        return f"extras {sorted(extras - EXTRAS)} are not in pyproject.toml ({sorted(EXTRAS)})"
    path_like = requirement.startswith((".", "/", "~")) or (
        "/" in requirement.split("[")[0] and " @ " not in requirement and "://" not in requirement)
    if path_like:
        folder = requirement.split("[")[0]
        if placeholder:
            requirement = str(ROOT) + requirement[len(folder):]
        elif not (Path(folder) / "pyproject.toml").is_file():
            return f"{folder} is not a checkout of urdftool"
    try:
        made = (install_req_from_editable if editable else install_req_from_line)(requirement)
    except InstallationError as error:
        return f"pip refuses it: {error}"
    if made.link is None and (made.name or "").lower() == "urdftool":
        return "urdftool is not on PyPI: name a checkout (a path) or a git URL"
    if made.link is not None and " @ " in requirement:
        if made.name != "urdftool" or not made.link.url.startswith(("git+https://", "git+ssh://",
                                                                    "https://", "file://")):
            return f"not a git URL of urdftool: {made.link.url}"
    return None


def _documented():
    for page in DOCUMENTS:
        for command in _commands_in(page.read_text(encoding="utf-8")):
            yield pytest.param(command, id=f"{page.relative_to(ROOT)}: {command}")


@pytest.mark.parametrize("command", list(_documented()))
def test_every_documented_install_command_works_as_written(command):
    requirements = _requirements(command)
    assert requirements, f"no requirement in {command!r}"
    problems = [f"{spec}: {problem}" for editable, spec in requirements
                if (problem := _accepted(editable, spec, placeholder=True))]
    assert not problems, problems


def test_the_documents_show_the_install_forms():
    commands = [c for page in DOCUMENTS for c in _commands_in(page.read_text(encoding="utf-8"))]
    assert any("-e '.[analysis]'" in c for c in commands)
    assert any("@ git+https://" in c for c in commands)


@pytest.mark.parametrize("bad", ["pip install urdftool", "pip install 'urdftool[analysis]'",
                                 "pip install -e '.[nope]'", "pip install '/x y/urdftool[lsp]'"])
def test_the_check_can_fail(bad):
    assert any(_accepted(editable, spec, placeholder=bad.startswith("pip install -e"))
               for editable, spec in _requirements(bad))


# ---- the hints urdftool prints --------------------------------------------------------------

def _string_constants(path: Path):
    for node in walked(path.read_text(encoding="utf-8")):
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            yield node.lineno, node.value


def test_hints_are_built_in_one_place():
    """No module spells out a pip command: each asks urdftool.origin.install_command, so every
    hint names where the urdftool that runs came from."""
    spelt = [f"{path.relative_to(ROOT)}:{line}" for path in sorted((ROOT / "urdftool").rglob("*.py"))
             if path.name != "origin.py"
             for line, value in _string_constants(path) if "pip install" in value]
    assert not spelt, spelt


def _extras_named_in_code() -> set[str]:
    named = set()
    for path in (ROOT / "urdftool").rglob("*.py"):
        source = path.read_text(encoding="utf-8")
        for node in walked(source):
            if isinstance(node, ast.Call) and getattr(node.func, "id", None) == "install_command":
                named |= {a.value for a in node.args if isinstance(a, ast.Constant)}
            if isinstance(node, ast.Constant) and isinstance(node.value, str) \
                    and node.value.startswith("extra:"):
                named.add(node.value.removeprefix("extra:"))
    named.discard("")  # the prefix itself, where it is read
    return named


def test_every_extra_a_hint_names_exists():
    named = _extras_named_in_code()
    assert {"analysis", "lsp", "sim", "drake"} <= named
    assert named <= EXTRAS, named - EXTRAS


@pytest.mark.parametrize("extra", [None, *sorted(EXTRAS)])
def test_the_hint_of_this_install_works_as_written(extra):
    """Here urdftool runs from this checkout: the hint is an editable install of it."""
    from urdftool.origin import install_command

    command = install_command(extra)
    assert command.startswith("pip install -e ") and str(ROOT) in command
    ((editable, spec),) = _requirements(command)
    assert editable and _accepted(editable, spec, placeholder=False) is None


@pytest.mark.parametrize("where", [
    Origin(folder=ROOT), Origin(url="https://github.com/you/urdftool", commit="0123abc"),
    Origin(url="ssh://git@git.example.com/you/urdftool.git", commit="v1")])
def test_the_hint_of_other_installs_works_as_written(monkeypatch, where):
    from urdftool import origin

    monkeypatch.setattr(origin, "origin", lambda: where)
    for extra in sorted(EXTRAS):
        ((editable, spec),) = _requirements(origin.install_command(extra))
        assert _accepted(editable, spec, placeholder=False) is None, spec


def test_the_hint_without_a_source_names_a_clone():
    """Nothing says where urdftool came from: a clone's path, said to be one."""
    from urdftool import origin

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(origin, "origin", lambda: Origin())
        text = origin.install_command("analysis")
    ((editable, spec),) = _requirements(text)
    assert "a clone" in text and _accepted(editable, spec, placeholder=True) is None
