"""The ``urdftool`` command line: thin commands over core modules.

Each command lives in ``urdftool/cli/<name>.py`` with a ``register(app)`` function. The modules
are imported only when their command runs (click's lazily loaded subcommands): ``urdftool
--help`` lists them from :data:`COMMANDS`, and ``urdftool check`` imports only ``check``. Heavy
libraries are imported inside the command that needs them, so start-up stays fast.
"""

from __future__ import annotations

import importlib

import typer
from typer.core import TyperGroup

# name -> the first sentence of its help (the module's own help starts with it: tested), shown
# by ``urdftool --help`` without importing the command
COMMANDS = {
    "check": "Check robot descriptions (files or folders) and report problems.",
    "collisions": "Self-collision with FCL.",
    "crosscheck": "Load the robot with each real loader installed (Pinocchio, MuJoCo, "
                  "PyBullet, Drake, sdformat's gz sdf), each in a process of its own, and "
                  "compare: loaded or why not (at the line), mass, degrees of freedom, base, "
                  "links dropped, frame positions, inertia.",
    "dh": "Extract the D-H table of the chain from --base to --tip.",
    "diff": "Compare two robot descriptions (OLD NEW, or --rev REV FILE: FILE as it was at git "
            "revision REV, includes from the same revision): links and joints added, removed or "
            "renamed, changed joints, inertials, geometry and materials; then the effect: how "
            "far every frame moves at zero and over sampled configurations, mass and centre of "
            "mass, reach of --chain, pairs that newly collide or no longer do; the SRDF's "
            "groups and disabled pairs and the controller YAML beside each.",
    "dynamics": "Mass, centre of mass, energies K, P, L, M(q), G(q), C(q,v), torques with "
                "damping and friction, with a fixed or a --floating base, standing on "
                "--support, and gravity margins against effort limits.",
    "fk": "Forward kinematics: link poses for joint configurations.",
    "graph": "Draw the kinematic tree as Graphviz DOT: links as boxes (red: errors, orange: "
             "warnings), joints as edges labelled with type and limits.",
    "ik": "Inverse kinematics: joint values that put --tip at a pose relative to --base; "
          "--check-reach FILE: which targets the limb reaches.",
    "inertia": "Compare each link's inertial with its geometry's; fix them.",
    "render": "Draw the robot's visual (or --collision) geometry posed at a configuration "
              "(default: 0, or mid-range when 0 is outside the limits) as PNG or SVG: flat "
              "shading, no GPU, no display.",
    "rules": "List every rule, or show one rule's documentation (CODE or name).",
    "server": "Run the language server (LSP) on standard input and output, for editors: "
              "diagnostics as you type, rule documentation on hover, quick fixes.",
    "tree": "Print the kinematic tree in check_urdf's format.",
    "workspace": "Reach envelope of --tip relative to --base from sampled configurations, with "
                 "a picture.",
    "xacro": "Expand a xacro file to URDF; $(find) and package:// resolve without ROS.",
}


class LazyGroup(TyperGroup):
    """The command group that imports a command's module the first time it is asked for."""

    def list_commands(self, ctx) -> list[str]:
        return sorted({*COMMANDS, *self.commands})

    def resolve_command(self, ctx, args):
        """The command named by ``args[0]``; a name that is none: a usage error that suggests
        the closest command (``urdftool chek``: did you mean 'check'?). Typer's own suggestion
        looks only at the commands already imported, which here is none."""
        from typer._click.exceptions import UsageError

        try:
            return super().resolve_command(ctx, args)
        except UsageError as error:
            from urdftool.errors import close_names

            close = close_names(args[0], self.list_commands(ctx), n=1) if args else []
            if close and "did you mean" not in error.message.lower():
                error.message = f"{error.message.rstrip('.')}; did you mean '{close[0]}'?"
            raise

    def parse_args(self, ctx, args):
        """The words of every command, before any is parsed: a word that reads as an option
        while a file of that name exists is a usage error (terminal.option_named_by_a_file)."""
        from urdftool.errors import UsageError
        from urdftool.terminal import refuse_options_named_by_files

        try:
            refuse_options_named_by_files(args[1:])
        except UsageError as error:
            from urdftool.cli._common import fail_usage

            fail_usage(error)
        return super().parse_args(ctx, args)

    def get_command(self, ctx, name: str):
        if name not in self.commands and name in COMMANDS:
            self.add_command(command(name), name)
        return super().get_command(ctx, name)

    def format_commands(self, ctx, formatter) -> None:
        """The commands and their summaries, as click writes them, without importing them."""
        from typer._click.utils import make_default_short_help

        names = self.list_commands(ctx)
        limit = formatter.width - 6 - max(map(len, names))
        rows = [(name, make_default_short_help(COMMANDS[name], limit) if name in COMMANDS
                 else self.commands[name].get_short_help_str(limit)) for name in names]
        with formatter.section("Commands"):
            formatter.write_dl(rows)


def command(name: str):
    """The click command ``name`` (a key of :data:`COMMANDS`), its module imported now, its
    options made uniform by :func:`_uniform_options`. Shell completion is an option of
    ``urdftool`` itself, not of each command."""
    single = typer.Typer(rich_markup_mode=None, pretty_exceptions_enable=False,
                         add_completion=False)
    importlib.import_module(f"urdftool.cli.{name}").register(single)
    built = typer.main.get_command(single)
    _uniform_options(built)
    built.callback = _usage_errors_end(built.callback)
    return built


def _usage_errors_end(callback):
    """``callback`` ending a UsageError that reaches it (an output file the system refuses,
    written by a report) as every usage error ends: one line, exit 2."""
    import functools

    @functools.wraps(callback)
    def run(*args, **kwargs):
        from urdftool.errors import UsageError

        try:
            return callback(*args, **kwargs)
        except UsageError as error:
            from urdftool.cli._common import fail_usage

            fail_usage(error)

    return run


