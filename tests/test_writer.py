"""Issue 29, class 3: one writer. ``urdftool/description/files.py`` is the only module that
opens a file for writing, renames, replaces, makes or removes files or folders, or makes
temporary ones; every command's output, the cache, ``--fix`` and the tree of a git revision
go through it, so its refusal of folders linked outside the repository holds everywhere.

The scan reads every module with ``ast``; a picture is drawn into an in-memory buffer (a
variable named ``buffer``) and its bytes handed to the writer.
"""

from __future__ import annotations

import ast
from pathlib import Path

import urdftool
from conftest import walked

PACKAGE = Path(urdftool.__file__).parent
WRITER = "description/files.py"
# os functions that write, rename, make or remove; shutil: every function but which();
# tempfile: every function (importing it is enough)
_OS = {"replace", "rename", "renames", "makedirs", "mkdir", "mkfifo", "mknod", "symlink", "link",
       "remove", "unlink", "rmdir", "removedirs", "truncate", "chmod", "chown", "utime"}
_PATH_METHODS = {"write_text", "write_bytes", "touch", "mkdir", "symlink_to", "hardlink_to",
                 "unlink", "rmdir", "rename", "chmod", "savefig", "extractall", "to_csv",
                 "tofile"}
_WRITE_FLAGS = {"O_WRONLY", "O_RDWR", "O_CREAT", "O_APPEND", "O_TRUNC"}


def _mode(call: ast.Call, position: int = 1) -> str:
    """The mode argument of ``open(file, mode)`` (``position`` 1) or ``path.open(mode)`` (0)."""
    for keyword in call.keywords:
        if keyword.arg == "mode" and isinstance(keyword.value, ast.Constant):
            return str(keyword.value.value)
    if len(call.args) > position and isinstance(call.args[position], ast.Constant):
        return str(call.args[position].value)
    return "r"


def _names(node) -> set[str]:
    return {n.attr if isinstance(n, ast.Attribute) else n.id for n in ast.walk(node)
            if isinstance(n, (ast.Attribute, ast.Name))}


def writes(source: str) -> list[tuple[int, str]]:
    """(line, what) for every place in ``source`` that writes to the file system."""
    found = []
    for node in walked(source):
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            modules = [a.name for a in node.names] if isinstance(node, ast.Import) else [node.module]
            if any(m and m.split(".")[0] == "tempfile" for m in modules):
                found.append((node.lineno, f"imports {', '.join(filter(None, modules))}"))
            continue
        if not isinstance(node, ast.Call):
            continue
        function = node.func
        if isinstance(function, ast.Name) and function.id == "open":
            if any(c in _mode(node) for c in "wax+"):
                found.append((node.lineno, f"open(..., {_mode(node)!r})"))
        elif isinstance(function, ast.Attribute):
            owner = function.value.id if isinstance(function.value, ast.Name) else None
            if owner == "os" and function.attr in _OS:
                found.append((node.lineno, f"os.{function.attr}"))
            elif owner == "shutil" and function.attr != "which":
                found.append((node.lineno, f"shutil.{function.attr}"))
            elif owner == "os" and function.attr == "open":
                target = node.args[0] if node.args else None
                devnull = isinstance(target, ast.Attribute) and target.attr == "devnull"
                if not devnull and len(node.args) > 1 and _names(node.args[1]) & _WRITE_FLAGS:
                    found.append((node.lineno, "os.open for writing"))
            elif function.attr in _PATH_METHODS or function.attr == "extract" and node.args \
                    or function.attr == "export" and (node.args or any(
                        k.arg in ("file_obj", "path") for k in node.keywords)):
                # trimesh's export() without a file returns the bytes: that is no write
                found.append((node.lineno, f".{function.attr}()"))
            elif function.attr in ("replace", "rename") and len(node.args) == 1 \
                    and not node.keywords:  # Path.replace(target); str.replace takes two
                found.append((node.lineno, f".{function.attr}(target)"))
            elif function.attr == "open" and owner != "os" \
                    and any(c in _mode(node, 0) for c in "wax+"):
                found.append((node.lineno, f".open({_mode(node, 0)!r})"))
            elif function.attr == "save" and not (
                    node.args and isinstance(node.args[0], ast.Name)
                    and node.args[0].id == "buffer"):
                found.append((node.lineno, ".save() to a file"))
    return found


def test_only_the_writer_writes():
    offenders = [f"{path.relative_to(PACKAGE).as_posix()}:{line}: {what}"
                 for path in sorted(PACKAGE.rglob("*.py"))
                 if path.relative_to(PACKAGE).as_posix() != WRITER
                 for line, what in writes(path.read_text())]
    assert not offenders, "write through urdftool.description.files:\n" + "\n".join(offenders)


def test_the_scan_sees_each_way_of_writing():
    """The scan itself can fail: each of these is one finding, and reading is none."""
    samples = {
        "open(p, 'w')": 1, "open(p, mode='ab')": 1, "open(p, 'r+b')": 1, "open(p)": 0,
        "open(p, 'rb')": 0, "Path(p).write_text('x')": 1, "p.write_bytes(b'')": 1,
        "os.replace(a, b)": 1, "os.rename(a, b)": 1, "p.replace(q)": 1, "s.replace('a', 'b')": 0,
        "os.makedirs(d)": 1, "p.mkdir()": 1, "os.unlink(p)": 1, "import shutil": 0,
        "import tempfile": 1, "from tempfile import mkstemp": 1, "p.open('w')": 1,
        "p.open()": 0, "os.open(p, os.O_WRONLY | os.O_CREAT)": 1, "shutil.rmtree(d)": 1,
        "shutil.which('dot')": 0, "tar.extract(member, d)": 1, "joint.extract()": 0,
        "os.open(os.devnull, os.O_WRONLY)": 0, "os.open(p, os.O_RDONLY)": 0,
        "image.save('x.png')": 1, "image.save(buffer, format='PNG')": 0,
        "tar.extractall(d)": 1, "os.symlink(a, b)": 1, "os.chmod(p, 0o600)": 1,
        "mesh.export('x.obj')": 1, "mesh.export(file_obj=f)": 1,
        "mesh.export(file_type='obj')": 0,
    }
    for source, expected in samples.items():
        assert len(writes(source)) == expected, source
