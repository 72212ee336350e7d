"""Time and memory budgets in every command: a robot that hangs or eats memory ends as a finding
located at the element being expanded (U015, U018), exit 1, within the budget; never a hang, an
out-of-memory kill or a traceback."""

from __future__ import annotations

import resource
import subprocess
import sys
import time
from pathlib import Path

import pytest

from conftest import ROOT
from urdftool.budget import Budget, format_memory, parse_memory
from urdftool.lint.engine import CheckOptions, load_and_check
from urdftool.errors import UsageError
from urdftool.lint.runner import check_files

pytestmark = pytest.mark.worker  # budgets and deaths: run_cli's commands in the forked worker

XACRO = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
# One C call: no signal handler can interrupt it, only killing the process stops it.
FACTORIAL = (f'<robot name="r" {XACRO}>\n'
             '  <link name="base"/>\n'
             '  <link name="${factorial(10**7)}"/>\n'
             '</robot>\n')
GOOD = '<robot name="g"><link name="a"/></robot>\n'
# [s] the time budget of the tests that prove a stop and where it is, not the figure: the
# factorial is the first expression expanded, reached in milliseconds where the analysis
# libraries are imported (run_cli's analysis_imported; 2 s cost these tests 14 s of CPU)
STOP = "0.5"
COMMANDS = ["tree", "fk", "inertia", "xacro", "check"]
# The budgets are the net under the sandbox: these tests play a gap in the sandbox's guards by
# raising its limits, so that the expressions below pass it and only the budgets can stop them.
LENIENT = {("urdftool.description.xacro_sandbox", "MAX_INT_BITS"): 10 ** 9,
           ("urdftool.description.xacro_sandbox", "MAX_WORK"): 10 ** 12,
           ("urdftool.description.xacro", "MAX_TEXT"): 10 ** 12}
RUN = ("import importlib\n"
       f"for (module, name), value in {LENIENT!r}.items():\n"
       "    setattr(importlib.import_module(module), name, value)\n"
       "from urdftool.cli import main; main()")


@pytest.fixture(autouse=True)
def lenient_sandbox(monkeypatch):
    import importlib

    for (module, name), value in LENIENT.items():
        monkeypatch.setattr(importlib.import_module(module), name, value)


def hungry(properties: int = 400) -> str:
    """A robot whose properties keep 0.9 MB each alive: every expression is small enough for the
    sandbox, all of them together are not (line 2 + 2 i: the link using property i)."""
    lines = [f'<robot name="r" {XACRO}>', '  <link name="base"/>']
    for i in range(properties):
        lines.append(f'''  <xacro:property name="p{i}" value="${{['x' * 900000]}}"/>''')
        lines.append(f'  <link name="l{i}${{p{i}[0][:0]}}"/>')
    return "\n".join([*lines, "</robot>"]) + "\n"


@pytest.fixture(scope="module")
def expansion_imported(tmp_path_factory, analysis_imported):
    """What a first xacro expansion in this process imports (xacro, its sandbox, the rules),
    imported by one check before the time tests: their budget then covers the expansion,
    whose first expression is reached in milliseconds, not these imports (at load 10 a 0.5 s
    budget ran out before the factorial was reached)."""
    path = tmp_path_factory.mktemp("warm") / "warm.urdf.xacro"
    path.write_text(f'<robot name="w" {XACRO}>\n  <link name="${{"a" * 2}}"/>\n</robot>\n')
    load_and_check(str(path), CheckOptions())


@pytest.fixture
def factorial(tmp_path, expansion_imported):
    path = tmp_path / "fact.urdf.xacro"
    path.write_text(FACTORIAL)
    return path


@pytest.fixture
def memory_robot(tmp_path):
    path = tmp_path / "hungry.urdf.xacro"
    path.write_text(hungry())
    return path


def urdftool(*args, address_space: int | None = None, cwd=None):
    """The command line in a fresh process (real file descriptors, a small address space);
    ``address_space``: an RLIMIT_AS for the whole process, as a harsh machine would set."""
    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (address_space, address_space))

    started = time.monotonic()
    result = subprocess.run([sys.executable, "-c", RUN, *map(str, args)], capture_output=True,
                            text=True, timeout=120, cwd=cwd,
                            preexec_fn=limit if address_space else None)
    return result, time.monotonic() - started


# ---- time ----------------------------------------------------------------------------------

@pytest.mark.parametrize("command", COMMANDS)
def test_every_command_stops_a_hung_expansion_at_its_element(run_cli, factorial, command):
    started = time.monotonic()
    result = run_cli(command, "--timeout", STOP, factorial)
    elapsed = time.monotonic() - started
    assert result.exit_code == 1, result.output
    assert "U015" in result.output and f"{factorial.name}:3:" in result.output, result.output
    assert f"took longer than {STOP} s" in result.output
    assert "Traceback" not in result.output
    assert elapsed < 12, elapsed


def test_standard_input_has_a_budget_too(run_cli, expansion_imported):
    for command in ("check", "tree"):
        result = run_cli(command, "--timeout", STOP, "-", input=FACTORIAL)
        assert result.exit_code == 1 and "<stdin>:3:" in result.output, result.output
        assert "U015" in result.output


