"""The real loaders, each a function run in a worker process of its own: it loads one URDF file
and says what it made of it, as plain data (a dict that pickles).

Every function takes a :class:`Job` and returns a dict with the keys of the crosscheck JSON
(``loaded``, ``error``, ``mass``, ``dof``, ``floating_base``, ``links``, ``frames``,
``inertia``...), reading the loader's own model, never urdftool's. Heavy libraries are imported
inside the function, in the worker. What the loader prints from C (PyBullet's b3Warning,
MuJoCo's warnings) is caught on the worker's file descriptors and kept in ``output``.
"""

from __future__ import annotations

import math
import os
import re
import shutil
import subprocess
from contextlib import contextmanager
from dataclasses import dataclass, field


@dataclass(frozen=True)
class Job:
    """What a loader is given.

    urdf: the URDF file to load (the user's file, or xacro's output in a temporary folder)
    packages: ROS package name -> folder, for the loaders that take them (Drake's PackageMap,
        Pinocchio's package_dirs; for PyBullet they are linked beside xacro's output)
    configurations: joint name -> value [rad or m], one mapping per configuration (the first
        is all zeros); frames are reported at each
    """

    urdf: str
    packages: dict = field(default_factory=dict)
    configurations: tuple = ()


@dataclass(frozen=True)
class Loader:
    """One loader: its name, the module (or command) that makes it present, and how to get it.

    name: as the crosscheck report names it; target: the ``--target`` its rules are under
    get: urdftool's pip extra that brings it, or how to install it when it is no Python package
    """

    name: str
    title: str
    target: str
    probe: str  # a Python module to import, or "cmd:" and a command on PATH
    get: str

    @property
    def extra(self) -> str | None:
        """urdftool's pip extra that brings the loader; None for a system package."""
        return self.get.removeprefix("extra:") if self.get.startswith("extra:") else None

    @property
    def install(self) -> str:
        """What to run to install the loader: the extra's command for this urdftool."""
        from urdftool.origin import install_command

        return install_command(self.extra) if self.extra else self.get


# pip extras of urdftool: `sim` brings MuJoCo and PyBullet, `drake` Drake (a wheel of 170 MB);
# sdformat is a system package (Debian: ignition-tools and libsdformat-dev give `ign sdf`).
LOADERS = {loader.name: loader for loader in (
    Loader("pinocchio", "Pinocchio", "pinocchio", "pinocchio", "extra:analysis"),
    Loader("mujoco", "MuJoCo", "mujoco", "mujoco", "extra:sim"),
    Loader("pybullet", "PyBullet", "pybullet", "pybullet", "extra:sim"),
    Loader("drake", "Drake", "drake", "pydrake", "extra:drake"),
    Loader("sdformat", "sdformat (gz sdf)", "gz", "cmd:gz|ign",
           "apt-get install ignition-tools libsdformat-dev  (Debian: `ign sdf`), or Gazebo's "
           "`gz` tool"),
)}


def sdformat_command() -> list[str] | None:
    """``gz sdf`` or ``ign sdf``, whichever is on PATH and answers (None: neither)."""
    for tool in ("gz", "ign"):
        path = shutil.which(tool)
        if path is None:
            continue
        try:
            done = subprocess.run([path, "sdf", "--versions"], capture_output=True, text=True,
                                  timeout=60)
        except (OSError, subprocess.TimeoutExpired):
            continue
        if done.returncode == 0 and done.stdout.strip():
            return [path, "sdf"]
    return None


def available(name: str) -> bool:
    """Whether loader ``name`` can run here (its module imports, its command answers), found
    without importing it (find_spec)."""
    import importlib.util

    probe = LOADERS[name].probe
    if probe.startswith("cmd:"):
        return sdformat_command() is not None
    try:
        return importlib.util.find_spec(probe) is not None
    except (ImportError, ValueError):
        return False


def version(name: str) -> str | None:
    """The installed version of a loader, None when it is absent."""
    from importlib import metadata

    if name == "sdformat":
        command = sdformat_command()
        if command is None:
            return None
        done = subprocess.run([*command, "--versions"], capture_output=True, text=True,
                              timeout=60)
        lines = done.stdout.split()
        return lines[-1] if lines else None
    distribution = {"pinocchio": "pin", "drake": "drake"}.get(name, name)
    try:
        return metadata.version(distribution)
    except metadata.PackageNotFoundError:
        return None


