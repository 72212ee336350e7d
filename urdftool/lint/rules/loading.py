"""U0xx: reading the file, parsing XML and expanding xacro.

The loader raises errors and records notes tagged with a kind; the engine turns them into these
codes (``urdftool.lint.engine.LOAD_CODES`` and ``NOTE_CODES``). U015 and U018 are the runner's.
"""

from urdftool.description.urdf import version_problem
from urdftool.diagnostics import Location
from urdftool.errors import PackageNotFound, close_names
from urdftool.lint.catalogue import Conditional, Severity, Taken, declare, rule

U001 = declare("U001", "malformed-xml", Severity.ERROR, """
    The file is not well-formed XML.

    Every tool that reads the robot (robot_state_publisher, Gazebo, MoveIt) stops here. The
    finding gives the parser's line and reason, with what it met there: the prefix no
    ``xmlns:`` declares (``<xacro:property>`` in a ``<robot>`` without
    ``xmlns:xacro="http://www.ros.org/wiki/xacro"``), a byte that is not UTF-8 (a file saved as
    Latin-1), a ``--`` inside a comment, a tag whose ``>`` is missing, a comment before the XML
    declaration, an element after the root's end, the element a mismatched end tag meets still
    open. A file left with git's conflict markers (``<<<<<<<``, ``=======``, ``>>>>>>>``) is
    said to hold an unresolved merge conflict, at its first marker's line.

    A **warning**, not an error, for white space before a ``.urdf``'s XML declaration, and for
    a ``--`` inside one of its comments (``<!-- ------ -->``, ``<!-- x --!>``): urdfdom
    (TinyXML2) skips the one and ends a comment at the first ``-->``, and reads the robot, while
    xacro, urdf_parser_py and yourdfpy refuse the file; the robot is checked as urdfdom reads it.

    Bad: ``<link name="base"><visual></link>``
    Good: ``<link name="base"><visual/></link>``
    """)


U002 = declare("U002", "empty-file", Severity.ERROR, """
    The file is empty or holds only white space.

    Checked when something loads it as a robot: a launch file here runs it as the robot
    description, or you name it with ``-`` (standard input). A blank file nothing loads is a
    placeholder, as an empty ``<robot>`` is: walked or named, it is not a robot to check (``-v``
    says so); a robot including it fails to expand (U005).

    Bad: a zero-byte ``robot.urdf``.
    Good: ``<robot name="r"><link name="base"/></robot>``
    """)


U003 = declare("U003", "binary-file", Severity.ERROR, """
    The file is binary, not XML text.

    Usually a mesh or an archive saved under a ``.urdf`` name.
    """)


U004 = declare("U004", "root-not-robot", Severity.ERROR, """
    The root element is not ``<robot>``.

    URDF parsers look for ``<robot>`` at the top and find nothing else.

    A **warning**, not an error, for a ``<robot xmlns="...">`` (a default XML namespace, often
    urdf.xsd's, written to validate the file against it): urdfdom's TinyXML2 and xacro know no
    namespaces and read the robot by its elements' names as written, while parsers that read
    namespaces (urdf_parser_py, yourdfpy) find no link in it; the robot is checked as urdfdom
    reads it.

    Bad: ``<model name="r">...</model>`` (that is SDF)
    Good: ``<robot name="r">...</robot>``
    """)


