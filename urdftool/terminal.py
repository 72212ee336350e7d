"""How a command prints and exits, and the command-line words every robot command reads,
without Typer: the commands print through :data:`urdftool.cli._common.TYPER` (click's echo,
Typer's exit), and the door (``urdftool/__main__.py``) runs a ``check`` whose words are plain
through a :class:`Terminal` of its own (:func:`plain`), Typer never imported.

:meth:`Terminal.say`, :meth:`Terminal.show` and :meth:`Terminal.document` are the only ways a
command prints (``tests/report/test_escape.py``).
"""

from __future__ import annotations

import sys
from pathlib import Path

from urdftool.errors import UsageError


class Terminal:
    """Printing and exiting for a command: ``echo(text, err=False, nl=True)`` writes a line
    (click's echo, or :func:`plain_echo`); ``exit(code)`` is the exception that ends the
    command with ``code`` (Typer's Exit, or SystemExit)."""

    def __init__(self, echo, exit):
        self.echo, self.exit = echo, exit

    def say(self, message: object, err: bool = False) -> None:
        """Print a message, one line of terminal text (:func:`urdftool.report.escape.text`): a
        name from the robot's files, a file name or a word of the command line in it cannot
        end the line, start a workflow command or send an escape sequence."""
        from urdftool.report.escape import text

        self.echo(text(message), err=err)

    def show(self, block: str, err: bool = False, nl: bool = True, keep: str = "") -> None:
        """Print the lines a renderer built (its values escaped as terminal text), each line
        through :func:`urdftool.report.escape.text` once more: whatever reached it, no line it
        prints is a workflow command or holds an escape sequence. ``keep``: characters left as
        they are (tabs of lines copied from a file)."""
        from urdftool.report.escape import lines

        self.echo(lines(block, keep), err=err, nl=nl)

    @staticmethod
    def document(data: str, xml: bool = False) -> None:
        """Write a document to standard output exactly as a report function made it for a
        terminal or a log (JSON, a report format, ``urdftool xacro``'s XML): its own kind's
        escaping is done (urdftool.report.escape), :meth:`say`'s would change its data.
        ``xml``: what the stream's encoding cannot hold becomes character references
        (:func:`urdftool.report.escape.write_xml`)."""
        if xml:
            from urdftool.report.escape import write_xml

            write_xml(sys.stdout, data)
        else:
            sys.stdout.write(data)

    def fail_usage(self, error: UsageError) -> None:
        self.say(f"urdftool: error: {error}", err=True)
        raise self.exit(2)

    def refuse_bad_outputs(self, *paths, inputs=(), also=()) -> None:
        """Exit 2 with one line when an output path given (None: not given) cannot be written:
        its folder is missing or it is a folder, it would replace an input of the command
        (:func:`replaced_input`: ``check robot.urdf -o robot.urdf`` wrote its report over the
        robot), or it names the file another output of the command (of ``paths`` or ``also``,
        outputs checked elsewhere) names (``diff --render x.svg -o x.svg``: the picture written
        over the report, which was lost). Call it before the work."""
        from urdftool.description.files import check_output

        try:
            for path in paths:
                if path is not None:
                    check_output(path)
                    replaced = replaced_input(path, inputs)
                    if replaced is not None:
                        raise UsageError(f"cannot write '{path}': it is {replaced}, which the "
                                         "output would replace; give another file name")
            named = [path for path in (*paths, *also) if path is not None]
            first: dict[str, int] = {}
            for index, path in enumerate(named):
                at = first.setdefault(_written_at(path), index)
                if at != index:
                    raise UsageError(f"'{path}' and '{named[at]}' name one file, where two "
                                     "outputs of the command would be written; give another "
                                     "file name")
        except UsageError as error:
            self.fail_usage(error)

    def write_output(self, path, data: str | bytes, rewrites: bool | frozenset = False) -> None:
        """Write an output file with :func:`urdftool.description.files.write_file` (a symbolic
        link planted at ``path`` is replaced, never followed; a file the command read is not
        replaced unless ``rewrites``); exit 2 with one line when it cannot be written."""
        from urdftool.description.files import write_file

        try:
            write_file(path, data, rewrites)
        except UsageError as error:
            self.fail_usage(error)


def _written_at(output) -> str:
    """Where writing ``output`` puts a file: its name in its folder's real place (a link at
    that name is replaced, never followed: files.write_file)."""
    import os

    from urdftool.description.files import real_path

    output = os.path.abspath(output)
    return os.path.join(real_path(os.path.dirname(output)), os.path.basename(output))


