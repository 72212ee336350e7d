"""``urdftool check``: the linter and CI step."""

from __future__ import annotations

from pathlib import Path

import typer

from urdftool.checking import FORMATS  # noqa: F401  (the --format values it takes)
from urdftool.cli._common import PackageOption, XacroArgOption, max_memory_option, timeout_option


def register(app: typer.Typer) -> None:
    app.command(
        "check",
        help="Check robot descriptions (files or folders) and report problems. "
             "Exit code: 0 clean, 1 errors (or warnings with --strict), 2 usage error or "
             "files not checked (a package they need is not installed: U006).",
    )(check)


def check(
    words: list[str] = typer.Argument(..., metavar="PATH... [NAME:=VALUE...]",
                                      help="URDF/xacro files or folders; '-' reads stdin."),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
    format: str = typer.Option("auto", "--format", "-f",
                               help="text, concise, json, json-lines, sarif, junit, github, "
                                    "gitlab, rdjson, or auto (github under GitHub Actions, "
                                    "else text)."),
    output: Path = typer.Option(None, "--output", "-o", help="Write the report to this file."),
    select: list[str] = typer.Option([], "--select", metavar="CODES",
                                     help="Only these codes, prefixes or names "
                                          "(comma-separated, repeatable)."),
    ignore: list[str] = typer.Option([], "--ignore", metavar="CODES",
                                     help="Skip these codes, prefixes or names."),
    target: list[str] = typer.Option([], "--target", "-t", metavar="NAME",
                                     help="Also check what this simulator refuses or changes "
                                          "(repeatable): gazebo, gz, mujoco, drake, pybullet, "
                                          "isaac, pinocchio; NAME@VERSION for an older one. "
                                          "See docs/targets.md."),
    strict: bool = typer.Option(False, "--strict", help="Exit 1 on warnings too."),
    verbose: bool = typer.Option(False, "--verbose", "-v", help="Say which files were skipped, "
                                 "and which companion files each robot was checked with."),
    quiet: bool = typer.Option(False, "--quiet", "-q",
                               help="Text format: print the findings only, no summary line."),
    notes: bool = typer.Option(None, "--notes/--no-notes", show_default=False,
                               help="Text format: show the notes (severity info: what a check "
                                    "assumed or could not do, not problems); the other formats "
                                    "always include them [default: --no-notes, or notes in "
                                    "the settings]."),
    exit_zero: bool = typer.Option(False, "--exit-zero",
                                   help="Exit 0 even when problems are found (usage errors "
                                        "still exit 2)."),
    statistics: bool = typer.Option(False, "--statistics",
                                    help="Print how many times each rule fired, most first, "
                                         "instead of the findings."),
    config: Path = typer.Option(None, "--config", metavar="FILE",
                                help="Use this settings file for every path instead of the "
                                     "one found above each."),
    isolated: bool = typer.Option(False, "--isolated",
                                  help="Ignore every settings file."),
    stdin_filename: str = typer.Option(None, "--stdin-filename", metavar="PATH",
                                       help="The path standard input is checked as: its "
                                            "includes, packages and settings are found from "
                                            "there, and findings name it."),
    allow_env: bool = typer.Option(
        None, "--allow-env/--no-env", show_default=False,
        help="--no-env, the safe mode for untrusted input: the environment is never read "
             "($(env) is an error, $(optenv NAME DEFAULT) its default) and xacro reads no "
             "file outside the repository and its packages. --allow-env: "
             "both allowed. [default: --no-env when CI is set, as CI services do; else "
             "--allow-env]"),
    max_file_size: int = typer.Option(None, "--max-file-size", metavar="BYTES",
                                      help="Refuse input files larger than this [default: 16 MiB]."),
    controllers: list[Path] = typer.Option([], "--controllers", metavar="FILE",
                                           help="Controller configuration YAML (repeatable) "
                                                "[default: config/*.yaml beside the robot]."),
    srdf: Path = typer.Option(None, "--srdf", metavar="FILE",
                              help="MoveIt SRDF [default: the *.srdf beside the robot]."),
    spec: Path = typer.Option(None, "--spec", metavar="FILE",
                              help="Joint spec table [default: joint_limits.yaml beside the "
                                   "robot, when it is a urdftool spec]."),
    max_triangles: int = typer.Option(None, "--max-triangles", metavar="N", min=1,
                                      help="Refuse meshes with more triangles than this "
                                           "[default: 2,000,000, or max-triangles in the "
                                           "settings]."),
    timeout: float = timeout_option("each file", "the file is stopped and reported as U015, "
                                                 "exit 1", default=None,
                                    note=" [default: 60, or timeout in the settings]"),
    max_memory: str = max_memory_option("each worker", "its file is stopped and reported as "
                                        "U018, exit 1", default=None,
                                        note=" [default: 2G, or max-memory in the settings]"),
    jobs: int = typer.Option(0, "--jobs", "-j", metavar="N",
                             help="Check files in N worker processes [default: one per idle core, "
                                  "at most one per 4 files]."),
    fix: bool = typer.Option(False, "--fix", help="Apply the safe fixes ([*] in the report) to "
                             "the files (inside the repository), then report what remains."),
    unsafe_fixes: bool = typer.Option(False, "--unsafe-fixes",
                                      help="With --fix or --diff: the unsafe fixes ([~]) too."),
    diff: bool = typer.Option(False, "--diff", help="Print the fixes as a unified diff and "
                              "write nothing; exit 1 when there is something to fix."),
    no_cache: bool = typer.Option(False, "--no-cache", help="Neither read nor keep results."),
    cache_dir: Path = typer.Option(None, "--cache-dir", metavar="DIR",
                                   help="Keep results here between runs [default: "
                                        ".urdftool_cache; none when CI is set]."),
) -> None:
    values = dict(locals())  # the parameters, as Typer parsed them
    from urdftool.checking import run
    from urdftool.cli._common import TYPER

    raise typer.Exit(run(TYPER, **values))
