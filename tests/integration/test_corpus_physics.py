"""Issue 32 classes 4-6 and issue 30 item 11 on the public corpus: every finding of the
conventions (U417-U421), symmetry (U218-U222) and inertials-against-geometry (U312-U316)
rules, and the tensors of light links (U306), judged one by one. The findings come from the
shared ``corpus_run`` (tests/conftest.py)."""

from __future__ import annotations

import re

import pytest

from conftest import corpus_entry_points

pytestmark = pytest.mark.skipif(not corpus_entry_points(), reason="corpus not available")

ERD = "example-robot-data/robots/"
SIMPLE = [ERD + f"simple_humanoid_description/urdf/simple_humanoid{v}.urdf"
          for v in ("", "_classical")]
ICUB = [ERD + f"icub_description/robots/icub{v}.urdf" for v in ("", "_reduced")]
ALLEGRO = [ERD + f"allegro_hand_description/urdf/allegro_{side}_hand.urdf"
           for side in ("left", "right")]
TALOS_REDUCED = [ERD + f"talos_data/robots/talos_reduced{v}.urdf"
                 for v in ("", "_box", "_corrected")]
PR2_ERD = ERD + "pr2_description/urdf/pr2.urdf"
PR2 = [f"pr2_description/robots/pr2{v}.urdf.xacro" for v in ("", "_no_arms", "_no_kinect", "_se")]
ICUB_Y_UP = ("DEBATABLE: its COLLADA meshes are Y_UP; read as rviz reads them (up_axis ignored) "
             "the limbs' meshes do not line up with the joints (urdftool render shows the legs "
             "apart from the body), so the centres of mass lie outside them")
PLACEHOLDER = ("TRUE: the same placeholder tensor (0.001-0.01 kg m^2) on frames and parts of "
               "1 g to 100 g, beyond any mass inside their geometry")