U005 = declare("U005", "xacro-error", Severity.ERROR, """
    xacro could not expand the file.

    Undefined properties, bad expressions, missing includes, unknown macros, macro recursion and
    include cycles end here, located at the line of the xacro file (or the included file) where
    the element that failed was written.

    An argument without a default (``<xacro:arg name="robot_model"/>``, or ``$(arg name)``
    read with no declaration) is not a defect in itself: xacro fails only when whoever builds the
    robot does not give it, and a robot meant to be built several ways asks for it on purpose.
    The repository's launch files say who builds it (docs/launch.md), and what is certain is
    reported so:

    - **error** when a launch file makes the robot from this file, unconditionally, with every
      xacro argument it gives read, and does not give this one: xacro fails there, every time;
      and when the build a launch file makes with no launch argument involved fails (on a
      package not installed here, U006's warning: the environment's, mmuav_gazebo's RotorS;
      on an included file its package's build may install, a warning);
    - **warning**, naming the launch file and its condition, when one makes it without the
      argument only under a condition (an ``if``, a launch argument choosing the file, or
      naming its package: "when launched with description_package's default 'x'"); and
      when no launch file gives it, it is declared nowhere and its name is close to one that is
      declared (``$(arg robot_nmae)``: a misspelt name fails unless a command line gives it);
    - **note** when launch files give it: the robot is checked as the first one builds it
      (the arguments known only at launch left at the robot's defaults; when that build
      fails, the failure is the note), or, when its value is known only at launch, not
      checked; and when no launch file here builds the robot: an argument a robot others
      build asks for (ROS 1 robots often read ``$(arg name)`` undeclared, given by the
      command line). ``--arg name=VALUE`` checks a build of your choice.

    A robot whose own argument defaults do not build (placeholders such as ``default=""`` that
    make an include path ``arms//urdf/_macro.xacro``: ros_kortex's kortex_dual_robots.xacro)
    is, when a launch file here builds it giving arguments with which xacro succeeds, checked as
    that launch file builds it, and the failure of the defaults is a **warning** saying so: it
    holds for a plain ``xacro FILE``, not for the build the repository runs. A **warning** too
    when a launch file builds it giving arguments whose values are known only at launch
    (``arm:=$(arg arm)`` from a launch argument without a default), and that build is not
    checked; but an **error** when no value can change the failure: a macro call under no
    ``xacro:if``/``xacro:unless`` giving a parameter the macro lacks (``Invalid parameter``,
    which xacro checks before any value: adv4ncr/motoman_ROS2's ``use_mock_hardware`` for
    ``mock_hardware``). Otherwise the failure is an error.

    An included file missing from the source tree below a package (``$(find NAME)/...``) is
    looked for where the package's build installs it from (docs/packages.md); when that
    package's install rules cannot be read, it may exist after the build: a warning saying so.
    A warning too for an include xacro cannot open beside the file including it that is there
    from a folder above (written for a tool run from that folder, as upkie's Makefile runs
    xacrodoc from the repository root), or written after ``$(cwd)``: the message says where.
    And for a macro used before its definition in a catkin package: ROS 1's xacro up to Lunar
    (Kinetic's default order) read every definition first and expands it; every xacro since
    Melodic fails (allegro_hand_ros_v4, written for Kinetic). Outside ROS 1, an error.

    A **note** when the file is a part of a robot defined elsewhere (its top level writes no
    link: only blocks such as ``<transmission>`` or ``<gazebo>``, through macro calls too),
    nothing here includes it nor builds it, and xacro fails on a name the robot including it
    would define (``${name}``, a macro): as the other findings of such a part, right only
    inside that robot (talos_description's left_arm.transmissions.urdf.xacro).
    A **warning** naming the condition when such a file calls macros defined nowhere here,
    writes no link of its own and its ``<robot>`` has no name, as a file written for xacro to
    include needs none (xacro keeps only the includer's root): it fails if built alone, and
    inside the robot including it that robot may define the name (bluerov2's
    urdf/gazebo/actuators.xacro, thruster macro calls with ``${namespace}``, which base.xacro's
    macro defines).

    Bad: ``<origin xyz="${wheel_radus} 0 0"/>`` (misspelt property)
    Good: ``<origin xyz="${wheel_radius} 0 0"/>``
    """)


