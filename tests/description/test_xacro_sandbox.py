"""The xacro expression sandbox: attacks refused with a located finding (real robots:
tests/integration/test_corpus_xacro.py)."""

from __future__ import annotations

import os

import pytest

from urdftool.errors import LoadError
from urdftool.lint.engine import load_error_findings
from urdftool.description.load import load

HEADER = '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'


def _load(tmp_path, body: str, name="robot.urdf.xacro", **kwargs):
    path = tmp_path / name
    path.write_text(HEADER + body + "\n</robot>\n")
    return load(path, **kwargs)


def _refused(tmp_path, body: str, **kwargs):
    with pytest.raises(LoadError) as caught:
        _load(tmp_path, body, **kwargs)
    [finding] = load_error_findings(caught.value)
    assert finding.location.line is not None, finding
    return finding


# (attack, property f, expression); every one must end in a located error and touch nothing.
ATTACKS = {
    "dunder attribute": ("", "${().__class__}"),
    "__import__": ("", "${__import__('os').system('touch MARK')}"),
    "subclasses walk": ("", "${().__class__.__base__.__subclasses__()}"),
    "dunder inside lambda": ("", "${(lambda: ().__class__.__base__.__subclasses__())()}"),
    "dunder inside comprehension": ("", "${[c.__class__ for c in [1]]}"),
    "dunder keyword": ("", "${dict(__x=1)}"),
    "generator frame walk": ("", "${[g.gi_frame.f_back.f_globals for g in [(x for x in [1])]]}"),
    "frame back": ("", "${(x for x in [1]).gi_frame.f_back}"),
    "type mro": ("", "${python.type(1).mro()}"),
    "format attribute": ("{0.__class__}", "${f.format(1)}"),
    "format globals": ("{0.__globals__[os].environ}", "${f.format(xacro.load_yaml)}"),
    "format unbound": ("{0.__class__}", "${str.format(f, 1)}"),
    "format_map": ("{x.__class__}", "${f.format_map(dict(x=1))}"),
    "format nested spec": ("{0:{1.__class__}}", "${f.format(1, 2)}"),
    "format frame": ("{0.gi_frame.f_back}", "${f.format((x for x in [1]))}"),
    "format through map": ("{0.__class__}", "${list(map(f.format, [1]))}"),
    "format built at run time": ("{0.|}", "${f.replace('|', '_' * 2 + 'class' + '_' * 2).format(1)}"),
    "dotify dunder": ("", "${xacro.dotify(dict(a=1)).__class__}"),
    "integer power bomb": ("", "${10**10**10}"),
    "string repeat bomb": ("", "${'a' * 10**10}"),
    "list repeat bomb": ("", "${[0] * 10**9}"),
    "range bomb": ("", "${python.sorted(range(10**9))}"),
    "shift bomb": ("", "${1 &lt;&lt; 10**10}"),
    "product bomb": ("", "${(10**20000) * (10**20000) * (10**20000)}"),
}
SANDBOX_CODE = "U016"
NOT_AVAILABLE = {  # refused because the symbol is gone or limited: xacro's own error (U005)
    "vars dictionary": "${python.vars(python.type)['__subclasses__'](object)}",
    "type with three arguments": "${python.type('X', (), dict())}",
}


@pytest.mark.parametrize("attack", sorted(ATTACKS))
def test_attack_is_refused_with_a_located_finding(tmp_path, attack, monkeypatch):
    monkeypatch.chdir(tmp_path)
    prop, expression = ATTACKS[attack]
    finding = _refused(tmp_path, f'<xacro:property name="f" value="{prop}"/>\n'
                                 f'<link name="{expression}"/>')
    assert finding.code == SANDBOX_CODE, finding
    assert finding.location.line == 3
    assert not (tmp_path / "MARK").exists()


@pytest.mark.parametrize("attack", sorted(NOT_AVAILABLE))
def test_removed_symbols_are_unavailable(tmp_path, attack):
    finding = _refused(tmp_path, f'<link name="{NOT_AVAILABLE[attack]}"/>')
    assert finding.code == "U005"


