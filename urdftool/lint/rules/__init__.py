"""The rule families and the catalogue built from them.

Each module holds one family's rules (see :mod:`urdftool.lint.catalogue` for what a rule is).
A new family module is added to ``FAMILY_MODULES``: nothing is found by scanning the package.
The portability family, whose rules run only for a target (``check --target``), is imported
when its rules are first asked for (:class:`~urdftool.lint.catalogue.Catalogue`'s ``later``):
a check without a target never imports it.
"""

from __future__ import annotations

from urdftool.lint.catalogue import Catalogue
from urdftool.lint.rules import (controllers, conventions, gazebo, geometry, inertials, internal,
                                 joints, loading, moveit, parameters, plugins, ros2_control,
                                 running, spec, srdf, symmetry, transmissions, tree, vocabulary)

# the families every check runs, in order; then those of targets, imported when asked for
_EVERY_CHECK = (loading, vocabulary, tree, joints, symmetry, inertials, geometry, conventions,
                transmissions, ros2_control, controllers, gazebo, running, parameters, plugins,
                spec, srdf, moveit, internal)


def _portability():
    from urdftool.lint.rules import portability

    return portability


_FOR_TARGETS = (_portability,)  # (each imports its family: an import statement the contracts see)
CATALOGUE = Catalogue.from_modules(_EVERY_CHECK, later=_FOR_TARGETS)

__all__ = ["CATALOGUE", "FAMILY_MODULES"]


def __getattr__(name: str):
    """``FAMILY_MODULES``: every family module, in order (the targets' imported)."""
    if name == "FAMILY_MODULES":
        return (*_EVERY_CHECK, *(imported() for imported in _FOR_TARGETS))
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
