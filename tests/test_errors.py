"""One exception hierarchy: every public error is an UrdftoolError defined in urdftool.errors,
and the module that raises it still exports it (``except fk.FKError`` keeps working)."""

from __future__ import annotations

import importlib
import inspect
import re
from pathlib import Path

import pytest

from urdftool import errors

EXPORTED = {
    "urdftool.collision.srdf": ["SrdfError"],
    "urdftool.description.meshes": ["MeshProblem"],
    "urdftool.kinematics.configuration": ["ConfigError", "MimicError"],
    "urdftool.kinematics.tree": ["TreeError"],
    "urdftool.kinematics.fk": ["FKError", "MimicError"],
    "urdftool.kinematics.dh": ["DHError"],
    "urdftool.physics.dynamics": ["DynamicsError"],
    "urdftool.report.dot": ["DotMissing"],
}
LOCATED = ["MeshProblem", "SrdfError", "ConfigError", "MimicError", "TreeError", "FKError",
           "DHError", "DynamicsError"]


@pytest.mark.parametrize("module", sorted(EXPORTED))
def test_old_modules_re_export_the_one_class(module):
    for name in EXPORTED[module]:
        assert getattr(importlib.import_module(module), name) is getattr(errors, name)
        assert issubclass(getattr(errors, name), errors.UrdftoolError)


def test_located_errors_carry_element_and_location():
    for name in LOCATED:
        assert issubclass(getattr(errors, name), errors.LocatedError), name
    element = object()
    error = errors.DHError("bad row", element, where="table.yaml:3")
    assert (str(error), error.element, error.where, error.location) == \
        ("bad row", element, "table.yaml:3", None)
    assert str(errors.ConfigError("too few values", "q.csv:2")) == "q.csv:2: too few values"
    problem = errors.MeshProblem("missing", "mesh 'm.stl' not found")
    assert (str(problem), problem.kind, problem.element) == ("mesh 'm.stl' not found", "missing",
                                                              None)


def test_no_public_exception_is_defined_outside_errors():
    """A public class deriving from an exception anywhere but errors.py is a second hierarchy.
    (Private control flow, ``_Name``, the loader's XmlProblem/XacroFailure/SandboxViolation,
    which become LoadError, the COLLADA reader's ColladaProblem, which becomes MeshProblem, and
    numbers' NumberRefused, which a YAML loader makes a YAML error and the command line a
    usage error, are left out.)"""
    package = Path(errors.__file__).parent
    pattern = re.compile(r"^class ([A-Z]\w*)\((\w*(Exception|Error)|OSError)\)", re.M)
    found = {f"{path.relative_to(package)}:{match[1]}"
             for path in package.rglob("*.py") if path.name != "errors.py"
             for match in pattern.finditer(path.read_text(encoding="utf-8"))}
    assert found == {"description/xml.py:XmlProblem", "description/xacro.py:XacroFailure",
                     "description/xacro_sandbox.py:SandboxViolation",
                     "description/files.py:TooLarge",
                     "description/collada.py:ColladaProblem", "numbers.py:NumberRefused"}, found


def test_every_errors_class_is_an_urdftool_error():
    for name, value in vars(errors).items():
        if inspect.isclass(value) and issubclass(value, BaseException):
            assert issubclass(value, errors.UrdftoolError), name


def test_a_name_holding_a_substitution_without_its_dollar_says_so():
    # quadruped_ros2_control's leg.xacro: <gazebo reference="{name}_thigh"> was asked
    # "did you mean 'RR_thigh'?", one leg's of the four its macro call names
    names = ["FL_thigh", "FR_thigh", "RL_thigh", "RR_thigh"]
    text = errors.available("links", "{name}_thigh", names)
    assert text.startswith("'{name}' is a xacro substitution without its '$' (${name})")
    assert "did you mean" not in text and "available links: FL_thigh" in text
    assert "substitution" not in errors.available("links", "${name}_thigh", names)


def test_a_name_differing_only_in_white_space_says_so_and_the_list_is_quoted():
    """Kristine23/Shadow_Hand_Public's shadow_hand (1).urdf writes '   rh_forearm' (three spaces)
    as the link's name and 'rh_forearm' in its joint: the hint and the list showed the two
    alike ('did you mean '   rh_forearm'? available links:    rh_ff_taxel_15, ...')."""
    names = ["   rh_forearm", "   rh_palm", "rh_wrist"]
    text = errors.available("links", "rh_forearm", names)
    assert text.startswith("did you mean '   rh_forearm'? the two differ only in white space")
    assert "available links: '   rh_forearm', '   rh_palm', 'rh_wrist'" in text
    assert "white space" not in errors.available("links", "rh_wirst", ["rh_wrist", "rh_palm"])


