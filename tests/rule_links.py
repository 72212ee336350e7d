"""Where a rule link points, in this checkout: the tests of every output that links a rule's
documentation (SARIF, rdjson, the language server) check that the page exists."""

from __future__ import annotations

from pathlib import Path
from urllib.parse import unquote, urlparse

from conftest import ROOT
from urdftool.origin import RULE_PAGES


def page_of(url: str) -> Path:
    """The file of this checkout a rule link names: a ``file:`` URL's path, or for a git host's
    page the path after the commit (``.../blob/COMMIT/docs/rules/U204.md``)."""
    parsed = urlparse(url)
    if parsed.scheme == "file":
        return Path(unquote(parsed.path))
    _, _, tail = parsed.path.partition(f"/{RULE_PAGES}/")
    assert tail, f"{url} does not point into {RULE_PAGES}/"
    return ROOT / RULE_PAGES / unquote(tail)


def assert_rule_page(url: str | None, code: str) -> None:
    """``url`` is the generated page of ``code`` in this checkout."""
    assert url is not None, f"{code} has no documentation link"
    page = page_of(url)
    assert page == ROOT / RULE_PAGES / f"{code}.md" and page.is_file(), (url, page)
    assert page.read_text(encoding="utf-8").splitlines()[2].startswith(f"# {code} "), page
