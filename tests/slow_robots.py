"""A robot that takes hours to expand while staying under every cap of the xacro sandbox, for
the tests of time budgets (the check's guardian, the language server's budget, the fuzz child's
time limit).

Each level of the macro calls the next twice (2^24 calls), and each call's condition is a legal
million-item walk (~20 ms): quick calls alone reach the sandbox's cap of 20,000 macro calls
(U016, ``description.xacro.MAX_MACRO_CALLS``) within a few seconds on a fast machine (CI's did in
4.3 s), so that a test waiting for the time limit (U015, a kill) got the cap's finding instead.
"""

from __future__ import annotations


def slow_xacro(link: str = "base") -> str:
    """The robot's text, its one link named ``link``; the macro is called from line 9."""
    return f"""\
<?xml version="1.0"?>
<robot name="slow" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="twice" params="n">
    <xacro:if value="${{n > 0 and max(range(1000000)) > 0}}">
      <xacro:twice n="${{n - 1}}"/>
      <xacro:twice n="${{n - 1}}"/>
    </xacro:if>
  </xacro:macro>
  <xacro:twice n="24"/>
  <link name="{link}"/>
</robot>
"""
