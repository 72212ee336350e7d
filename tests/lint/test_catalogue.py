"""The catalogue: every code declared once, in order, and documented (the pages generated from
it: tests/test_docs.py)."""

import ast
import re
import types

import pytest

from conftest import ROOT, walked
from urdftool.lint.catalogue import Catalogue, Severity, UnknownRule, declare, rule
from urdftool.lint.rules import CATALOGUE, FAMILY_MODULES


def test_every_rule_is_documented():
    for found in CATALOGUE:
        assert found.doc and found.summary.endswith("."), f"{found.code} needs a docstring summary"
        assert found.name == found.name.lower() and " " not in found.name


def _family(name: str, **values) -> types.ModuleType:
    module = types.ModuleType(name)
    for key, value in values.items():
        if callable(value):
            value.__module__ = name
        setattr(module, key, value)
    return module


def _check(code: str, name: str):
    @rule(code, name, Severity.ERROR)
    def check(robot):
        """Summary."""
        yield from ()

    return check


def test_a_family_module_gives_its_rules_in_source_order_once():
    shared = declare("U002", "two", Severity.ERROR, "Two.")
    first = _family("fake.first", U001=declare("U001", "one", Severity.ERROR, "One."),
                    U002=shared, again=shared, three=_check("U003", "three"))
    second = _family("fake.second", borrowed=first.three, four=_check("U104", "four"))
    catalogue = Catalogue.from_modules([first, second])
    assert [r.code for r in catalogue.declared] == ["U001", "U002", "U003", "U104"]
    assert catalogue.get("U003").check is first.three
    assert catalogue.find("four").code == "U104"


@pytest.mark.parametrize("values, complaint", [
    ({"a": _check("U204", "a"), "b": _check("U204", "b")}, "U204 declared twice"),
    ({"a": _check("U2040", "a")}, "not of the form"),
    ({"a": _check("X204", "a")}, "not of the form"),
    ({"a": _check("U2x4", "a")}, "not of the form"),
    ({"a": _check("UA04", "a")}, "not of the form"),
    ({"a": _check("U204", "same"), "b": _check("U205", "same")}, "name same declared twice"),
    ({"a": _check("U205", "a"), "b": _check("U204", "b")}, "out of order"),
], ids=["taken", "too-long", "no-U", "not-digits", "no-family", "repeated-name", "misordered"])
def test_registration_refuses_a_bad_code_or_name(values, complaint):
    with pytest.raises(ValueError, match=complaint):
        Catalogue.from_modules([_family("fake.family", **values)])


def test_a_code_taken_in_another_family_module_is_refused():
    first = _family("fake.first", a=_check("U204", "a"))
    second = _family("fake.second", b=_check("U204", "b"))
    with pytest.raises(ValueError, match="U204 declared twice"):
        Catalogue.from_modules([first, second])


def _declared_in_source() -> list[str]:
    """Every code a family module's source passes to rule() or declare(), read with ast."""
    codes = []
    for module in FAMILY_MODULES:
        source = open(module.__file__, encoding="utf-8").read()
        for node in walked(source):
            if isinstance(node, ast.Call) and getattr(node.func, "id", None) in ("rule", "declare"):
                codes.append(node.args[0].value)
    return codes


def test_the_catalogue_lists_every_declared_code_exactly_once():
    in_source = _declared_in_source()
    listed = [r.code for r in CATALOGUE.declared]
    assert sorted(in_source) == sorted(listed)
    assert len(listed) == len(set(listed)) == len(CATALOGUE.rules)
    assert listed == sorted(listed), "declare each code in order (family modules too)"


def test_the_catalogue_is_built_without_importing_the_engine():
    import subprocess
    import sys

    code = ("import sys; from urdftool.lint.rules import CATALOGUE; "
            "assert 'U900' in CATALOGUE and 'U901' in CATALOGUE; "
            "assert 'urdftool.lint.engine' not in sys.modules, 'engine imported'; "
            "assert 'urdftool.lint.suppressions' not in sys.modules, 'suppressions imported'")
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT)