JUDGED = [
    # (entries, code, subjects, verdict: the real defect, or why it is debatable)
    (SIMPLE, "U220", ("LLEG_HIP_P", "LLEG_HIP_Y", "LLEG_KNEE", "LLEG_ANKLE_P", "LARM_SHOULDER_Y",
                      "LARM_ELBOW", "LARM_WRIST_Y", "LARM_WRIST_P", "LARM_WRIST_R"),
     "TRUE: one side's limit rows are shifted by a joint (LLEG_KNEE has the right hip yaw's "
     "range [-2.095, 0.7] and effort; LARM_ELBOW the right wrist yaw's)"),
    (SIMPLE, "U220", ("LLEG_HIP_R", "LLEG_ANKLE_R", "LARM_SHOULDER_R"),
     "TRUE: roll joints about the same x axis on both sides with equal ranges: one side swings "
     "inwards 90 degrees and outwards 20"),
    ([ERD + "romeo_description/urdf/romeo_laas_small.urdf"], "U220",
     ("LShoulderPitch_joint", "LShoulderYaw_joint"),
     "DEBATABLE: both stops of one side 0.11 and 0.17 rad off the mirror of the other's; a "
     "real robot's stops may differ by side"),
    (["darwin_description/urdf/darwin.urdf"], "U220", ("j_low_arm_l",),
     "DEBATABLE: the left elbow's range [-2.618, 2.618] and the right's [-1.635, 2.618]; one "
     "looks retyped"),
    (["robotis_op_description/robots/robotis_op.urdf"], "U221",
     ("MP_ARM_LOW_L", "MP_THIGH2_L", "MP_TIBIA_L"),
     "TRUE: the left forearm, thigh and tibia weigh 0.01, 0.007 and 0.007 kg against the right "
     "ones' 0.059, 0.119 and 0.070: a factor 10 slip and copies of another part's mass"),
    (["darwin_description/urdf/darwin.urdf"], "U221", ("MP_PELVIS_L",),
     "DEBATABLE: the left pelvis 0.167 kg, the right 0.197 kg (15 %)"),
    (ICUB, "U221", ("l_shoulder_1", "l_shoulder_3"),
     "DEBATABLE: equal masses, principal moments 2.2 and 1.4 times apart"),
    ([ERD + "romeo_description/urdf/romeo_laas_small.urdf"], "U221",
     ("LElbowYaw_link", "l_wrist"), "DEBATABLE: equal masses, smallest moments 2.7 times apart"),
    (ALLEGRO, "U312", ("palm_link",),
     "TRUE: the collision box spans z = -0.095 to 0 and the inertial sits at z = +0.0475: a "
     "sign flipped"),
    (ICUB, "U312", ("root_link", "l_forearm", "r_forearm", "l_hip_1", "r_hip_1",
                    "l_lower_leg", "r_lower_leg", "l_upper_arm", "r_upper_arm", "l_upper_leg",
                    "r_upper_leg", "r_shoulder_1"), ICUB_Y_UP),
    (["franka_description/robots/panda/panda.urdf.xacro[arm_id=panda,gazebo=true,hand=true]"],
     "U314", ("panda_hand",),
     "TRUE: the hand spans 0.2 m along y; its declared iyy 0.0025 is the geometry's ixx and "
     "its ixx 0.001 near the geometry's iyy: x and y swapped"),
    (["franka_description/robots/fr3/fr3.urdf.xacro[arm_id=fr3,gazebo=true,hand=true]"],
     "U314", ("fr3_hand",), "TRUE: the panda's hand tensor, as above"),
    (TALOS_REDUCED, "U314", ("rgbd_link",),
     "TRUE: a camera bar along y whose declared moment about y (3e-5) is the geometry's about z "
     "and its izz (2e-6) the geometry's iyy: y and z swapped"),
    ([PR2_ERD] + PR2[:3], "U316", ("head_plate_frame",), PLACEHOLDER),
    ([PR2_ERD] + PR2, "U316", ("laser_tilt_link",), PLACEHOLDER),
    ([PR2_ERD, PR2[0], PR2[2], PR2[3]], "U316", ("r_forearm_cam_frame",), PLACEHOLDER),
    ([PR2_ERD, PR2[0], PR2[2]], "U316", ("l_forearm_cam_frame",
                                         "l_gripper_motor_accelerometer_link"), PLACEHOLDER),
    ([PR2_ERD, PR2[0], PR2[2], PR2[3]], "U316", ("r_gripper_motor_accelerometer_link",),
     PLACEHOLDER),
    ([PR2_ERD], "U316", ("l_wrist_roll_link", "r_wrist_roll_link", "wide_stereo_link",
                         "narrow_stereo_gazebo_r_stereo_camera_frame",
                         "wide_stereo_gazebo_l_stereo_camera_frame"), PLACEHOLDER),
    ([ERD + "iris_description/robots/iris.urdf"], "U316",
     tuple(f"iris__rotor_{k}" for k in range(4)),
     "TRUE: 5 g rotors with iyy = izz = 2.7e-4: a radius of gyration of 0.23 m in a 0.13 m "
     "propeller (inflated to steady the simulation)"),
    (["turtlebot3_description/urdf/turtlebot3_burger_for_autorace_2020.urdf.xacro"], "U316",
     ("caster_back_link",), "TRUE: 1e-6 kg with 1e-3 kg m^2: a radius of gyration of 31 m"),
    (["rrbot_description/urdf/rrbot.xml"], "U417", ("camera_link",),
     "TRUE: the camera plugin stamps images with camera_link (x forward); rrbot.xacro later "
     "added camera_link_optical for it"),
    (["op3_description/urdf/robotis_op3.urdf.xacro"], "U417", ("cam_link",),
     "DEBATABLE: cam_link is optical from the head, but the sensor's <pose> (-1.5708 0 -3.14, "
     "DARwIn's, made for a head frame turned otherwise) turns the simulated camera away from it"),
    ([ERD + "hyq_description/robots/hyq_no_sensors.urdf"], "U306",
     ("base_link", "lf_foot", "rf_foot", "lh_foot", "rh_foot"),
     "TRUE: 1e-6 in all six fields, products included: rank 1, refused by MuJoCo, Drake and "
     "sdformat (judged since the mass no longer switches the check off)"),
    (ICUB, "U306", ("base_link",), "TRUE: as hyq's, a 1e-6 placeholder of rank 1"),
]
CODES = tuple(f"U{n}" for n in (*range(218, 223), *range(312, 317), *range(417, 422)))
LIGHT = {(entry, "U306", subject) for entries, code, subjects, _ in JUDGED if code == "U306"
         for entry in entries for subject in subjects}
_SUBJECT = re.compile(r"stamps its images with '([^']*)'|^(?:link|joints?|links|wheel|caster|"
                      r"optical frame|servo IDs of) '([^']*)'|'(base_footprint)'")


def _subject(message: str) -> str:
    found = _SUBJECT.search(message)
    return next(group for group in found.groups() if group) if found else "?"


def test_every_finding_is_judged(corpus_run):
    expected = {(entry, code, subject) for entries, code, subjects, _ in JUDGED
                for entry in entries for subject in subjects}
    found = set()
    for key, (_, result) in corpus_run.items():
        for f in result.findings:
            if f.code in CODES or (key, f.code, _subject(f.message)) in LIGHT:
                found.add((key, f.code, _subject(f.message)))
    assert found == expected, (sorted(found - expected), sorted(expected - found))


def test_the_judgements_are_counted():
    verdicts = [reason.split(":")[0] for *_, reason in JUDGED]
    assert set(verdicts) <= {"TRUE", "DEBATABLE"}
