"""Fixes: edits of the files the user wrote that remove a finding, and applying them.

- :mod:`.tags`: where each start tag of a source file is, and its parts (byte spans);
- :mod:`.building`: the edits a rule proposes (:class:`Unfixable` when there is none, with why);
- :mod:`.applying`: the plan of the edits that apply to the files as they are now, and writing it.
"""

from urdftool.lint.fixes.applying import MAX_PASSES, Plan, apply, inertia_rewrite, plan, write
from urdftool.lint.fixes.building import append_child, converted_mesh, \
    element_to_attribute, inertial_edits, insert_before, offer, prefix_text, rename_attribute, \
    rename_element, set_attribute, swap_attributes
from urdftool.lint.fixes.tags import EXPRESSION, Source, Tag, Unfixable, edit_of, parse_source, \
    source, source_tag

__all__ = ["EXPRESSION", "MAX_PASSES", "Plan", "Source", "Tag", "Unfixable", "append_child",
           "apply", "converted_mesh", "edit_of", "element_to_attribute", "inertia_rewrite",
           "inertial_edits", "insert_before", "offer", "parse_source", "plan", "prefix_text",
           "rename_attribute", "rename_element", "set_attribute", "source", "source_tag",
           "swap_attributes", "write"]