@pytest.mark.parametrize("expression, expected", [
    ("${'{0:.2f} {1}'.format(3.14159, 'x')}".replace("{", "{{").replace("}", "}}"), None),
    ("${math.pi * 2}", "6.283185307179586"),
    ("${radians(90)}", "1.5707963267948966"),
    ("${'%s_%d' % ('wheel', 2)}", "wheel_2"),
    ("${[i * 2 for i in range(3)][2]}", "4"),
    ("${(lambda x: x + 1)(1)}", "2"),
    ("${xacro.dotify(dict(a=1)).a}", "1"),
    ("${' '.join(str(i) for i in python.range(3))}", "0 1 2"),
    ("${2**10}", "1024"),
])
def test_ordinary_expressions_still_work(tmp_path, expression, expected):
    if expected is None:
        return  # braces cannot appear inside ${} (xacro's lexer); see the property test below
    robot = _load(tmp_path, f'<link name="{expression}"/>')
    assert robot.root.find("link").get("name") == expected


def test_format_of_a_property_still_works(tmp_path):
    robot = _load(tmp_path, '<xacro:property name="f" value="{0:.2f}_{1}"/>\n'
                            '<link name="${f.format(3.14159, \'x\')}"/>')
    assert robot.root.find("link").get("name") == "3.14_x"


def test_plain_xacro_is_restored_after_expansion(tmp_path):
    import xacro

    before = (xacro.safe_eval, xacro.eval_text, dict(xacro._global_symbols["python"]))
    _refused(tmp_path, '<link name="${().__class__}"/>')
    assert (xacro.safe_eval, xacro.eval_text) == before[:2]
    assert dict(xacro._global_symbols["python"]) == before[2]
    assert not hasattr(xacro, "open")


def test_yaml_units_go_through_the_sandbox(tmp_path):
    (tmp_path / "good.yaml").write_text("a: !degrees 90\n")
    (tmp_path / "bad.yaml").write_text("b: !degrees ().__class__\n")
    robot = _load(tmp_path, '<link name="${xacro.load_yaml(\'good.yaml\').a}"/>')
    assert float(robot.root.find("link").get("name")) == pytest.approx(1.5707963)
    finding = _refused(tmp_path, '<link name="${xacro.load_yaml(\'bad.yaml\').b}"/>')
    assert finding.code == SANDBOX_CODE


# ---- resource limits of the expansion itself ----

def test_property_billion_laughs_is_refused(tmp_path):
    body = ['<xacro:property name="p0" value="lolololololololololo"/>']
    body += [f'<xacro:property name="p{i}" value="{("${p%d}" % (i - 1)) * 10}"/>'
             for i in range(1, 10)]
    finding = _refused(tmp_path, "\n".join(body) + '\n<link name="${p9}"/>')
    assert finding.code == SANDBOX_CODE


@pytest.fixture
def small_limits(monkeypatch):
    from urdftool.description import xacro as xacro_expand

    monkeypatch.setattr(xacro_expand, "MAX_ELEMENTS", 2000)
    monkeypatch.setattr(xacro_expand, "MAX_MACRO_CALLS", 500)


def test_macro_bomb_is_refused(tmp_path, small_limits):
    body = ['<xacro:macro name="m0"><link name="x"/></xacro:macro>']
    body += [f'<xacro:macro name="m{i}">' + f"<xacro:m{i - 1}/>" * 10 + "</xacro:macro>"
             for i in range(1, 9)]
    finding = _refused(tmp_path, "\n".join(body) + "\n<xacro:m8/>")
    assert finding.code == SANDBOX_CODE and "macro calls" in finding.message


def test_block_doubling_bomb_is_refused(tmp_path, small_limits):
    body = ['<xacro:macro name="d0" params="*b"><xacro:insert_block name="b"/></xacro:macro>']
    for i in range(1, 40):
        body.append(f'<xacro:macro name="d{i}" params="*b"><xacro:d{i - 1}><g>'
                    '<xacro:insert_block name="b"/><xacro:insert_block name="b"/>'
                    f'</g></xacro:d{i - 1}></xacro:macro>')
    finding = _refused(tmp_path, "\n".join(body) + '\n<xacro:d39><link name="x"/></xacro:d39>')
    assert finding.code == SANDBOX_CODE and "elements" in finding.message