@contextmanager
def captured_output():
    """Catch what is written to file descriptors 1 and 2 (C libraries print there) in a
    temporary file; yields a list that holds the text once the block ends."""
    from urdftool.description.files import scratch_file

    caught: list[str] = []
    for stream in ("stdout", "stderr"):
        getattr(__import__("sys"), stream).flush()
    saved = [os.dup(1), os.dup(2)]
    with scratch_file() as sink:
        os.dup2(sink.fileno(), 1)
        os.dup2(sink.fileno(), 2)
        try:
            yield caught
        finally:
            for stream in ("stdout", "stderr"):
                try:
                    getattr(__import__("sys"), stream).flush()
                except Exception:  # noqa: BLE001
                    pass
            _flush_c_streams()  # printf's buffer, which a pipe or file makes a full one
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            for fd in saved:
                os.close(fd)
            sink.seek(0)
            caught.append(sink.read(1 << 20).decode("utf-8", errors="replace"))


def _flush_c_streams() -> None:
    try:
        import ctypes

        ctypes.CDLL(None).fflush(None)
    except (OSError, AttributeError):
        pass


def _finished(result: dict, caught: list[str]) -> dict:
    result["output"] = caught[0][-4000:] if caught else ""
    if not result.get("loaded") and result.get("error"):
        causes = [cause for cause in printed_errors(result["output"])
                  if cause not in result["error"]]
        if causes:  # Pinocchio: "... does not contain a valid URDF model"; urdfdom printed why
            result["error"] = f"{result['error'].rstrip('.')}; it printed why: {'; '.join(causes[:3])}"
    return result


# console_bridge's messages (urdfdom, sdformat): "Error:   text" then "at line N in file.cpp",
# the line of the library's source that printed it, never one of the robot's
# (line ends: the library's output's, LF)
_PRINTED = re.compile(r"^(?:Error|Warning):\s+(.*)\s*$((?:\n[ \t]+(?!at line \d+ in )\S.*$)*)", re.M)
SOURCE_LINE = re.compile(r"(?<!\s)\s*\bat line \d+ in \S+\.(?:cpp|cc|cxx|c|hpp|hh|h)\b")


def printed_errors(output: str) -> list[str]:
    """The errors a loader's C library printed (console_bridge's ``Error:`` lines, continued on
    indented lines), without the library's own source lines."""
    found = []
    for match in _PRINTED.finditer(SOURCE_LINE.sub("", output)):
        if match.group(0).startswith("Error"):
            text = " ".join((match.group(1) + match.group(2)).split())
            if text:
                found.append(text)
    return list(dict.fromkeys(found))


def _failed(error: BaseException | str) -> dict:
    from urdftool.errors import described

    text = error if isinstance(error, str) else described(error)
    return {"loaded": False, "error": text.strip()}


def _caught(load):
    """``load(job)`` with what it prints caught into the result's ``output``."""
    def run(job: Job) -> dict:
        with captured_output() as caught:
            result = load(job)
        return _finished(result, caught)

    run.__name__ = load.__name__
    run.__doc__ = load.__doc__
    return run


def _rounded(values) -> list[float]:
    return [float(v) for v in values]


# ---- Pinocchio -------------------------------------------------------------------------------

def load_pinocchio(job: Job) -> dict:
    import pinocchio as pin

    try:
        model = pin.buildModelFromUrdf(job.urdf)
    except Exception as error:  # noqa: BLE001 - the loader's own error, reported
        return _failed(error)
    data = model.createData()
    bodies = [f for f in model.frames if f.type == pin.FrameType.BODY]
    frames = []
    for configuration in job.configurations:
        q = pin.neutral(model)
        for name, value in configuration.items():
            if model.existJointName(name):
                joint = model.joints[model.getJointId(name)]
                if joint.nq == 1:
                    q[joint.idx_q] = value
                elif joint.nq == 2:  # continuous: cos, sin
                    q[joint.idx_q], q[joint.idx_q + 1] = math.cos(value), math.sin(value)
        pin.forwardKinematics(model, data, q)
        pin.updateFramePlacements(model, data)
        frames.append({f.name: _rounded(data.oMf[model.getFrameId(f.name, pin.FrameType.BODY)]
                                        .translation) for f in bodies})
    moved = {}  # joint -> the link it moves (its first body frame), which names its inertia
    for frame in bodies:
        moved.setdefault(frame.parentJoint, frame.name)
    return {
        "loaded": True, "error": None,
        "mass": float(sum(inertia.mass for inertia in model.inertias)),
        "dof": int(model.nv), "floating_base": False, "links": [f.name for f in bodies],
        "frames": frames, "mimic": "ignored (buildModelFromUrdf without mimic=True)",
        "inertia": {moved.get(i, model.names[i]): {
            "mass": float(model.inertias[i].mass),
            "inertia": _rounded(model.inertias[i].inertia.diagonal())}
            for i in range(1, model.njoints)},
    }


