"""A synthetic monorepo of small robots checked with ``--jobs``: does it take about
files / cores x the cost of one file?

The reference is measured in the same run: ``check_files`` with one job checks the files one after
another in this process (the cost of one file, times the count), then with one worker per core.
ratio = the CPU time of the parallel run (this process and its workers) / that of the serial
run: what the workers add to the work (forks, the pipe, what each reads again). With the cores
idle the wall time is the parallel CPU time / workers, so a ratio r means r x files / cores x
the cost of one file; the target allows for process start-up and the pipe. Medians of three
runs of each, alternating.

CPU time, not wall time: on a machine shared with other users (2 cores, load 3-4) a second
worker finds no idle core, and the wall-time ratio (parallel / (serial / workers)) measures the
neighbours' load, not the pool. The wall times and the load are printed beside it. Whether the default ``--jobs`` starts a second worker only when it
pays is ``bench_check``'s line (default ``--jobs`` against ``--jobs 1``).
"""

from __future__ import annotations

import os
import resource
import statistics
import tempfile
import time
from pathlib import Path

COUNT = 1000
TARGET = 1.5
REPEATS = 3

ROBOT = """<?xml version="1.0"?>
<robot name="bot{index}" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="r" value="{radius}"/>
  <xacro:macro name="wheel" params="side y">
    <link name="${{side}}_wheel">
      <inertial><mass value="0.5"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
      <visual><geometry><cylinder radius="${{r}}" length="0.02"/></geometry></visual>
    </link>
    <joint name="${{side}}_wheel_joint" type="continuous">
      <parent link="base_link"/><child link="${{side}}_wheel"/>
      <origin xyz="0 ${{y}} 0"/><axis xyz="0 1 0"/>
    </joint>
  </xacro:macro>
  <link name="base_link">
    <inertial><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <xacro:wheel side="left" y="0.1"/>
  <xacro:wheel side="right" y="-0.1"/>
</robot>
"""


def _write_repo(folder: Path, count: int) -> list[str]:
    files = []
    for index in range(count):
        path = folder / f"pkg{index // 50}" / f"bot{index}.urdf.xacro"
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(ROBOT.format(index=index, radius=0.05 + index * 1e-5))
        files.append(str(path))
    return files


def _cpu() -> float:
    """CPU time [s] of this process and its ended children (the workers, once joined)."""
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.process_time() + children.ru_utime + children.ru_stime


def main() -> dict:
    from urdftool.lint.engine import CheckOptions, load_and_check
    from urdftool.lint.pool import default_jobs
    from urdftool.lint.runner import check_files

    with tempfile.TemporaryDirectory() as tmp:
        files = _write_repo(Path(tmp), COUNT)
        options = CheckOptions()
        load_and_check(files[0], options)  # warm up imports and rule registration
        jobs = default_jobs()
        serials, parallels, serial_cpu, parallel_cpu = [], [], [], []
        for _ in range(REPEATS):
            start, cpu = time.perf_counter(), _cpu()  # one job: in this process, no pool
            check_files(files, lambda p: options, jobs=1, timeout=0)
            serials.append(time.perf_counter() - start)
            serial_cpu.append(_cpu() - cpu)
            start, cpu = time.perf_counter(), _cpu()
            results = check_files(files, lambda p: options, jobs=jobs, timeout=60)
            parallels.append(time.perf_counter() - start)
            parallel_cpu.append(_cpu() - cpu)
        serial, parallel = statistics.median(serials), statistics.median(parallels)
    assert len(results) == COUNT
    ratio = statistics.median(parallel_cpu) / statistics.median(serial_cpu)
    wall_ratio = parallel / (serial / jobs)
    load = "load {:.1f}/{:.1f}/{:.1f}".format(*os.getloadavg())
    result = {"name": f"many-files: {jobs} workers' CPU / one job's ({load})",
              "ratio": round(ratio, 3), "target": TARGET, "files": COUNT,
              "jobs": jobs, "serial_s": round(serial, 3), "parallel_s": round(parallel, 3),
              "wall_ratio": round(wall_ratio, 3), "one_file_ms": round(serial / COUNT * 1000, 3),
              "detail": f"goal <= {TARGET}x; {jobs} workers {_text(parallel_cpu)} cpu, "
                        f"{parallel:.2f} s wall; one job {_text(serial_cpu)} cpu, {serial:.2f} s "
                        f"wall; wall / (one job's / {jobs}): {wall_ratio:.2f}"}
    print(f"many-files: {COUNT} files, {jobs} workers: {parallel:.2f} s vs {serial:.2f} s serial "
          f"({result['one_file_ms']} ms/file); CPU ratio {ratio:.2f} (target <= {TARGET}), "
          f"wall ratio {wall_ratio:.2f}; {load}")
    return result


def _text(samples: list[float]) -> str:
    return f"{statistics.median(samples):.2f} s [{min(samples):.2f}-{max(samples):.2f}]"


if __name__ == "__main__":
    main()
