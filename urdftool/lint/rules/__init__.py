"""The rule families and the catalogue built from them.

Each module holds one family's rules (see :mod:`urdftool.lint.catalogue` for what a rule is).
A new family module is added to ``FAMILY_MODULES``: nothing is found by scanning the package.
"""

from __future__ import annotations

from urdftool.lint.catalogue import Catalogue
from urdftool.lint.rules import (controllers, conventions, gazebo, geometry, inertials, internal,
                                 joints, loading, moveit, parameters, plugins, portability,
                                 ros2_control, running, spec, srdf, symmetry, transmissions, tree,
                                 vocabulary)

FAMILY_MODULES = (loading, vocabulary, tree, joints, symmetry, inertials, geometry, conventions,
                  transmissions, ros2_control, controllers, gazebo, running, parameters, plugins,
                  spec, srdf, moveit, internal, portability)
CATALOGUE = Catalogue.from_modules(FAMILY_MODULES)

__all__ = ["CATALOGUE", "FAMILY_MODULES"]