U006 = declare("U006", "unresolved-package", Severity.WARNING, """
    A ``$(find pkg)`` names a package not installed here: the robot is not checked.

    urdftool looks at ``--package NAME=PATH``, ROS_PACKAGE_PATH, AMENT_PREFIX_PATH, and
    package.xml (or rosbuild manifest.xml) files above the input and below the repository
    root; the message lists them. When the file is not checked, the run exits 2 and says so
    last: nothing in the file is known to be wrong, and a run that could not check it is no
    pass.

    A package not installed is the environment's, not the robot's: a dependency the file's
    package.xml declares is there wherever the package is built, and another repository's
    package may be installed beside it. A **note** when the package.xml declares it: a
    question of the workspace, not a defect of the file (install the dependencies: ``rosdep
    install --from-paths . --ignore-src``; Robotnik's robots naming robotnik_sensors, 100 rows
    of the sweep). A **warning** when it does not (rosdep would not install it: add
    ``<exec_depend>``), or when the name is close to a package found here (a misspelt name:
    "did you mean"). Either way the robot is not checked, and a run that could not check it is
    no pass: ``urdftool check`` exits 2 and says how many files it could not check
    (``--package NAME=PATH`` gives it what it needs). A note, and no exit 2, for a library of
    macros (its top level defines macros and calls none) that no launch file here builds:
    expanded, it would make no robot to check (talos' sensors/xtion_pro_live.urdf.xacro,
    including ``$(find reemc)``, made the whole repository exit 2).

    Bad: ``$(find my_robot_descripton)/urdf/arm.xacro``
    Good: ``$(find my_robot_description)/urdf/arm.xacro``, or ``--package my_pkg=path/to/pkg``
    """)



U007 = declare("U007", "xacro-in-urdf", Severity.ERROR, """
    A file named ``.urdf`` contains xacro.

    urdftool expands it (and checks the result), but robot_state_publisher, check_urdf and
    simulators read ``.urdf`` files as plain URDF: they reject ``${...}`` values and ignore
    ``xacro:`` elements.

    Which it is, the repository's launch files say (docs/launch.md): when every launch file
    that loads the file runs xacro on it (``<param command="xacro ...">``, ``Command(["xacro",
    ...])``, ``xacro.process_file``; a launch test's ``generate_test_description`` counts, as it
    builds the robot), its consumers read it expanded, so it is checked as a
    xacro robot (a xacro error is then U005's, theirs) and this is a **note** naming the launch
    files and launch tests, each as what it is: only a tool given the file itself reads it
    unexpanded. A **warning** when a launch file or launch test that names the file cannot be
    read (not well-formed, not valid Python): what it does with the file is not known. A
    **warning** too when every use of xacro is inside ``<gazebo>`` (a plugin's
    ``<parameters>$(find ...)/controllers.yaml</parameters>``): URDF parsers skip it, and only
    Gazebo given the file itself reads it unexpanded. When every launch file that loads it
    reads its text and rewrites it first (``text.replace('$(config)', path)``), the file is a
    template the launch file fills: a **note** when each replaces every ``$(...)`` and
    ``${...}`` in it by name, a **warning** when what it replaces is not known without
    running it (``format``, ``string.Template``, ``re.sub``, a variable). An **error**
    otherwise: a launch file reads it as it is (``textfile=``, ``cat``, Python's ``open``), or
    none loads it.

    Bad: ``robot.urdf`` containing ``<xacro:property .../>``
    Good: rename it ``robot.urdf.xacro``
    """)