def test_deeply_nested_macros_stop_with_a_located_error(tmp_path):
    body = [f'<xacro:macro name="m{i}"><xacro:m{i + 1}/></xacro:macro>' for i in range(300)]
    body.append('<xacro:macro name="m300"><link name="x"/></xacro:macro>')
    finding = _refused(tmp_path, "\n".join(body) + "\n<xacro:m0/>")
    assert finding.code == "U005" and "nested deeper" in finding.message


# ---- files outside the repository ----

def _outside_robot(tmp_path):
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    (tmp_path / "secret.yaml").write_text("token: hunter2\n")
    (tmp_path / "outside.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="o"/></robot>')
    path = repo / "robot.urdf.xacro"
    path.write_text(HEADER + '<link name="${xacro.load_yaml(\'../secret.yaml\').token}"/>\n'
                    '<xacro:include filename="../outside.xacro"/>\n</robot>\n')
    return path


def test_files_outside_the_repository_are_reported(tmp_path):
    from urdftool.lint.engine import CheckOptions, load_and_check

    result = load_and_check(str(_outside_robot(tmp_path)), CheckOptions())
    outside = sorted((f.code, f.line) for f in result.findings if f.code == "U013")
    assert outside == [("U013", 2), ("U013", 3)]


def test_files_outside_the_repository_are_refused_without_env(tmp_path):
    with pytest.raises(LoadError) as caught:
        load(_outside_robot(tmp_path), allow_env=False)
    [finding] = load_error_findings(caught.value)
    assert (finding.code, finding.line) == ("U014", 2)
    assert "hunter2" not in finding.message


def test_symlink_out_of_the_repository_is_outside(tmp_path):
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    (tmp_path / "secret.yaml").write_text("token: hunter2\n")
    (repo / "link.yaml").symlink_to(tmp_path / "secret.yaml")
    path = repo / "robot.urdf.xacro"
    path.write_text(HEADER + '<link name="${xacro.load_yaml(\'link.yaml\').token}"/>\n</robot>')
    with pytest.raises(LoadError) as caught:
        load(path, allow_env=False)
    assert caught.value.kind == "outside"


def test_special_files_are_not_read(tmp_path):
    finding = _refused(tmp_path, '<link name="${xacro.load_yaml(\'/dev/zero\')}"/>')
    assert finding.code == "U005" and "regular file" in finding.message


def test_yaml_alias_bomb_is_refused(tmp_path):
    lines = ['a: &a ["lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol"]']
    for i in range(1, 10):
        previous = "a" if i == 1 else f"a{i - 1}"
        lines.append(f"a{i}: &a{i} [" + ", ".join([f"*{previous}"] * 10) + "]")
    (tmp_path / "bomb.yaml").write_text("\n".join(lines) + "\n")
    finding = _refused(tmp_path, '<link name="${xacro.load_yaml(\'bomb.yaml\')}"/>')
    assert finding.code == SANDBOX_CODE and "YAML" in finding.message


@pytest.mark.parametrize("expression, code", [
    ("${xacro.fatal('stop here')}", "U005"),
    ("${xacro.arg('not_an_arg')}", "U005"),
    ("${xacro.tokenize('a]b', sep=']')}", None),
    ("${xacro.abs_filename('x.yaml')}", None),
    ("${xacro.warning('careful')}", None),
    ("${math.floor(2.5)}", None),
])
def test_xacro_helpers_stay_harmless(tmp_path, expression, code):
    if code is None:
        _load(tmp_path, f'<link name="{expression}"/>')
    else:
        assert _refused(tmp_path, f'<link name="{expression}"/>').code == code


def test_bare_range_keeps_xacro_deprecation_warning(tmp_path):
    from urdftool.lint.engine import CheckOptions, load_and_check

    path = tmp_path / "robot.urdf.xacro"
    path.write_text(HEADER + '<link name="${len(range(3))}"/>\n</robot>\n')
    result = load_and_check(str(path), CheckOptions())
    assert [f.code for f in result.findings] == ["U010"]
    assert "deprecated" in result.findings[0].message