def test_a_name_of_the_same_words_reordered_is_the_one_suggested():
    """youbot_gz_ros2's <gazebo reference='gripper_finger_l_link'>: difflib ranked the other
    finger's gripper_finger_link_r first; the link meant is gripper_finger_link_l."""
    from urdftool.errors import available, close_names

    names = ["gripper_finger_link_r", "gripper_finger_link_l", "gripper_palm_link"]
    assert close_names("gripper_finger_l_link", names, n=1) == ["gripper_finger_link_l"]
    assert "did you mean 'gripper_finger_link_l'?" in available("links", "gripper_finger_l_link",
                                                                 names)



def test_a_close_name_holding_every_word_of_the_one_wanted_comes_first():
    # Gazebo's openni_kinect: depthImageInfoTopicName means depthImageCameraInfoTopicName,
    # which difflib ranks below depthImageTopicName (fewer characters to change)
    from urdftool.errors import close_names

    names = ["depthImageTopicName", "depthImageCameraInfoTopicName", "pointCloudTopicName"]
    assert close_names("depthImageInfoTopicName", names)[:2] == [
        "depthImageCameraInfoTopicName", "depthImageTopicName"]
    assert close_names("positon", ["position", "velocity"]) == ["position"]
    assert close_names("joint1", ["joint1_mimic", "joint_1"])[0] == "joint_1"


@pytest.mark.parametrize("wanted, name, suggested", [
    # the real sweep's suggestions, judged: a word added, dropped, reordered or misspelt ...
    ("FRHAA", "FR_HAA", True), ("link3", "Link3", True), ("link2", "link_02", True),
    ("arm_left_7_joint", "arm_7_joint", True), ("gazebo_HEAD_JOINT1_Link", "HEAD_JOINT1_Link", True),
    ("rightThumbMotorPitch1", "rightThumbPitch1", True), ("base", "base_link", True),
    ("hardware_interface/EffortJoinInterface", "EffortJointInterface", True),
    ("LF_Rollert2", "LF_Roller2", True), ("left_gripper_joint", "l_gripper_finger_joint", True),
    # ... and a word replaced, which misled (fresh17: wheel_left_joint on a TIAGo)
    ("wheel_left_joint", "torso_lift_joint", False), ("wrist_3_joint", "hand_3_joint", False),
    ("ur_description", "sr_description", False), ("arm_0_link", "arm_6_link", False),
    ("ur_description", "mur_desciption", False), ("ur", "mur", False),  # (session 20)
    ("shoulder_pan_joint", "forearm_hand_joint", False), ("link4", "imu_link", False),
    # ... and words dropped down to a kind and a number (session 19: xArm Lite 6's gripper
    # controller on the arm alone), not down to a parameter's word (joint_state_broadcaster's)
    ("finger_joint1", "joint1", False), ("state_interfaces", "interfaces", True),
    ("state_interface_names", "interface_names", True), ("LR_foot_link", "LR_foot", True),
    ("g_base", "gripper_base", True), ("r_gripper_aft_link", "gripper_roll_link", False),
])
def test_a_close_name_is_suggested_only_with_the_same_words(wanted, name, suggested):
    from urdftool.errors import close_names, same_words

    assert same_words(wanted, name) is suggested
    assert close_names(wanted, [name, "zzz"]) == ([name] if suggested else [])


def test_a_name_whose_first_word_was_replaced_is_found_by_its_other_words():
    from urdftool.errors import renamed

    names = ["victor_left_arm_joint_6", "victor_left_arm_joint_7", "victor_right_arm_joint_7"]
    assert renamed("iiwa_joint_7", names) == ["victor_left_arm_joint_7", "victor_right_arm_joint_7"]
    assert renamed("iiwa_joint_7", ["iiwa_joint_7", "joint_7"]) == []  # itself; no word before
    assert renamed("finger_joint", ["left_finger_joint"]) == []  # no number: too loose


def test_listed_names_a_dozen_each_cut_and_says_how_many():
    from urdftool.errors import listed

    assert listed([]) == "" and listed(["a", "b"]) == "'a', 'b'"
    assert listed(["a", "b"], quote=False) == "a, b"
    many = listed(f"n{i}" for i in range(5000))
    assert many.endswith("'n11', ... (5000 in all)") and many.count("'") == 24
    assert listed(["x" * 100]) == f"'{'x' * 64}... (100 characters)'"


def test_described_names_an_error_once_and_says_one_without_text():
    """pycollada's error said its own name: "does not load: DaeMalformedError:
    DaeMalformedError: XML Parsing Error: ..." (a binary STL named .dae); a MemoryError said
    "MemoryError: " and nothing."""
    from urdftool.errors import described

    class DaeMalformedError(Exception):
        pass

    assert described(DaeMalformedError("DaeMalformedError: XML Parsing Error: x")) == \
        "DaeMalformedError: XML Parsing Error: x"
    assert described(ValueError("bad")) == "ValueError: bad"
    assert described(MemoryError()) == "MemoryError"
    assert described(KeyError("k")) == "KeyError: 'k'"