def required_argument(path: str, error, build):
    """(robot or None, the xacro arguments it was built with, findings) for a robot that needs
    the argument ``error.subject`` (a LoadError of kind "arg"), which has no default and the user
    did not give; ``build(args)`` loads the robot with those arguments (raises LoadError). What
    the launch files of its repository say decides (:func:`~urdftool.description.runtime.builds`);
    U005's documentation says how."""
    from urdftool.description.runtime import builds, launch_xacro_args, unread_naming
    from urdftool.errors import LoadError

    name, rule = error.subject, U005
    hint = f"pass {name}:=VALUE (or --arg {name}=VALUE) to check a build"
    for made, given in launch_xacro_args(path, name):
        try:
            robot = build(given)
        except LoadError as again:
            later = sorted(k for k, v in made.args.items() if v is None)
            certain = made.certain and not made.free and not later
            told = f"{made.named} builds it ({made.shown_args()}" + (
                "" if certain else f"; {', '.join(later)} known only at launch, left at the "
                "robot's defaults" if later else ", its launch arguments at their defaults") + ")"
            if again.kind == "package":  # not installed here: the environment's, as U006 says
                message = again.message + f"; {told}, and xacro fails so here"
                declared = again.declared  # the workspace's: a note
                return None, given, [U006.finding(
                    message if certain and not declared else Conditional(message, Severity.INFO),
                    again.location, not_checked=certain or declared)]
            message = again.message + f"; {told}, and xacro fails so"
            if not certain:
                message = Conditional(message, Severity.INFO)
            elif not again.certain:  # an included file the package's build may install
                message = Conditional(message)
            return None, given, [rule.finding(message, again.location)]
        message = error.message + (f"; checked as {made.named} builds it ({made.shown_args()}); "
                                   f"{hint} of your choice")
        return robot, given, [rule.finding(Conditional(message, Severity.INFO), error.location)]
    made = [b for b in builds(path) if b.xacro]
    giving = [b for b in made if name in b.args]
    if giving:
        return None, {}, [rule.finding(Conditional(
            error.message + f"; {giving[0].named} gives it a value known only at launch, so the "
            f"robot is not checked; {hint}", Severity.INFO), error.location)]
    lacking = [b for b in made if b.complete]
    for b in lacking:
        if b.certain:
            return None, {}, [rule.finding(
                error.message + f"; {b.named_at()} builds this robot without it, and xacro fails "
                "there", error.location)]
    if lacking:
        b = lacking[0]
        when = b.condition or "when its launch argument chooses this file"
        return None, {}, [rule.finding(Conditional(
            error.message + f"; {b.named_at()} builds this robot without it {when}, and xacro "
            "fails then"), error.location)]
    declared = _declared(path, error)
    near = close_names(name, declared - {name})
    # what a launch file or test not read does with the robot is unknown: it may give the name
    unread = unread_naming(path)
    unknown = f" (but {', '.join(unread[:3])} may)" if unread else ""
    if name in declared or not near:
        return None, {}, [rule.finding(Conditional(
            error.message + f": {name} has no default and no launch file or launch test here "
            f"builds the robot{unknown}: a parameter whoever builds it gives; not checked: "
            f"{hint}", Severity.INFO), error.location)]
    message = (error.message + f": {name} is declared nowhere and no launch file or launch test "
               f"here gives it{unknown}, but {', '.join(near)} is (<xacro:arg>): a misspelt name "
               f"fails unless the command line gives {name}; {hint}")
    return None, {}, [rule.finding(Conditional(message, Severity.INFO) if unread else
                                   Conditional(message), error.location)]


def failing_defaults(path: str, error, build):
    """(robot or None, the xacro arguments it was built with, findings) for a robot that xacro
    cannot expand with its own argument defaults (``error``, a LoadError): built as the first
    launch file that gives it arguments builds it (:func:`~urdftool.description.runtime.builds`;
    those known only at launch left at the robot's defaults) when xacro succeeds so, with a
    warning that the defaults fail; None when no launch file's build succeeds (the failure then
    stands). ``build(args)`` loads the robot with those arguments (raises LoadError)."""
    from urdftool.description.runtime import builds
    from urdftool.errors import LoadError

    tried, unknown = set(), None
    for made in builds(path):
        known = {name: text for name, text in made.args.items() if text is not None}
        if not made.xacro or not made.args:
            continue
        later = sorted(name for name, text in made.args.items() if text is None)
        unknown = unknown or (later and (made, later))
        if tuple(sorted(known.items())) in tried:
            continue
        tried.add(tuple(sorted(known.items())))
        try:
            robot = build(known)
        except LoadError:
            continue
        message = (error.message + "; xacro fails so with the robot's own argument defaults, "
                   f"but {made.named} builds it with {made.shown_args()} and xacro succeeds: "
                   "checked as built there (--arg NAME=VALUE checks another build)")
        return robot, known, [U005.finding(Conditional(message), error.location)]
    if unknown and error.whatever_args:  # the values given at launch cannot change it
        made, later = unknown
        message = (error.message + "; xacro fails so whatever the arguments: it checks a call's "
                   f"parameter names before any value, and the call is under no condition, so "
                   f"{made.named}'s build fails too, whatever {', '.join(later)} it is given")
        return None, {}, [U005.finding(message, error.location)]
    if unknown:  # the build the repository runs depends on values given at launch
        made, later = unknown
        message = (error.message + "; xacro fails so with the robot's own argument defaults, "
                   f"and {made.named} builds it giving {', '.join(later)} values known only at "
                   "launch, so that build is not checked (--arg NAME=VALUE checks one)")
        return None, {}, [U005.finding(Conditional(message), error.location)]
    return None, {}, []