def test_a_check_without_a_target_never_imports_the_targets_family(tmp_path):
    """The portability family (U92x-U98x, rules of targets only) is imported when its rules
    are first asked for: not by a check without a target, which runs the same rules as
    before, in the same order; by one with a target, and by any list of the rules."""
    import subprocess
    import sys

    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    code = """if True:
        import sys
        from urdftool.lint import engine
        from urdftool.lint.options import Selection
        from urdftool.description.load import load
        from urdftool.lint.rules import CATALOGUE
        portability = "urdftool.lint.rules.portability"
        robot = load(sys.argv[1])
        ran = []
        for selection in (Selection(), Selection(targets=("mujoco",))):
            engine.check_robot(robot, selection)
            ran.append(portability in sys.modules)
        every = [r.code for r in CATALOGUE]
        print(ran, every == sorted(every), len(every), any(c.startswith("U92") for c in every))
    """
    done = subprocess.run([sys.executable, "-c", code, str(robot)], capture_output=True,
                          text=True, cwd=ROOT, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["[False,", "True]", "True", str(len(_declared_in_source())),
                                   "True"]


def test_a_selector_of_the_other_rules_never_imports_the_targets_family():
    """``--ignore U103`` (or a settings file's ``select``) imported the portability family to
    check the selector, and every robot's check then asked each of its rules whether it runs:
    14 M instructions of a check of the corpus. Only a selector that picks none of the other
    rules imports it; once imported, a check without a target still runs only the others."""
    import subprocess
    import sys

    code = """if True:
        import sys
        from urdftool.lint.options import Selection
        from urdftool.lint.settings import check_selectors
        from urdftool.lint.rules import CATALOGUE
        portability = "urdftool.lint.rules.portability"
        check_selectors(["U103", "U2", "inverted-limits"])
        nothing = Selection(ignore=("U103",)).runs_nothing()
        print(portability in sys.modules, nothing)
        before = CATALOGUE.running(False)
        check_selectors(["U92"])
        print(portability in sys.modules, CATALOGUE.running(False) == before,
              any(r.code.startswith("U92") for r in CATALOGUE.running(True)))
        print(Selection(select=("U92",)).runs_nothing(),
              Selection(select=("U92",), targets=("mujoco",)).runs_nothing())
    """
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["False", "False", "True", "True", "True", "True", "False"]


def test_codes_are_emitted_by_modules_that_do_not_declare_them():
    """Nothing declares a code where it is emitted: U900/U901 live in lint/rules/internal.py."""
    for path in (ROOT / "urdftool" / "lint").glob("*.py"):
        if path.name != "catalogue.py":
            assert not re.search(r"\bdeclare\(", path.read_text(encoding="utf-8")), path


def test_find_names_the_close_rules():
    with pytest.raises(UnknownRule, match="did you mean U204 inverted-limits"):
        CATALOGUE.find("inverted-limit")
    with pytest.raises(UnknownRule, match="the rules starting with U7 are: U701"):
        CATALOGUE.find("U7")
    assert CATALOGUE.find("u204").name == "inverted-limits"


def test_an_empty_word_names_no_rule():
    """``urdftool rules ''`` answered "the rules starting with  are: ..." and every rule."""
    for word in ("", " ", "\t"):
        with pytest.raises(UnknownRule, match="give a code \\(U204\\) or a name") as caught:
            CATALOGUE.find(word)
        assert "starting with" not in str(caught.value)


def test_a_finding_may_be_less_severe_than_its_rule_never_more():
    from urdftool.diagnostics import Location

    @rule("U999", "conditional", Severity.WARNING)
    def conditional(robot):
        """A defect that holds under a condition."""
        yield None, "x"

    where = Location("r.urdf", 1)
    assert conditional.rule.finding("m", where).severity == Severity.WARNING
    assert conditional.rule.finding("m", where, None, Severity.INFO).severity == Severity.INFO
    with pytest.raises(ValueError, match="cannot be more severe"):
        conditional.rule.finding("m", where, None, Severity.ERROR)


def test_a_taken_message_makes_a_finding_urdfdom_takes():
    """A rule says urdfdom parses the shape a finding is about with a Taken message; the
    finding keeps the rule's severity, and a plain message makes a refusal."""
    from urdftool.diagnostics import Location
    from urdftool.lint.catalogue import Taken

    @rule("U999", "shape", Severity.ERROR)
    def shape(robot):
        """A shape urdfdom parses in one form and refuses in another."""
        yield None, "x"

    where = Location("r.urdf", 1)
    taken = shape.rule.finding(Taken("m"), where)
    assert taken.urdfdom_takes and taken.severity == Severity.ERROR and taken.message == "m"
    assert type(taken.message) is str
    assert not shape.rule.finding("m", where).urdfdom_takes


def test_a_refused_message_makes_a_warning_that_is_urdfdoms_refusal():
    """The engine makes a rule's UrdfdomAlone a Refused message on a file another reader
    takes: a warning (a Conditional) that is urdfdom's refusal all the same; a Conditional
    message is no refusal."""
    from urdftool.diagnostics import Location
    from urdftool.lint.catalogue import Conditional, Refused

    @rule("U999", "shape", Severity.ERROR)
    def shape(robot):
        """A shape urdfdom refuses and another reader takes."""
        yield None, "x"

    where = Location("r.urdf", 1)
    refused = shape.rule.finding(Refused("if urdfdom loads it: m"), where)
    assert refused.urdfdom_refuses and refused.severity == Severity.WARNING
    assert not refused.urdfdom_takes and type(refused.message) is str
    conditional = shape.rule.finding(Conditional("if x: m"), where)
    assert conditional.severity == Severity.WARNING and not conditional.urdfdom_refuses


def test_the_engine_stamps_a_findings_own_severity(tmp_path):
    from urdftool.lint.engine import stamp

    @rule("U998", "graded", Severity.ERROR)
    def graded(robot):
        """A rule whose findings may be conditional."""
        yield None, "x"

    robot = types.SimpleNamespace(locate=lambda where: None)
    from urdftool.diagnostics import Location
    at = Location("r.urdf", 3)
    assert stamp(graded.rule, at, "m", robot).severity == Severity.ERROR
    assert stamp(graded.rule, at, "m", robot, None, Severity.WARNING).severity == Severity.WARNING
