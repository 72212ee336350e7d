"""urdftool: lint and analyse URDF/xacro robot descriptions (docs/python-api.md).

>>> import urdftool
>>> run = urdftool.check_paths(["robots/"])      # what `urdftool check robots/` does
>>> run.exit_code, [f.code for r in run.results for f in r.findings]

The names below are imported on first use, so ``import urdftool`` (and ``urdftool --help``)
stays fast: nothing heavy (lxml, numpy, typer, rich) is loaded until it is needed. It imports
nothing at all: ``python -m urdftool`` runs it before :mod:`urdftool.__main__` takes the
current folder off ``sys.path``.
"""

__version__ = "0.1.0"

# name -> the module that owns it (documentation, and checked by tests/test_api.py)
_LAZY = {
    "load": "urdftool.description.load", "Robot": "urdftool.description.robot",
    "check_file": "urdftool.lint.runner", "check_paths": "urdftool.lint.runner",
    "Run": "urdftool.lint.runner", "FileResult": "urdftool.lint.engine",
    "CheckRequest": "urdftool.lint.settings", "Companions": "urdftool.lint.settings",
    "Settings": "urdftool.lint.settings",
    "Finding": "urdftool.diagnostics", "Location": "urdftool.diagnostics",
    "Severity": "urdftool.diagnostics", "Fix": "urdftool.diagnostics",
    "Edit": "urdftool.diagnostics",
    "UrdftoolError": "urdftool.errors", "LoadError": "urdftool.errors",
    "SettingsError": "urdftool.errors", "TargetError": "urdftool.errors",
    "OptionError": "urdftool.errors",
}
__all__ = ["__version__", *_LAZY]


def __getattr__(name: str):
    # Explicit imports, not import_module(_LAZY[name]): the layering test refuses dynamic ones.
    if name == "load":
        from urdftool.description import load as module
    elif name == "Robot":
        from urdftool.description import robot as module
    elif name in ("check_file", "check_paths", "Run"):
        from urdftool.lint import runner as module
    elif name == "FileResult":
        from urdftool.lint import engine as module
    elif name in ("CheckRequest", "Companions", "Settings"):
        from urdftool.lint import settings as module
    elif name in ("Finding", "Location", "Severity", "Fix", "Edit"):
        from urdftool import diagnostics as module
    elif name in ("UrdftoolError", "LoadError", "SettingsError", "TargetError", "OptionError"):
        from urdftool import errors as module
    else:
        raise AttributeError(f"module 'urdftool' has no attribute {name!r}")
    value = globals()[name] = getattr(module, name)
    return value


def __dir__():
    return sorted({*globals(), *__all__})