def part_note(path: str, error, packages, limit: int) -> list | None:
    """The load error as a note, or None to report it as it is: the file is a part of a robot
    defined elsewhere that no launch file here builds, so what it cannot do alone is right
    only inside the robot that includes it (as the findings of a part that expands:
    :mod:`urdftool.lint.parts`). Two kinds of part:

    - U005: its top level writes no link (only definitions, extension blocks and calls of
      macros writing <transmission>, <gazebo> or <ros2_control> blocks:
      :func:`~urdftool.description.xacro_text.writes_no_links`) and xacro fails on a name the
      robot including it would define (talos' left_arm.transmissions.urdf.xacro: ``${name}``);
      a syntax error, a missing file, stay errors. A warning, not a note, when it calls
      macros not known here, writes no link of its own and its ``<robot>`` has no name, as a
      file written for xacro to include
      (:func:`~urdftool.description.xacro_text.nameless_robot`: bluerov2's
      urdf/gazebo/actuators.xacro, thruster macro calls with ``${namespace}`` that its
      includer's macro defines, named by a path that moved);
    - U006: a library of macros (:func:`~urdftool.description.xacro_text.macro_library`:
      talos' xtion_pro_live.urdf.xacro, including ``$(find reemc)``) whose package's name is
      not nearly that of one found here (doosan-robot2's libraries naming the ROS 1
      ``dsr_description`` beside dsr_description2 are wrong for any robot including them):
      expanded with the package it would make no robot to check, so its not being expanded
      loses nothing and does not make the run exit 2.

    ``packages``, ``limit``: the check's ``--package`` paths and file size limit [bytes]."""
    from urdftool.description.runtime import builds
    from urdftool.description.xacro_text import macro_library, nameless_robot, writes_no_links

    severity = Severity.INFO
    if error.kind == "xacro" and error.undefined:  # (a name a robot including it may define)
        if builds(path):
            return None
        rule = U005
        if writes_no_links(path, packages, limit):
            said = ("a part of a robot defined elsewhere (its top level writes no link, only "
                    "blocks such as <transmission>, <gazebo> or <ros2_control>, through macro "
                    "calls too), right only inside the robot that includes it, which defines "
                    "that name; no file here includes it, and no launch file here builds it")
        elif nameless_robot(path, limit, own_links=False):
            severity = Severity.WARNING
            said = ("when it is built alone: its <robot> has no name and writes no link of its "
                    "own, as a file written for xacro to include, and no file or launch file here "
                    "builds it (inside the robot including it, that robot may define the name)")
        else:
            return None
    elif error.kind == "package" and not error.close:
        if builds(path) or not macro_library(path, limit):
            return None
        rule = U006
        said = ("a library of macros (its top level defines macros and calls none), which no "
                "launch file here builds: expanded, it would make no robot to check, so nothing "
                "is lost (its macros are checked in the robots calling them)")
    else:
        return None
    return [rule.finding(Conditional(error.message + f"; {said}", severity), error.location)]