# metavar of an option that names none, by the kind of its value
_METAVARS = {"path": "FILE", "int": "N", "int range": "N", "float": "NUMBER",
             "float range": "NUMBER"}


def _uniform_options(built) -> None:
    """Every option's help the same way: one default, said once (an option whose help says its
    default in words, ``[default: number of cores]``, does not get click's ``[default: 0]``
    too), and a metavar in capitals (FILE, N, NUMBER, or the option's name: ``--format
    FORMAT``), never click's ``<str>``."""
    from typer.core import TyperOption

    for param in built.params:
        _finite_numbers(param)
        _bounded_integers(param)
        if not isinstance(param, TyperOption) or param.is_flag:
            continue
        if param.help and "[default:" in param.help:
            param.show_default = False
        if param.metavar is None:
            long = max(param.opts, key=len).lstrip("-")
            param.metavar = _METAVARS.get(param.type.name, long.upper().replace("-", "_"))


def _finite_numbers(param) -> None:
    """Every number a command reads as a float (``--density``, ``--timeout``, ``--tolerance``,
    ``--xyz X Y Z``, ...) finite: click reads ``nan``, ``inf`` and ``1e999`` as floats, and a
    NaN passes every ``min=``/``max=`` comparison (a NaN density gave NaN masses, a NaN
    tolerance made every change equal, an infinite timeout ended in a traceback). The one
    guard of the command line's numbers; ``JOINT=VALUE`` words are read by
    ``kinematics.configuration``, which refuses the same."""
    from typer._click import types

    if isinstance(param.type, types.Tuple):
        param.type.types = [_Finite(kind) if isinstance(kind, types.FloatParamType)
                            else kind for kind in param.type.types]
    elif isinstance(param.type, types.FloatParamType):
        param.type = _Finite(param.type)


def _Finite(kind):
    """A copy of click's float type ``kind`` (``FLOAT``, a ``FloatRange``: its help and range
    unchanged) whose conversion refuses NaN and infinities."""
    import copy
    import functools

    @functools.cache
    def finite_class(base):
        def convert(self, value, param, ctx):
            import math

            number = base.convert(self, value, param, ctx)
            if isinstance(number, float) and not math.isfinite(number):
                self.fail(f"{value!r} is not a finite number.", param, ctx)
            return number

        return type(f"Finite{base.__name__}", (base,), {"convert": convert})

    finite = copy.copy(kind)
    finite.__class__ = finite_class(type(kind))
    return finite


def _bounded_integers(param) -> None:
    """Every integer a command reads (``--seed``, ``--samples``, ``--random``, ``--workers``,
    ``--jobs``, ...) converted by :func:`urdftool.numbers.integer` and held within an int64:
    click's ``int()`` of 5,000 digits said "is not a valid integer" and quoted them all, and
    one past int64 reached numpy, which refused it with its own traceback ("Maximum allowed
    dimension exceeded", fk --random 10**30) or forked for it (``collisions --workers``). The
    one guard of the command line's integers, as :func:`_finite_numbers` is of its floats."""
    from typer._click import types

    if isinstance(param.type, types.Tuple):
        param.type.types = [_Int64(kind) if isinstance(kind, types.IntParamType) else kind
                            for kind in param.type.types]
    elif isinstance(param.type, types.IntParamType):
        param.type = _Int64(param.type)


def _Int64(kind):
    """A copy of click's integer type ``kind`` (``INT``, an ``IntRange``: its help and range
    unchanged) converting by :func:`urdftool.numbers.integer` and refusing what an int64 does
    not hold, each in a message that quotes the word cut (:func:`urdftool.errors.shown_word`)."""
    import copy
    import functools

    @functools.cache
    def bounded_class(base):
        def convert(self, value, param, ctx):
            from urdftool.errors import shown_word
            from urdftool.numbers import INT64, TooLong, in_int64, integer

            if isinstance(value, str):
                try:
                    value = integer(value.strip())
                except TooLong as error:
                    self.fail(f"'{shown_word(value.strip())}' is too long: {error}.", param, ctx)
                except ValueError:
                    self.fail(f"'{shown_word(value)}' is not a valid integer.", param, ctx)
            number = base.convert(self, value, param, ctx)
            if isinstance(number, int) and not in_int64(number):
                self.fail(f"{shown_word(str(number))} is past what an integer option holds "
                          f"(an int64: {INT64[0]} to {INT64[1]}).", param, ctx)
            return number

        return type(f"Bounded{base.__name__}", (base,), {"convert": convert})

    bounded = copy.copy(kind)
    bounded.__class__ = bounded_class(type(kind))
    return bounded


app = typer.Typer(
    name="urdftool",
    cls=LazyGroup,
    help="Validate and analyse URDF and xacro robot descriptions, without ROS.",
    no_args_is_help=True,
    add_completion=True,  # --install-completion / --show-completion for bash, zsh, fish
    pretty_exceptions_enable=False,
    rich_markup_mode=None,  # plain click help: rich formatting would import rich for --help
    context_settings={"help_option_names": ["-h", "--help"]},
)


def _version(value: bool):
    if value:
        from urdftool import __version__

        from urdftool.cli._common import say

        say(f"urdftool {__version__}")
        raise typer.Exit()


@app.callback()
def _root(version: bool = typer.Option(False, "--version", "-V", callback=_version,
                                       is_eager=True, help="Show the version and exit.")):
    """Validate and analyse URDF and xacro robot descriptions, without ROS."""


def main() -> None:
    """The ``urdftool`` program, on the words of ``sys.argv``."""
    app(prog_name="urdftool")


if __name__ == "__main__":
    main()