# ---- MuJoCo ----------------------------------------------------------------------------------

def load_mujoco(job: Job) -> dict:
    import mujoco

    try:
        model = mujoco.MjModel.from_xml_path(job.urdf)
    except Exception as error:  # noqa: BLE001
        return _failed(error)
    data = mujoco.MjData(model)
    names = [mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, i) for i in range(model.nbody)]
    free = [i for i in range(model.njnt)
            if int(model.jnt_type[i]) == int(mujoco.mjtJoint.mjJNT_FREE)]
    frames = []
    for configuration in job.configurations:
        mujoco.mj_resetData(model, data)
        for name, value in configuration.items():
            joint = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
            if joint >= 0 and int(model.jnt_type[joint]) in (
                    int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE)):
                data.qpos[model.jnt_qposadr[joint]] = value
        mujoco.mj_kinematics(model, data)
        frames.append({names[i]: _rounded(data.xpos[i]) for i in range(1, model.nbody)})
    return {
        "loaded": True, "error": None, "mass": float(sum(model.body_mass)),
        "dof": int(model.nv), "floating_base": bool(free), "links": names[1:],
        "frames": frames, "constraints": int(model.neq), "geoms": int(model.ngeom),
        "joints": {mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, i):
                   (_rounded(model.jnt_range[i]) if model.jnt_limited[i] else None)
                   for i in range(model.njnt)},
        "inertia": {names[i]: {"mass": float(model.body_mass[i]),
                               "inertia": _rounded(model.body_inertia[i])}
                    for i in range(1, model.nbody)},
    }


# ---- PyBullet --------------------------------------------------------------------------------

def load_pybullet(job: Job) -> dict:
    import pybullet

    client = pybullet.connect(pybullet.DIRECT)
    try:
        # no setAdditionalSearchPath: PyBullet does not ask it for meshes; the packages are
        # linked beside an expanded xacro instead (crosscheck._packages_beside)
        try:
            body = pybullet.loadURDF(job.urdf, physicsClientId=client)
        except Exception as error:  # noqa: BLE001
            return _failed(error)
        return _pybullet_model(pybullet, client, body, job)
    finally:
        pybullet.disconnect(client)


def _pybullet_model(pybullet, client, body, job: Job) -> dict:
    count = pybullet.getNumJoints(body, physicsClientId=client)
    info = [pybullet.getJointInfo(body, i, physicsClientId=client) for i in range(count)]
    base = pybullet.getBodyInfo(body, physicsClientId=client)[0].decode()
    links = [base] + [entry[12].decode() for entry in info]
    masses = [pybullet.getDynamicsInfo(body, i, physicsClientId=client)[0]
              for i in range(-1, count)]
    inertias = [pybullet.getDynamicsInfo(body, i, physicsClientId=client)[2]
                for i in range(-1, count)]
    movable = [i for i, entry in enumerate(info) if entry[2] != pybullet.JOINT_FIXED]
    frames = []
    for configuration in job.configurations:
        for i, entry in enumerate(info):
            if entry[2] != pybullet.JOINT_FIXED:
                pybullet.resetJointState(body, i, configuration.get(entry[1].decode(), 0.0),
                                         physicsClientId=client)
        position, orientation = pybullet.getBasePositionAndOrientation(body,
                                                                       physicsClientId=client)
        local = pybullet.getDynamicsInfo(body, -1, physicsClientId=client)[3:5]
        inverse = pybullet.invertTransform(*local)
        base_frame = pybullet.multiplyTransforms(position, orientation, *inverse)[0]
        found = {base: _rounded(base_frame)}
        for i in range(count):
            state = pybullet.getLinkState(body, i, computeForwardKinematics=True,
                                          physicsClientId=client)
            found[links[i + 1]] = _rounded(state[4])
        frames.append(found)
    return {"loaded": True, "error": None, "mass": float(sum(masses)), "dof": len(movable) + (
        6 if masses[0] > 0 else 0), "floating_base": masses[0] > 0, "links": links,
        "frames": frames, "constraints": pybullet.getNumConstraints(physicsClientId=client),
        "joints": {entry[1].decode(): [float(entry[8]), float(entry[9])] for entry in info
                   if entry[2] != pybullet.JOINT_FIXED},
        "inertia": {name: {"mass": float(m), "inertia": _rounded(i)}
                    for name, m, i in zip(links, masses, inertias)}}