def replaced_input(output, inputs) -> str | None:
    """What writing ``output`` would replace of the command's ``inputs`` (its words: files,
    folders, ``NAME:=VALUE``), in words; None when nothing: the very file named (links
    followed), refused before the work. What the command reads below a folder or through a
    file is refused where files are written (:func:`urdftool.description.files.write_file`:
    any file this process read), which knows it exactly."""
    import os

    from urdftool.description.files import kind_of, real_path

    # what the writer replaces: the file at that very name (a link there is replaced, never
    # followed: files.write_file), in its folder's real place
    if kind_of(output, follow=False) != "file":
        return None
    real = _written_at(output)
    for word in inputs:
        word = os.fspath(word)
        if word == "-" or ":=" in word:
            continue
        if kind_of(word) == "file" and real_path(word) == real:
            return "an input of the command"
    return None


def plain_echo(message: str, err: bool = False, nl: bool = True) -> None:
    """click's echo of a text where it is the same (see :func:`plain`): write, then flush."""
    stream = sys.stderr if err else sys.stdout
    stream.write(message + "\n" if nl else message)
    stream.flush()


def plain() -> Terminal | None:
    """A Terminal printing as click does, without click, or None when click would print
    otherwise: a standard stream missing or not a text stream of its own encoding that can
    write any text (click rewraps an ASCII one), or not a POSIX system (click's Windows
    console). urdftool's lines hold no escape sequence (:func:`urdftool.report.escape.text`),
    which click would strip off a terminal."""
    import os

    if os.name != "posix":
        return None
    for stream in (sys.stdout, sys.stderr):
        encoding = getattr(stream, "encoding", None)
        if stream is None or not encoding or not hasattr(stream, "buffer"):
            return None
        if encoding.lower().replace("-", "").replace("_", "") not in ("utf8", "utf8sig"):
            return None
    return Terminal(plain_echo, SystemExit)


def option_named_by_a_file(words: list[str]) -> str | None:
    """The first word before ``--`` that reads as an option (``--select=U9.yaml``,
    ``-oREADME.urdf``) while a file or link of that very name exists: a file name a stranger
    committed, handed over by a tool that appends file names without ``--`` (pre-commit's
    ``pass_filenames``), which the parser would take as an option (a companion named on the
    command line is read wherever its link leads; ``--select`` checks nothing). None when
    there is none. One ``lstat`` per word that starts with ``-`` (the door's ``kind_of``)."""
    for word in words:
        if word == "--":
            return None
        if word.startswith("-") and word != "-":
            from urdftool.description.files import kind_of

            if kind_of(word, follow=False):
                return word
    return None


def refuse_options_named_by_files(words: list[str]) -> None:
    """UsageError when :func:`option_named_by_a_file` finds one: every command, both doors
    (``__main__``'s plain check and the Typer app)."""
    word = option_named_by_a_file(words)
    if word is not None:
        raise UsageError(f"'{word}' reads as an option, but a file of that name exists here; "
                         "name files after '--' (urdftool COMMAND [OPTIONS] -- FILE...)")


def split_words(words: list[str]) -> tuple[list[str], dict[str, str]]:
    """Separate ``name:=value`` xacro words from paths."""
    paths, args = [], {}
    for word in words:
        if ":=" in word:
            name, _, value = word.partition(":=")
            args[name] = value
        else:
            paths.append(word)
    return paths, args


def pairs(values: list[str], what: str, separator: str = "=",
          strip: bool = False, last: bool = False) -> dict[str, str]:
    """``NAME=VALUE`` option values as a dict; a malformed one is a usage error. The one
    NAME=VALUE parser: --arg, --package, --q, --v, --a.

    strip: remove blanks around each NAME (joint values: ``--q " elbow=1"``)
    last: split at the last separator, not the first: a NAME that may hold it and a VALUE that
        cannot (a joint named ``gain=2`` and its number: ``--q gain=2=0.5``)
    """
    result = {}
    for value in values:
        name, sep, rest = value.rpartition(separator) if last else value.partition(separator)
        name = name.strip() if strip else name
        if not sep or not name:
            raise UsageError(f"{what} must be NAME{separator}VALUE, got '{value}'")
        result[name] = rest
    return result


def robot_inputs(words: list[str], arg_options: list[str], package_options: list[str]):
    """(paths, xacro args, packages) from a command's words and options; checks paths exist."""
    paths, args = split_words(words)
    args.update(pairs(arg_options, "--arg"))
    packages = {name: Path(path) for name, path in pairs(package_options, "--package").items()}
    from urdftool.description.files import kind_of, unreachable

    for path in paths:
        if path != "-" and not kind_of(path):
            raise UsageError(f"path '{path}' {unreachable(path)}")
    return paths, args, packages