def _declared(path: str, error) -> set[str]:
    """The xacro arguments declared (``<xacro:arg name="...">``) in the robot's file and the
    file where xacro failed."""
    import re

    from urdftool.description.files import read_regular

    declaration = re.compile(rb"<(?:xacro:)?arg\s[^<>]*?name\s*=\s*[\"']([^\"'<>]+)[\"']")
    found: set[str] = set()
    for file in dict.fromkeys([path, *([error.location.file] if error.location else [])]):
        try:
            data = read_regular(file, 16 << 20, as_="include")
        except OSError:
            continue
        found.update(name.decode("utf-8", "replace") for name in declaration.findall(data))
    return found




U008 = declare("U008", "file-too-large", Severity.ERROR, """
    The input file is larger than ``--max-file-size`` (default 16 MiB).

    Robot descriptions are small; a huge file is a mistake or an attack on the CI runner.
    """)


U009 = declare("U009", "xml-entity", Severity.ERROR, """
    The file declares XML entities or references an external DTD.

    Entity declarations are how XML bombs and ``file:///etc/passwd`` leaks are built, and an
    external DTD (``<!DOCTYPE robot SYSTEM "...">``) makes XML libraries read a local file or
    reach the network; no robot description needs either. urdftool refuses them without
    expanding or fetching anything.

    Bad: ``<!DOCTYPE robot [<!ENTITY x SYSTEM "file:///etc/passwd">]>``
    Good: use a xacro property instead.
    """)


U010 = declare("U010", "xacro-warning", Severity.WARNING, """
    xacro printed a warning while expanding the file.

    xacro warns about unknown attributes on its own tags, deprecated syntax and includes whose
    glob matched nothing; these are usually typos that change the result silently. What a
    file prints with ``xacro.message()`` or ``<xacro:message>`` (its author's information,
    written without xacro's "warning: ") is no warning.

    Bad: ``<xacro:include filename="parts/*.xacro"/>`` matching no file
    Good: a pattern that matches the files meant
    """)


@rule("U011", "robot-name-missing", Severity.ERROR)
def robot_name_missing(robot):
    """The ``<robot>`` element has no ``name`` attribute, or an empty one.

    urdfdom (check_urdf, robot_state_publisher) refuses a robot without a ``name`` attribute.
    It takes ``name=""`` (check_urdf prints "robot name is: "): a robot without a name, which
    an SRDF or a simulator's model, matched to a robot by its name, cannot be. The commands that
    pose a robot take an empty name as urdfdom does (its finding says urdfdom takes it:
    ``lint.catalogue.Taken``). On a part of a robot defined elsewhere (see U105, U106), a note: the robot that includes it has the name.
    A warning naming the condition on a file xacro expands that no launch file of its
    repository builds: a file another package's robot includes needs none, since xacro keeps
    only the includer's ``<robot>`` (Autoware's ``<model>_description/urdf/vehicle.xacro``,
    included by tier4_vehicle_launch's robot ``vehicle``); loaded alone, urdfdom refuses it
    without the attribute, and takes it as a robot without a name with an empty one.

    Bad: ``<robot>``, ``<robot name="">``
    Good: ``<robot name="my_robot">``
    """
    name = robot.root.get("name")
    if name:
        return
    if not _built_by_nothing_here(robot):
        yield robot.root, ('<robot> has no name attribute; add name="..."' if name is None
                           else Taken('<robot> has an empty name (name=""); give it one'))
        return
    # the condition said as it is: urdfdom refuses a missing attribute, takes an empty one
    alone = ('<robot> has no name attribute: urdfdom refuses it if it is loaded alone (add '
             'name="...")' if name is None else
             '<robot> has an empty name (name=""): loaded alone it is a robot without a name '
             "(urdfdom takes it, but an SRDF or a simulator's model names the robot it is for; "
             "give it one)")
    yield robot.root, Conditional(
        f"{alone}; no launch file here builds it, and a file another robot's xacro includes "
        "needs none (xacro keeps only the includer's <robot>)")