def test_every_list_is_cut_by_one_function():
    """``first_listed`` owns the cut ("first 12, ... (N in all)"): the names of a message
    (``listed``), where a package was looked for, the places and call sites of the text
    report's grouped lines; they were three copies of it."""
    from urdftool.errors import LISTED, PackageNotFound, first_listed
    from urdftool.report import text_format

    items = [str(i) for i in range(LISTED + 1)]
    assert first_listed(items[:LISTED], LISTED) == ", ".join(items[:LISTED])
    assert first_listed(items, len(items)) == ", ".join(items[:LISTED]) + ", ... (13 in all)"
    assert first_listed(items, 8000, "places").endswith("11, ... (8000 places in all)")
    assert text_format._listed(items) == first_listed(items, len(items))
    searched = [f"/p{i}" for i in range(20)]
    assert f"looked in: {first_listed(searched, 20, 'places')}. Pass" in \
        str(PackageNotFound("x", searched))


def test_where_a_package_was_looked_for_is_a_part_of_its_message_named():
    """PackageNotFound.repeated: the part of its message every file and mesh naming the package
    says again (where it was looked for, how to pass it), for a report to write once."""
    for owner, declares in ((None, True), ("bot", True), ("bot", False)):
        error = errors.PackageNotFound("pkg", ["/a", "/b"]).declared(owner, declares)
        [(kind, part, name)] = error.repeated
        assert (kind, name) == ("searched", "pkg") and str(error).endswith(part)
        assert part.startswith("; looked in: /a, /b. Pass --package pkg=PATH")


def test_a_said_message_is_never_rebuilt_into_a_plain_str_silently():
    """A Said carries the parts a report says once (an available list); a wrapper that rebuilt
    the message with an f-string dropped them without a word (failing_defaults' U005 wrote
    the list in full at each finding). Formatting one raises; + and a slice keep them; str()
    drops them on purpose; a LoadError's message carries its error's parts."""
    said = "joint 'x' is not known; " + errors.available("joints", "x", ["a", "b"])
    [part] = said.repeated
    with pytest.raises(TypeError, match="loses its repeated parts"):
        f"if it runs: {said}"
    with pytest.raises(TypeError, match="loses its repeated parts"):
        "if it runs: {}".format(said)
    with pytest.raises(TypeError, match="loses its repeated parts"):
        "if it runs: %s" % said
    assert ("if it runs: " + said).repeated == (part,)
    assert said[len("joint 'x' "):].repeated == (part,) and said[:5].repeated == ()
    assert type(str(said)) is str and type(f"{said!s}") is str
    assert part == ("available", "available joints: a, b", "2 joints")
    error = errors.LoadError("xacro", said, None, repeated=said.repeated)
    assert (error.message + "; more").repeated == (part,)


def test_a_mesh_problem_leaves_a_contextmanager_block_as_itself():
    """MeshProblem is a frozen dataclass, whose __setattr__ refused every name, the exception
    state Python sets too: leaving a ``@contextmanager`` block (contextlib sets
    ``__traceback__``), it became a FrozenInstanceError (met under pytest, whose runner wraps
    each test in such blocks, with a trimesh that found no triangles in a recovered COLLADA
    file). Its fields stay frozen."""
    import dataclasses
    from contextlib import contextmanager

    from urdftool.errors import MeshProblem

    @contextmanager
    def block():
        yield

    with pytest.raises(MeshProblem) as raised, block():
        raise MeshProblem("corrupt", "mesh 'm.dae' holds no triangles")
    raised.value.add_note("noted")
    assert raised.value.__notes__ == ["noted"]
    with pytest.raises(dataclasses.FrozenInstanceError):
        raised.value.kind = "missing"


def test_whose_an_error_is_is_said_by_the_error_and_a_table_or_file_is_the_questions():
    """``asked`` (the question's: exit 2 in every command, cli._common.fail_at) is False for
    the robot's errors unless the raiser says so, and True for a name the robot lacks, the
    values a user gave (ConfigError), and an error about a D-H table file (its ``where``)."""
    from urdftool.errors import (ConfigError, DHError, FKError, IKError, MeshProblem,
                                 UnknownLink, UsageError)

    assert not FKError("origin past 1e150").asked and not IKError("too many").asked
    assert not MeshProblem("missing", "mesh 'a.stl' not found").asked
    assert not DHError("axis cannot be placed", element=None).asked
    assert IKError("no joint moves 'a' relative to 'a'", asked=True).asked
    assert DHError("invalid JSON/YAML", where="table.yaml:3").asked
    assert UnknownLink("b", ["a"]).asked and ConfigError("unknown joint 'x'").asked
    assert UsageError("takes exactly one FILE").asked