def test_the_stop_is_located_in_the_macro_with_its_call_site(tmp_path, expansion_imported):
    (tmp_path / "slow.xacro").write_text(
        f'<robot {XACRO}>\n'
        '  <xacro:macro name="slow">\n'
        '    <link name="${factorial(10**7)}"/>\n'
        '  </xacro:macro>\n'
        '</robot>\n')
    robot = tmp_path / "r.urdf.xacro"
    robot.write_text(f'<robot name="r" {XACRO}>\n'
                     '  <xacro:include filename="slow.xacro"/>\n'
                     '  <link name="base"/>\n'
                     '  <xacro:slow/>\n'
                     '</robot>\n')
    [result] = check_files([str(robot)], lambda p: CheckOptions(), jobs=1, timeout=float(STOP))
    [finding] = result.findings
    assert finding.code == "U015"
    assert (Path(finding.file).name, finding.line) == ("slow.xacro", 3)
    assert [(Path(site.file).name, site.line) for site in finding.location.via] == \
        [("r.urdf.xacro", 4)]


def test_in_a_real_process_output_and_stop_reach_the_terminal_streams(factorial):
    # (2 s: a fresh process imports the loader within its budget, 0.25 s of CPU; at load 10
    # it reached the expression after a second)
    result, elapsed = urdftool("tree", "--timeout", "2", factorial)
    assert result.returncode == 1 and elapsed < 15
    assert f"{factorial.name}:3: error U015" in result.stderr and "Traceback" not in result.stderr
    result, _ = urdftool("tree", "robots/r2d2/r2d2.urdf.xacro", cwd=ROOT)
    assert result.returncode == 0 and "robot name is: r2d2" in result.stdout, result.stderr


# ---- memory --------------------------------------------------------------------------------

@pytest.mark.parametrize("command, budget", [("tree", "200M"), ("fk", "400M"), ("xacro", "200M")])
def test_a_command_over_its_memory_budget_ends_in_a_located_finding(memory_robot, command,
                                                                    budget):
    result, _ = urdftool(command, "--max-memory", budget, memory_robot)
    assert result.returncode == 1, result.stderr
    assert "U018" in result.stderr and f"more than {budget[:-1]} MiB" in result.stderr
    assert f"{memory_robot.name}:" in result.stderr  # at the link whose property failed
    assert "Traceback" not in result.stderr and "MemoryError" not in result.stderr


def test_check_workers_over_their_memory_budget_report_and_the_run_goes_on(tmp_path,
                                                                          memory_robot):
    good = tmp_path / "good.urdf"
    good.write_text(GOOD)
    result, _ = urdftool("check", "--jobs", "2", "--max-memory", "200M", good.name,
                         memory_robot.name, cwd=tmp_path)
    assert result.returncode == 1
    lines = [line for line in result.stdout.splitlines() if " error " in line]
    assert len(lines) == 1 and "hungry.urdf.xacro:" in lines[0] and "U018" in lines[0], lines
    line = int(lines[0].split("hungry.urdf.xacro:")[1].split(":")[0])
    assert line > 2 and line % 2 == 0  # a link, not the file


@pytest.mark.parametrize("command", [("check", "--jobs", "1"), ("tree",)], ids=["check", "tree"])
def test_a_memory_error_without_budget_is_a_finding_too(memory_robot, command):
    """No budget, so no worker; but the machine limits the process: the MemoryError in this
    process is still a located finding."""
    result, _ = urdftool(*command, "--timeout", "0", "--max-memory", "0", memory_robot,
                         address_space=250 * 1024 ** 2)
    output = result.stdout + result.stderr
    assert result.returncode == 1, output
    assert "U018" in output and "ran out of memory" in output and f"{memory_robot.name}:" in output
    assert "Traceback" not in output


# ---- options and settings ------------------------------------------------------------------

def test_sizes():
    assert parse_memory("2G") == 2 * 1024 ** 3
    assert parse_memory("512m") == 512 * 1024 ** 2
    assert parse_memory("1.5GiB") == 3 * 1024 ** 3 // 2
    assert parse_memory("1000") == 1000
    assert parse_memory("0") is None
    assert format_memory(2 * 1024 ** 3) == "2 GiB" and format_memory(200 * 1024 ** 2) == "200 MiB"
    for wrong in ("lots", "-1G", "2X", ""):
        with pytest.raises(UsageError):
            parse_memory(wrong)
    assert Budget.of(0, "0").unlimited
    assert Budget.of(60, None) == Budget(60.0, 2 * 1024 ** 3)


def test_budgets_past_what_a_number_or_poll_holds(tmp_path):
    """A timeout of 115 days (1e7 s) is finite, but poll() takes at most 24 days of ms: it
    ended in OverflowError; NaN passed ``timeout < 0``; 400 digits of memory are an infinite
    float."""
    for wrong in (float("nan"), float("inf"), -1.0):
        with pytest.raises(UsageError):
            Budget.of(wrong, None)
    with pytest.raises(UsageError):
        parse_memory("9" * 400 + "G")
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    found = check_files([robot], lambda path: CheckOptions(), jobs=1, timeout=1e7)
    assert [finding.code for finding in found[0].findings if finding.code.startswith("U0")] == []


@pytest.mark.parametrize("args", [("--max-memory", "lots"), ("--timeout", "-1")])
@pytest.mark.parametrize("command", COMMANDS)
def test_a_bad_budget_is_a_usage_error(run_cli, factorial, command, args):
    result = run_cli(command, *args, factorial)
    assert result.exit_code == 2 and result.output.count("\n") == 1, result.output


def test_the_settings_file_sets_the_memory_budget(tmp_path, memory_robot):
    (tmp_path / "urdftool.toml").write_text('max-memory = "200M"\n')
    result, _ = urdftool("check", memory_robot.name, cwd=tmp_path)
    assert result.returncode == 1 and "U018" in result.stdout and "200 MiB" in result.stdout
    (tmp_path / "urdftool.toml").write_text('max-memory = "plenty"\n')
    result, _ = urdftool("check", memory_robot.name, cwd=tmp_path)
    assert result.returncode == 2 and "'max-memory' must be a size" in result.stderr