def _built_by_nothing_here(robot) -> bool:
    """Whether ``robot`` is a file xacro expands (not a ``.urdf``, which its consumers read as
    written) that no launch configuration of its repository describes, however built."""
    from pathlib import Path

    from urdftool.description.runtime import runtime
    from urdftool.description.urdf import is_urdf_name

    if robot.path == "-" or is_urdf_name(Path(robot.path).name):
        return False
    return not runtime(robot).described


@rule("U012", "unsupported-version", Severity.ERROR)
def unsupported_version(robot):
    """The ``<robot version="...">`` is not a URDF version urdfdom supports (1.0 to 1.2).

    Bad: ``<robot name="r" version="2.0">``, ``version="1"``
    Good: ``<robot name="r" version="1.0">`` or no version attribute
    """
    text = robot.root.get("version")
    problem = version_problem(text) if text is not None else None
    if problem:
        yield robot.root, problem


U013 = declare("U013", "file-outside-root", Severity.WARNING, """
    xacro read an included or YAML file outside the repository and the packages it uses.

    The repository is the nearest folder above the input holding ``.git`` (without one, the
    nearest package.xml folder, else the input's folder); folders of packages found for
    ``$(find pkg)`` and paths given as xacro arguments count too. A description that reads
    ``/etc/...`` or ``~/...`` works only on one machine, or leaks a file into the output. Under
    ``--no-env`` such files are not read at all (U014).

    Bad: ``<xacro:include filename="/home/me/robot/arm.xacro"/>``
    Good: ``<xacro:include filename="$(find my_robot)/urdf/arm.xacro"/>``
    """)


U014 = declare("U014", "file-outside-root-refused", Severity.ERROR, """
    Under ``--no-env``, xacro tried to read a file outside the repository and its packages.

    ``--no-env`` is for untrusted input (CI on pull requests): the file is not read, so a
    crafted description cannot copy ``/etc/passwd`` or a CI secret into its output. See U013
    for which folders are allowed.

    Bad: ``${xacro.load_yaml('/etc/passwd')}``
    Good: ``${xacro.load_yaml('$(find my_robot)/config/limits.yaml')}``
    """)


U015 = declare("U015", "timeout", Severity.ERROR, """
    Checking the file took longer than ``--timeout`` seconds (default 60) and was stopped.

    A robot description loads in well under a second; a file that takes this long is a
    pathological xacro (deep loops, huge numbers) or an attack on the CI runner. The other files
    are still checked. Every command that reads a robot (``tree``, ``fk``, ``xacro``, ...) has
    the same budget. The finding is at the element xacro was expanding when it was stopped.

    Bad: ``<link name="${factorial(10**7)}"/>``
    Good: ``<link name="${'link_%d' % index}"/>``
    """)


U016 = declare("U016", "unsafe-xacro", Severity.ERROR, """
    A xacro expression was refused: it reaches into Python internals or builds something huge.

    xacro evaluates ``${...}`` and ``$(eval ...)`` as Python. urdftool evaluates both in a
    sandbox: no names or attributes starting with ``_``, no frame, code or generator internals
    (``gi_frame``, ``f_back``), no ``{0.__class__}`` format fields, no ``python.vars``, no
    ``exec``/``open``, and limits on the size of numbers, strings, lists (checked before they
    are built: ``'%0999999999d' % 0``, ``'x'.ljust(10**9)``), of what one expression builds in
    all, of YAML aliases and of the expansion itself (macro bombs). Real robot descriptions never
    need any of these.

    Bad: ``${(lambda: 0).__globals__}``, ``${'x' * 10**9}``, ``$(eval exec('...'))``
    Good: ``${radians(90)}``, ``${wheel_radius * 2}``
    """)