# ---- Drake -----------------------------------------------------------------------------------

def load_drake(job: Job) -> dict:
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
    from pydrake.multibody.tree import BodyIndex
    from pydrake.systems.framework import DiagramBuilder

    try:
        builder = DiagramBuilder()
        plant, _ = AddMultibodyPlantSceneGraph(builder, 0.0)
        parser = Parser(plant)
        for name, folder in job.packages.items():
            if not parser.package_map().Contains(name):
                parser.package_map().Add(name, os.fspath(folder))
        parser.AddModels(job.urdf)
        plant.Finalize()
    except Exception as error:  # noqa: BLE001
        return _failed(error)
    context = plant.CreateDefaultContext()
    bodies = [plant.get_body(BodyIndex(i)) for i in range(1, plant.num_bodies())]
    floating = [plant.get_body(i).name() for i in plant.GetFloatingBaseBodies()]
    frames = []
    for configuration in job.configurations:
        q = plant.GetDefaultPositions()
        for name, value in configuration.items():
            if plant.HasJointNamed(name):
                joint = plant.GetJointByName(name)
                if joint.num_positions() == 1:
                    q[joint.position_start()] = value
        plant.SetPositions(context, q)
        frames.append({b.name(): _rounded(plant.EvalBodyPoseInWorld(context, b)
                                          .translation()) for b in bodies})
    return {
        "loaded": True, "error": None,
        "mass": float(sum(b.default_mass() for b in bodies)),
        "dof": int(plant.num_velocities()), "floating_base": bool(floating),
        "links": [b.name() for b in bodies], "frames": frames,
        "constraints": int(plant.num_constraints()),
        "inertia": {b.name(): {"mass": float(b.default_mass()), "inertia": _rounded(
            b.default_rotational_inertia().get_moments())} for b in bodies
            if math.isfinite(b.default_mass())},
    }


# ---- sdformat --------------------------------------------------------------------------------

def load_sdformat(job: Job) -> dict:
    """``gz sdf -p`` (the URDF converted as Gazebo does) and ``-k`` (its validity check); the
    converted model's links, masses and frames (forward kinematics of the SDF's poses)."""
    command = sdformat_command()
    if command is None:
        return {"loaded": False, "error": "neither `gz sdf` nor `ign sdf` is installed"}
    printed = subprocess.run([*command, "-p", job.urdf], capture_output=True, text=True,
                             timeout=600)
    checked = subprocess.run([*command, "-k", job.urdf], capture_output=True, text=True,
                             timeout=600)
    errors = [line for line in (printed.stderr + "\n" + checked.stderr + "\n" + checked.stdout)
              .splitlines() if "Error" in line and "backward" not in line]
    output = (printed.stderr + checked.stdout + checked.stderr)[-4000:]
    if printed.returncode != 0 or not printed.stdout.strip():
        from urdftool.guardian import ended

        why = f"{os.path.basename(command[0])} sdf -p: {ended(printed.returncode)}" \
            if printed.returncode else "no model"
        return {"loaded": False, "error": "\n".join(dict.fromkeys(errors)) or why,
                "output": output}
    from urdftool.crosscheck.sdf import model_summary

    result = model_summary(printed.stdout, job.configurations)
    result["output"] = output
    if checked.returncode != 0:  # -p and -k print the same errors: each said once
        result["loaded"], result["error"] = False, "\n".join(dict.fromkeys(
            line for line in errors if "Error Code" in line or "Error [" in line))
    return result


LOAD = {"pinocchio": _caught(load_pinocchio), "mujoco": _caught(load_mujoco),
        "pybullet": _caught(load_pybullet), "drake": _caught(load_drake),
        "sdformat": load_sdformat}
