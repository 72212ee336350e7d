"""What a check compiles on every run, compiled once: the methods :mod:`dataclasses` writes
for each class (``__init__``, ``__repr__``, ``__eq__``, ...; Python compiles their source text
anew at every import) and the regular expressions of urdftool and the libraries it uses (the
pattern parser and compiler of :mod:`re` run in Python).

``python -m urdftool.kept_code`` runs a check of ``robots/`` in this process, notes every
source text dataclasses executes and every pattern :mod:`re` compiles, and writes their
compiled forms beside urdftool's bytecode (:data:`urdftool.__main__.KEPT_CODE`, under
``__pycache__``, named by the interpreter's cache tag); ``make`` writes it after installing.
``urdftool/__main__.py`` (:func:`~urdftool.__main__.kept_code`) installs them before the
command imports anything. Each is kept under its whole source text or pattern and flags, so a
kept form is used only for the very text it was compiled from; the file is used only by the
Python that wrote it (version, bytecode and regular expression engine checked) and only whole
(its forms checksummed): a stale, foreign, truncated or corrupt file costs the compilation it
would have saved, nothing else.
"""

from __future__ import annotations

import builtins
import dataclasses
import os
import re
import sys
from pathlib import Path

from urdftool import __main__ as door

ROOT = Path(os.path.abspath(__file__)).parent.parent


def collect(workload) -> tuple[dict, dict]:
    """(source text -> code object, (pattern, flags) -> the arguments of ``_sre.compile``
    after the pattern) of what ``workload()`` compiles."""
    functions, patterns = {}, {}

    def exec_noted(source, globals=None, locals=None):
        if isinstance(source, str):
            source = functions.setdefault(source, builtins.compile(source, "<string>", "exec"))
        return builtins.exec(source, globals, locals)

    class NotedSre:
        def __getattr__(self, name):
            return getattr(real_sre, name)

        @staticmethod
        def compile(pattern, flags, code, groups, groupindex, indexgroup):
            noted.append((int(flags), [int(c) for c in code], int(groups), dict(groupindex),
                          tuple(indexgroup)))  # (plain ints: marshal takes no RegexFlag)
            return real_sre.compile(pattern, flags, code, groups, groupindex, indexgroup)

    compiler = re._compiler
    real_sre, real_compile, noted = compiler._sre, compiler.compile, []

    def compile_noted(pattern, flags=0):
        noted.clear()
        compiled = real_compile(pattern, flags)
        if noted and isinstance(pattern, (str, bytes)) and not flags & re.DEBUG:
            patterns[(pattern, int(flags))] = noted[0]
        return compiled

    dataclasses.exec = exec_noted
    compiler._sre, compiler.compile = NotedSre(), compile_noted
    re.purge()
    try:
        workload()
    finally:
        del dataclasses.exec
        compiler._sre, compiler.compile = real_sre, real_compile
    return functions, patterns


def check_robots() -> None:
    """``urdftool check robots/`` in this process (in one process, without the cache), its
    report thrown away; the mesh readers and the portability family imported first (a check
    imports them for a robot with meshes or a target, and the robots of ``robots/`` have
    neither)."""
    import contextlib
    import io

    import urdftool.description.meshes  # noqa: F401
    import urdftool.lint.rules.portability  # noqa: F401
    from urdftool import cli

    words = ["check", "--no-cache", "--jobs", "1", "--timeout", "0", "--max-memory", "0",
             str(ROOT / "robots")]  # (no worker: what it compiles is noted here)
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        try:
            cli.app(words, prog_name="urdftool")
        except SystemExit:
            pass


def main() -> None:
    if any(name.startswith("urdftool.") and name != "urdftool.__main__"
           and name != __name__ for name in sys.modules):
        raise SystemExit("python -m urdftool.kept_code must run in a fresh interpreter")
    functions, patterns = collect(check_robots)
    data = door.kept_code_file(functions, patterns)
    from urdftool.description.files import write_file

    write_file(door.KEPT_CODE, data, rewrites=True)
    print(f"wrote {door.KEPT_CODE}: {len(functions)} functions, {len(patterns)} patterns",
          file=sys.stderr)


if __name__ == "__main__":
    main()