U017 = declare("U017", "symlink-outside-root", Severity.ERROR, """
    A symbolic link in the repository leads outside it; urdftool does not follow it.

    A robot file, an included file or a folder that ``check DIR`` walks may be a link planted by
    a pull request to read ``/etc/passwd``, a CI secret or ``/dev/zero``. The link is reported
    and its target never opened, with or without ``--no-env``. (A package folder that is such a
    link is not a package: U006 names it.) The repository
    is the nearest folder above the link holding ``.git`` (without one, the nearest package.xml
    folder, else the link's own folder). Files named with ``--package``, ROS_PACKAGE_PATH and
    AMENT_PREFIX_PATH are not links in the repository and stay allowed.

    Bad: ``urdf/arm.xacro -> /home/me/other_robot/arm.xacro``
    Good: a copy of the file in the repository, or ``$(find other_robot)/urdf/arm.xacro``
    with ``--package other_robot=PATH``
    """)


U018 = declare("U018", "out-of-memory", Severity.ERROR, """
    Checking the file needed more memory than ``--max-memory`` (default 2 GiB) and was stopped.

    Every worker and every command that reads a robot runs with its address space capped, so a
    crafted file (an expression or YAML document that slips past xacro's size limits, a huge
    mesh) ends here instead of taking the CI runner's memory. The finding is at the element xacro
    was expanding when memory ran out; the other files are still checked.

    Bad: ``<link name="${len([[0] * 10**6 for i in range(400)])}"/>``
    Good: ``<link name="${'link_%d' % index}"/>``
    """)


@rule("U019", "undeclared-package-dependency", Severity.WARNING)
def undeclared_package_dependency(robot):
    """A robot file uses another ROS package that its own package.xml does not declare.

    ``$(find other_pkg)`` and ``package://other_pkg/...`` work in a source workspace, where
    every package is built from the same checkout; installed from binaries (``apt install
    ros-<distro>-my-robot-description``, rosdep on a fresh machine), only the packages
    package.xml declares come along, and the look-up fails there. Any dependency tag counts
    (``<depend>``, ``<exec_depend>``, ``<run_depend>``, ``<build_depend>``, ...), whatever its
    ``condition``. Each file read to build the robot is judged by the package.xml above it, in
    the robot's repository only (installed packages are not the user's to fix; nor a rosbuild
    package, a manifest.xml, ROS 1's, built from source only), at the first
    place it names the package. Not judged: a use inside ``<xacro:if>``/``<xacro:unless>``
    (needed in some configurations only, such as a simulator's, often by a package that
    itself depends on this one), a name built by xacro (``$(find ${pkg})``), and a package
    that is not found (U006, U407).

    Bad: ``<xacro:include filename="$(find ur_description)/urdf/ur.urdf.xacro"/>`` in a
    package whose package.xml has no ``<exec_depend>ur_description</exec_depend>``
    Good: ``<exec_depend>ur_description</exec_depend>`` (or ``<depend>``) in its package.xml
    """
    from pathlib import Path

    from urdftool.description.files import inside
    from urdftool.description.packages import (containment_root, declared_dependencies,
                                               manifest_file, package_name, package_of,
                                               package_references)

    if robot.path == "-" or not robot.files:
        return
    root = containment_root(Path(robot.files[0]).parent)
    for file in robot.files:
        if file == "-" or file not in robot.sources or not inside(file, root):
            continue
        folder = package_of(file)
        declared = declared_dependencies(folder) if folder is not None else None
        if declared is None or manifest_file(folder) != "package.xml":
            continue
        own = package_name(folder)
        judged = set()
        for line, column, name in package_references(robot.sources[file]):
            if name in judged or name == own or name in declared:
                continue
            judged.add(name)
            try:
                robot.resolver.find(name)
            except PackageNotFound:
                continue
            yield Location(file, line, column=column), (
                f"uses package '{name}', which {own}'s package.xml does not declare (add "
                f"<exec_depend>{name}</exec_depend> or <depend>): found in a source workspace, "
                f"it is missing where {own} is installed from binaries")
