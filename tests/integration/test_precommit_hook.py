"""The ``.pre-commit-hooks.yaml`` definition, run by pre-commit itself on a temporary repository.

``pre-commit try-repo`` clones this repository and, as for any user, installs urdftool from the
clone into a fresh environment of its own (``pip install .``: the lint-only install). Here
pre-commit makes that environment with uv instead of virtualenv and pip (:data:`UV_PRE_COMMIT`,
as the pre-commit-uv plugin does), so the dependencies come from uv's cache that ``make``
filled rather than being downloaded, unpacked and compiled again: the hook's definition, the
package's build from the clone, its entry point and the lint-only behaviour are what is tested,
not pip. The install is done once for the module; the test is marked ``network`` (uv asks the
package index whether its cached versions are current; deselect with ``-m "not network"``).
"""

from __future__ import annotations

import os
import shutil
import socket
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ROBOTS, ROOT

PRE_COMMIT = [sys.executable, "-m", "pre_commit"]
# pre-commit, its Python hook environments made by uv (beside this interpreter, as make installs
# it) from its cache, instead of by virtualenv and pip from the package index
UV_PRE_COMMIT = """
import os, sys
from pre_commit import lang_base, main, store
from pre_commit.commands import try_repo
from pre_commit.languages import python
from pre_commit.util import cmd_output_b

def install_environment(prefix, version, additional_dependencies):
    folder = lang_base.environment_dir(prefix, python.ENVIRONMENT_DIR, version)
    cmd_output_b(UV, "venv", "--quiet", "--python", sys.executable, folder, cwd="/")
    with python.in_env(prefix, version):
        lang_base.setup_cmd(prefix, (UV, "pip", "install", "--quiet", ".",
                                     *additional_dependencies))

def health_check(prefix, version):  # uv writes 3.11.7 where virtualenv writes 3.11.7.final.0
    folder = lang_base.environment_dir(prefix, python.ENVIRONMENT_DIR, version)
    exists = os.path.isfile(prefix.path(python.bin_dir(folder), "python"))
    return None if exists else "no python in the environment"

python.install_environment, python.health_check = install_environment, health_check
# try-repo keeps its hook environments in a store of its own, in a folder it deletes at its
# end: each call installed urdftool again (3.4 s of CPU). They are kept in PRE_COMMIT_HOME, as
# `pre-commit run` keeps them for a user, so the second call uses the first's; a working tree
# with changes not committed is a new commit each call (try-repo's shadow), installed again.
try_repo.Store = lambda folder: store.Store()
sys.exit(main.main())
"""
UV = Path(sys.executable).parent / "uv"


def git(repo: Path, *args: str) -> None:
    subprocess.run(["git", "-c", "user.name=t", "-c", "user.email=t@example.com", *args],
                   cwd=repo, check=True, capture_output=True)


def test_manifest_is_valid():
    done = subprocess.run([*PRE_COMMIT, "validate-manifest", ".pre-commit-hooks.yaml"],
                          cwd=ROOT, capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr


@pytest.fixture(scope="module")
def hook(tmp_path_factory):
    """run(files) -> CompletedProcess of ``pre-commit try-repo ROOT urdftool --files ...``."""
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        pytest.skip("needs git and urdftool as a git checkout")
    if not UV.is_file():
        pytest.skip(f"needs uv at {UV}, as make installs it")
    try:
        socket.create_connection(("pypi.org", 443), timeout=5).close()
    except OSError:
        pytest.skip("PyPI is not reachable: pre-commit cannot install the hook")
    base = tmp_path_factory.mktemp("precommit")
    repo = base / "repo"
    shutil.copytree(ROBOTS, repo / "robots")
    wheel = repo / "robots" / "diffbot" / "wheel.xacro"
    wheel.write_text(wheel.read_text().replace('type="continuous"', 'type="contnuous"', 1))
    (repo / "urdftool.toml").write_text("notes = true\n")  # the text report hides them else
    git(repo, "init", "-q")
    git(repo, "add", "-A")
    git(repo, "commit", "-q", "-m", "robots")
    env = {**os.environ, "PRE_COMMIT_HOME": str(base / "cache"), "PRE_COMMIT_COLOR": "never"}

    def run(*files: str):
        return subprocess.run([sys.executable, "-c", f"UV = {str(UV)!r}\n{UV_PRE_COMMIT}",
                               "try-repo", str(ROOT), "urdftool", "--verbose",
                               "--files", *files], cwd=repo, env=env, capture_output=True,
                              text=True, timeout=600)

    return run


@pytest.mark.network
def test_changed_macro_fails_through_its_robot_and_clean_files_pass(hook):
    broken = hook("robots/diffbot/wheel.xacro", "robots/r2d2/r2d2.urdf.xacro")
    assert broken.returncode == 1, broken.stdout + broken.stderr
    assert "robots/diffbot/wheel.xacro:" in broken.stdout and "U201" in broken.stdout
    assert "2 files checked: 2 errors" in broken.stdout  # the left and the right wheel
    clean = hook("robots/humanoid/leg.xacro", "robots/r2d2/r2d2.urdf.xacro",
                 "robots/humanoid/joint_limits.yaml")
    assert clean.returncode == 0, clean.stdout + clean.stderr
    # pre-commit installs the lint-only urdftool: the humanoid's SRDF pose checks need FCL and
    # say so (U902 notes), nothing else is found; r2d2 has no SRDF, so nothing of it is missed
    # (U810, U811, U823; shown as the repository's settings ask: notes = true)
    assert "2 files checked: 0 errors, 0 warnings, 3 notes" in clean.stdout
    notes = [line for line in clean.stdout.splitlines() if " info " in line]
    assert len(notes) == 3 and all("U902" in line and "humanoid" in line for line in notes), \
        clean.stdout
