"""Where this urdftool came from, and the two answers that follow from it: the command that adds
an extra to it, and the address of its rule documentation.

urdftool is not on the package index. It runs from a checkout (``pip install -e .``, or
``python -m urdftool`` in the folder), from a copy of a checkout (``pip install PATH``), or from
a git URL (``pip install 'urdftool @ git+https://...'``); pip records the last two in the
distribution's ``direct_url.json`` (PEP 610). An install command names that same source, so it
works as printed (``pip install 'urdftool[analysis]'`` would ask the package index, which has no
urdftool). The rule pages are ``docs/rules/CODE.md`` in the repository: a checkout's own files,
or the git host's page of them at the commit installed; ``URDFTOOL_DOCS_URL`` (the folder's
address) overrides both. It is read from the environment of whoever runs urdftool, never from a
robot repository's settings, which a pull request could point at any site.
"""

from __future__ import annotations

import functools
import json
import os
import re
import shlex
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import unquote, urlparse

DOCS_URL_VARIABLE = "URDFTOOL_DOCS_URL"
RULE_PAGES = "docs/rules"  # in the repository: one page per rule, RULE_PAGES/CODE.md
PLACEHOLDER = "/path/to/urdftool"  # a clone, when nothing says where urdftool came from
# the page of a file at a commit, on the hosts whose address scheme is known
_BLOB = {"github.com": "{repo}/blob/{commit}/{path}", "gitlab.com": "{repo}/-/blob/{commit}/{path}"}


@dataclass(frozen=True)
class Origin:
    """folder: the source folder installed from, when it still exists (a checkout, or the
    folder a path install copied); editable: the folder is what runs (``pip install -e``, or
    no install at all); url and commit: the git repository and commit installed from."""

    folder: Path | None = None
    editable: bool = False
    url: str | None = None
    commit: str | None = None


@functools.cache
def origin() -> Origin:
    """Where the urdftool that runs came from (see the module's docstring)."""
    here = Path(__file__).resolve().parent.parent
    if (here / "pyproject.toml").is_file():  # the package runs from its checkout
        return Origin(folder=here, editable=True)
    try:
        from importlib.metadata import PackageNotFoundError, distribution

        record = distribution("urdftool").read_text("direct_url.json")
    except (ImportError, PackageNotFoundError, OSError):
        record = None
    try:
        direct = json.loads(record) if record else {}
    except ValueError:
        direct = {}
    url = direct.get("url") if isinstance(direct, dict) else None
    if not isinstance(url, str):
        return Origin()
    vcs = direct.get("vcs_info")
    if isinstance(vcs, dict) and vcs.get("vcs") == "git":
        return Origin(url=url, commit=vcs.get("commit_id") or vcs.get("requested_revision"))
    if url.startswith("file://"):
        folder = Path(unquote(urlparse(url).path))
        if (folder / "pyproject.toml").is_file():
            editable = bool((direct.get("dir_info") or {}).get("editable"))
            return Origin(folder=folder, editable=editable)
    return Origin()


def install_command(extra: str | None = None) -> str:
    """The command that installs this urdftool again, with ``extra`` (``"analysis"``, ...): from
    the folder it came from, or the git URL and commit, or else a clone at a placeholder path."""
    where = origin()
    extras = f"[{extra}]" if extra else ""
    if where.folder is not None:
        flag = "-e " if where.editable else ""
        return f"pip install {flag}{shlex.quote(f'{where.folder}{extras}')}"
    if where.url is not None:
        at = f"@{where.commit}" if where.commit else ""
        return f"pip install {shlex.quote(f'urdftool{extras} @ git+{where.url}{at}')}"
    return (f"pip install {shlex.quote(f'{PLACEHOLDER}{extras}')}  "
            "(in a clone of the urdftool repository)")


def docs_base() -> str | None:
    """The address of the folder of rule pages, ending with ``/``; None when nothing says where
    they are (no link beats a dead one)."""
    configured = os.environ.get(DOCS_URL_VARIABLE, "").strip()
    if re.match(r"(https?|file)://[!#-;=?-\[\]_a-z~]+$", configured):  # a URI's characters
        # (RFC 3986; others percent-encoded): no control, blank, quote, angle bracket or
        # non-ASCII character, which end an address in a SARIF reader or a hover's link
        return configured if configured.endswith("/") else configured + "/"
    where = origin()
    if where.folder is not None and (where.folder / RULE_PAGES).is_dir():
        return (where.folder / RULE_PAGES).as_uri() + "/"
    if where.url is not None and where.commit:
        parsed = urlparse(where.url)
        pattern = _BLOB.get(parsed.hostname or "")
        if pattern and parsed.scheme in ("https", "http"):
            repo = f"https://{parsed.hostname}{parsed.path.removesuffix('.git').rstrip('/')}"
            return pattern.format(repo=repo, commit=where.commit, path=RULE_PAGES) + "/"
    return None


def rule_url(code: str) -> str | None:
    """The address of the rule's page, ``<docs_base()>CODE.md``, or None."""
    base = docs_base()
    return f"{base}{code}.md" if base else None


def docs_index_url() -> str | None:
    """The address of the index of the rules (their folder's README.md), or None."""
    base = docs_base()
    return f"{base}README.md" if base else None
