"""ROS 2 Python launch files read by static analysis of their syntax tree (``ast``), never run.

The functions a launch file defines are walked from ``generate_launch_description`` (and the
functions it hands to ``OpaqueFunction`` or calls), their assignments followed, and the calls
that make launch actions read into :class:`~urdftool.description.launch.LaunchFile` actions:

- ``DeclareLaunchArgument(name, default_value=...)``, ``SetLaunchConfiguration``;
- ``Node(package=..., executable=..., arguments=[...], parameters=[...], remappings=[...],
  condition=...)``,
  ``ExecuteProcess(cmd=[...])``; parameter files given as paths, ``ParameterFile(path,
  allow_substs=True)``;
- ``IncludeLaunchDescription(PythonLaunchDescriptionSource(path), launch_arguments=...)``;
- ``GroupAction(actions, condition=...)`` (its condition held by every action inside it, in
  nested groups too), ``TimerAction``, ``RegisterEventHandler``;
  ``SetRemap(src, dst)``, for the nodes and includes after it in its group;
- robot descriptions: ``Command([FindExecutable(name="xacro"), " ", path, " name:=", ...])``,
  ``xacro.process_file(path, mappings={...})``, ``xacro.process_doc`` of a file ``xacro.parse`` read,
  MoveItConfigsBuilder's
  ``robot_description(file_path=..., mappings=...)``.

Values are read through ``LaunchConfiguration``, ``EnvironmentVariable`` and
``os.environ[NAME]``, ``os.environ.get``, ``os.getenv`` (a value given at launch, like an
argument), ``FindPackageShare``,
``get_package_share_directory`` (of a package named in the file, or by such a value:
``FindPackageShare(LaunchConfiguration("description_package"))``), ``PathJoinSubstitution``,
``os.path.join``, ``/`` on paths, ``+``, f-strings and ``TextSubstitution``; anything else (a value a function computes at run
time) is unknown. A Python ``if`` around an action is a condition read from its test when it
compares a launch argument with a constant, else an unknown one that names the test. The walk
is bounded (steps, depth, loop items); a file it cannot parse has a ``problem``.
"""

from __future__ import annotations

import ast
from ast import walk as ast_nodes  # (in memory: ast.walk reads no file)
from pathlib import Path

from urdftool.description.launch import (MAX_ACTIONS, Arg, Condition, Description, Include,
                                         LaunchFile, ParamFile, Remap, Start, Value, concat,
                                         literal, unknown)
from urdftool.records import NEW
from urdftool.errors import described
from urdftool.numbers import is_decimal

MAX_STEPS = 200_000  # expressions and statements evaluated per file
MAX_DEPTH = 40  # nested expressions, and calls into the file's own functions
MAX_LOOP_ITEMS = 64
# what reading the Python launch files of one repository (tests among them) may cost, all of
# them together: its bounds per file (MAX_STEPS, MAX_LAUNCH_SIZE) times MAX_LAUNCH_FILES were
# minutes; the most the 105 repositories of the real sweep use is 15,374 steps, 0.65 MB of text
# and 0.43 M characters built (xarm_ros2, moveo_ros)
MAX_REPOSITORY_STEPS = 1_000_000
MAX_REPOSITORY_CHARACTERS = 16 * 1024 * 1024  # of text parsed, and of texts built
MAX_REPOSITORY_ITEMS = 1_000_000  # of lists, dicts and texts' parts built
_BUILDS_NOTHING = (ast.Name, ast.Constant, ast.Subscript, ast.IfExp)  # (values already built)
_SOURCES = ("PythonLaunchDescriptionSource", "XMLLaunchDescriptionSource",
            "YAMLLaunchDescriptionSource", "AnyLaunchDescriptionSource",
            "FrontendLaunchDescriptionSource")
_TRY = (ast.Try, ast.TryStar)
_SHARE = ("FindPackageShare", "FindPackagePrefix", "get_package_share_directory",
          "get_package_share_path", "get_package_prefix")


MAX_MODULES = 16  # other modules of the repository the reading of one launch file may enter


class Modules:
    """Where the Python modules a launch file imports are, and their syntax trees: none here
    (a launch file read alone); a repository's are
    :class:`~urdftool.description.launch_configs.RepositoryModules`."""

    def named(self, name: str, level: int, importer: Path) -> Path | None:
        """The file of the module ``import name`` (``from name import ...``; ``level`` dots
        before it, relative to ``importer``'s package) reaches in the repository, else None."""
        return None

    def at(self, path: Value, importer: Path) -> Path | None:
        """The file ``load_python_launch_file_as_module(path)`` loads, else None."""
        return None

    def tree(self, path: Path) -> tuple[ast.Module, int] | None:
        """The module's syntax tree and the length of its text, None when it cannot be read."""
        return None


class _Stop(Exception):
    """The budget is spent."""


class Room:
    """What reading Python launch files may still cost (MAX_REPOSITORY_*): one per repository
    and run (:func:`urdftool.description.launch_configs.reading_room`), drawn on by every file
    read, whatever makes the reader work: steps walked, text parsed, and what the values its
    expressions build hold (:meth:`_Reader.built`)."""

    def __init__(self):
        self.steps, self.characters, self.items = (MAX_REPOSITORY_STEPS,
                                                   MAX_REPOSITORY_CHARACTERS, MAX_REPOSITORY_ITEMS)


class _Act:
    """An action made while walking; conditions of enclosing groups are added afterwards."""

    def __init__(self, kind: str, when: tuple, line: int | None, **fields):
        self.kind, self.when, self.line, self.fields = kind, list(when), line, fields


def read_python_launch(path: Path, display: str, text: str,
                       entry: str = "generate_launch_description", room: Room | None = None,
                       modules: Modules | None = None) -> LaunchFile:
    """A Python launch file read from the function ``entry`` (a launch test's
    ``generate_test_description``: :func:`~urdftool.description.launch.is_launch_test`), at
    the cost of ``room`` (its repository's; a room of its own when None), the modules of the
    repository it imports found by ``modules`` (none when None)."""
    launch = LaunchFile(path, display, "ros2-python", test=entry != "generate_launch_description")
    room = room if room is not None else Room()
    if len(text) > room.characters:
        launch.problem = "not read: the launch files of its repository are too large to read all"
        return launch
    room.characters -= len(text)
    try:
        tree = ast.parse(text, filename=display)
    except (SyntaxError, ValueError, RecursionError, MemoryError) as error:
        launch.problem = f"not valid Python: {described(error)}" if str(error) \
            else "not valid Python: nested too deeply for Python's parser"  # (MemoryError,
        launch.problem_line = getattr(error, "lineno", None)  # RecursionError: no text; the
        # launch file does not start either: "s_push: parser stack overflow")
        return launch
    reader = _Reader(tree, entry, room, path, modules or Modules())
    try:
        reader.run()
    except (_Stop, RecursionError):
        launch.problem = "too large or too deeply nested to read completely; read in part"
    finally:
        room.steps -= reader.steps
    _described_where_used(reader.acts)
    # A launch configuration is read when its action runs, after every argument is declared:
    # the declarations come first, whichever line made them.
    acts = sorted(reader.acts, key=lambda act: act.kind != "arg" or act.fields["fixed"])
    launch.actions = [action for action in (reader.convert(act) for act in acts)
                      if action is not None][:MAX_ACTIONS]
    return launch


class _Reader:
    def __init__(self, tree: ast.Module, entry: str, room: Room, path: Path, modules: Modules):
        self.tree, self.entry, self.path, self.modules = tree, entry, path, modules
        self.entered_modules: dict[str, _Module | None] = {}  # path -> module (None: entering)
        self.site: int | None = None  # the launch file's line calling into another module
        self.functions: dict[str, ast.FunctionDef] = {}
        self.acts: list[_Act] = []
        self.steps, self.max_steps, self.room = 0, min(MAX_STEPS, room.steps), room
        self.walked: set[str] = set()
        # names the launch file reads somewhere, and its own assignments: an action assigned
        # only to names it never reads is never handed to a launch description
        self.read_names = {n.id for n in ast_nodes(tree) if isinstance(n, ast.Name)
                           and isinstance(n.ctx, ast.Load)}
        self.own_assignments = {id(n) for n in ast_nodes(tree) if isinstance(n, ast.Assign)}

    # --- statements -----------------------------------------------------------------------

    def run(self) -> None:
        module_env: dict = {}
        self.block(self.tree.body, module_env, (), 0, top=True)
        entry = self.functions.get(self.entry)
        order = [entry] if entry is not None else []
        # then the functions handed over rather than called (OpaqueFunction(function=f)): a
        # helper the others call is walked where it is called, with its arguments
        others = [name for name, f in self.functions.items() if f is not entry]
        if others:  # (every node looked at: only when there is a function to hand over)
            handed = set()
            for node in _calls(self.tree):
                if isinstance(node.func, ast.Name):
                    handed.update(a.id for a in [*node.args, *(k.value for k in node.keywords)]
                                  if isinstance(a, ast.Name))
            order += [self.functions[name] for name in others if name in handed]
        for function in order:
            if function.name not in self.walked:
                self.call_function(function, [], {}, module_env, (), 0)

    def tick(self) -> None:
        self.steps += 1
        if self.steps > self.max_steps:
            raise _Stop

    def built(self, value):
        """``value``, a value just built (an expression's, a list grown in place), charged to
        the room (:class:`Room`: characters, and items counted through every nesting, shared
        ones each time): the one bound on what files make the reader build, in memory and
        time, whatever builds it (``x = x + x``, f-strings, ``x += x``, ``x.extend(x)``, ``x =
        [x, x]``, a list inside itself). _Stop when spent."""
        room, stack = self.room, [value]
        while stack:
            item = stack.pop()
            room.items -= 1
            if isinstance(item, Value):
                room.characters -= len(item.text) + sum(len(p) for p in item.parts
                                                        if isinstance(p, str))
                room.items -= len(item.parts)
            elif isinstance(item, list):
                stack.extend(item)
            elif isinstance(item, dict):
                stack.extend(item.values())
            if room.characters < 0 or room.items < 0:
                raise _Stop
        return value

    def block(self, statements, env: dict, when: tuple, depth: int, top: bool = False):
        """Walk statements; the value of a ``return`` if one is reached."""
        for index, statement in enumerate(statements):
            self.tick()
            if isinstance(statement, (ast.FunctionDef, ast.AsyncFunctionDef)):
                self.functions.setdefault(statement.name, statement)
            elif top and not isinstance(statement, (ast.Assign, ast.AnnAssign, ast.Import,
                                                    ast.ImportFrom)):
                continue
            elif isinstance(statement, ast.Assign):
                value = self.eval(statement.value, env, when, depth)
                for target in statement.targets:
                    self.bind(target, value, env)
                self.unread(statement, value)
            elif isinstance(statement, ast.AnnAssign) and statement.value is not None:
                self.bind(statement.target, self.eval(statement.value, env, when, depth), env)
            elif isinstance(statement, ast.AugAssign) and isinstance(statement.target, ast.Name):
                value = self.eval(statement.value, env, when, depth)
                current = env.get(statement.target.id)
                if isinstance(current, list) and isinstance(value, list):
                    self.built(current).extend(value)
                    self.built(current)
                elif isinstance(current, Value) and isinstance(value, Value):
                    env[statement.target.id] = self.built(concat([current, value]))
            elif isinstance(statement, ast.Expr):
                self.eval(statement.value, env, when, depth)
            elif isinstance(statement, ast.Return):
                return self.eval(statement.value, env, when, depth) if statement.value else None
            elif isinstance(statement, ast.If):
                decided, test = self.judged(statement.test, env, depth)
                if decided is not None:  # a test of values the file gives: one branch runs
                    found = self.block(statement.body if decided else statement.orelse, env,
                                       when, depth)
                    if found is not None:
                        return found
                    continue
                found = self.block(statement.body, env, when + (test,), depth)
                otherwise = self.block(statement.orelse, env, when + (_negated(test),), depth)
                if found is not None and otherwise is None:
                    # a guard (``if not ok: return LaunchDescription([])``): what follows
                    # runs when its test does not hold
                    otherwise = self.block(statements[index + 1:], env,
                                           when + (_negated(test),), depth)
                elif otherwise is not None and found is None:
                    found = self.block(statements[index + 1:], env, when + (test,), depth)
                if found is not None or otherwise is not None:
                    return _either(found, otherwise, test)
            elif isinstance(statement, (ast.For, ast.AsyncFor)):
                for item in self.items(statement.iter, env, depth):
                    self.bind(statement.target, item, env)
                    self.block(statement.body, env, when, depth)
            elif isinstance(statement, (ast.With, ast.AsyncWith)):
                for item in statement.items:  # with open(path) as file: the file
                    if item.optional_vars is not None:
                        self.bind(item.optional_vars,
                                  self.eval(item.context_expr, env, when, depth), env)
                found = self.block(statement.body, env, when, depth)
                if found is not None:
                    return found
            elif isinstance(statement, _TRY):
                # what the body returns when nothing fails (``try: with open(p) as f: return
                # f.read()``), else what ``else`` or ``finally`` returns; a handler's is the
                # failure's (``except OSError: return None``), walked for its actions only
                found = None
                for body in (statement.body, statement.orelse, statement.finalbody):
                    value = self.block(body, env, when, depth)
                    found = found if found is not None else value
                for handler in statement.handlers:
                    self.block(handler.body, env, when, depth)
                if found is not None:
                    return found
            elif isinstance(statement, (ast.Import, ast.ImportFrom)):
                self.imported(statement, env, depth)
        return None

    def unread(self, statement: ast.Assign, value) -> None:
        """Forget ``value``, a node or include just made, when ``statement`` of the launch file
        assigns it only to names the file never reads: it is never handed to a launch
        description, so never started (wearable_robot_eval's eduexo_only.launch.py builds
        ``eduexo_forward_position_controller_node = Node(... spawner ...)`` and returns a
        LaunchDescription without it). A name read anywhere in the file keeps it, whatever reads
        it; a module the file imports is not asked."""
        if isinstance(value, _Act) and value.kind in ("start", "include") and \
                id(statement) in self.own_assignments and all(
                    isinstance(t, ast.Name) and t.id not in self.read_names
                    for t in statement.targets):
            self.acts[:] = [act for act in self.acts if act is not value]

    def bind(self, target, value, env: dict) -> None:
        if isinstance(target, ast.Name):
            env[target.id] = value
        elif isinstance(target, ast.Attribute) and isinstance(target.value, ast.Name) and \
                isinstance(env.get(target.value.id), _Instance):  # self.path = ...
            env[target.value.id].attributes[target.attr] = value
        elif isinstance(target, (ast.Tuple, ast.List)):
            values = value if isinstance(value, list) and len(value) == len(target.elts) else \
                [unknown("?")] * len(target.elts)
            for element, item in zip(target.elts, values):
                self.bind(element, item, env)

    def items(self, node, env: dict, depth: int) -> list:
        """What a ``for`` loop or comprehension iterates over: the items of a list the file
        writes out (bounded), else one unknown item."""
        value = self.eval(node, env, (), depth)
        if isinstance(value, dict):
            value = [literal(k) if isinstance(k, str) else k for k in value]
        if isinstance(value, list) and value:
            return value[:MAX_LOOP_ITEMS]
        return [unknown(_source(node))]

    def call_function(self, function, args, keywords, env, when, depth, foreign=False):
        """What ``function`` returns called with ``args`` and ``keywords``, its globals ``env``
        (the caller's for the file's own functions; its module's when ``foreign``); a
        parameter not given has its default (evaluated there, making no action), else is
        unknown."""
        if depth > MAX_DEPTH // 4:
            return None
        if not foreign:
            self.walked.add(function.name)
        local = dict(env)
        names = [a.arg for a in [*function.args.posonlyargs, *function.args.args]]
        defaults = dict(zip(names[len(names) - len(function.args.defaults):],
                            function.args.defaults))
        defaults.update((a.arg, d) for a, d in zip(function.args.kwonlyargs,
                                                   function.args.kw_defaults) if d is not None)
        for name, value in zip(names, args):
            local[name] = value
        for name in [*names[len(args):], *(a.arg for a in function.args.kwonlyargs)]:
            if name in keywords:
                local[name] = keywords[name]
            elif name in defaults:
                made = len(self.acts)
                local[name] = self.eval(defaults[name], env, (), depth)
                del self.acts[made:]
            else:
                local[name] = unknown(name)
        if function.args.vararg is not None:
            local[function.args.vararg.arg] = list(args[len(names):])
        return self.block(function.body, local, when, depth + 1)

    # --- other modules of the repository ----------------------------------------------------

    def imported(self, statement, env: dict, depth: int, importer: Path | None = None) -> None:
        """``import m`` / ``from m import name``: a module of the repository
        (:meth:`Modules.named`) is read, never run (:meth:`entered`), and the names bound to
        what it defines; any other module binds nothing (its names stay unknown)."""
        importer = importer or self.path
        if isinstance(statement, ast.Import):
            for alias in statement.names:
                if alias.asname is None and "." in alias.name:
                    continue  # (import a.b binds a, a package: its attributes are modules)
                module = self.entered(self.modules.named(alias.name, 0, importer), depth)
                if module is not None:
                    env[alias.asname or alias.name] = module
            return
        name = statement.module or ""
        module = self.entered(self.modules.named(name, statement.level, importer), depth)
        for alias in statement.names:
            if alias.name == "*":
                if module is not None:
                    env.update((k, v) for k, v in module.env.items() if not k.startswith("_"))
                continue
            found = module.env.get(alias.name) if module is not None else None
            if found is None:  # from package import module
                found = self.entered(self.modules.named(f"{name}.{alias.name}".lstrip("."),
                                                        statement.level, importer), depth)
            if found is not None:
                env[alias.asname or alias.name] = found

    def entered(self, path: Path | None, depth: int):
        """The module of the repository at ``path`` read: its functions and classes, and the
        values its top level assigns (any action made there dropped: importing a module adds
        nothing to a launch description); at most MAX_MODULES a launch file, each once."""
        if path is None:
            return None
        key = str(path)
        if key in self.entered_modules:
            return self.entered_modules[key]  # (None while it is being entered: a cycle)
        if len(self.entered_modules) >= MAX_MODULES or depth > MAX_DEPTH // 4:
            return None
        self.entered_modules[key] = None
        read = self.modules.tree(path)
        if read is None:
            return None
        tree, size = read
        if size > self.room.characters:
            raise _Stop
        self.room.characters -= size
        module = _Module(path, {})
        made = len(self.acts)
        for statement in tree.body:
            self.tick()
            if isinstance(statement, (ast.FunctionDef, ast.AsyncFunctionDef)):
                module.env[statement.name] = _Function(statement, module)
            elif isinstance(statement, ast.ClassDef):
                module.env[statement.name] = _class(statement, module)
            elif isinstance(statement, (ast.Import, ast.ImportFrom)):
                self.imported(statement, module.env, depth + 1, path)
            elif isinstance(statement, (ast.Assign, ast.AnnAssign)):
                self.block([statement], module.env, (), depth + 1)
        del self.acts[made:]
        self.entered_modules[key] = module
        return module

    def call_target(self, target, args, keywords, when, depth, node):
        """A call of what another module defines: a function (a class's static or class
        method, or a method of an instance made here), or a class (an instance). What it
        makes is the launch file's, at the line of its call there."""
        if isinstance(target, _Class):
            made = _Instance((("unknown", _source(node)),), _source(node), target)
            initial = target.attributes.get("__init__")
            if initial is not None:
                self.call_target(_Function(initial.node, initial.module, made), args, keywords,
                                 when, depth, node)
            return made
        if target.bound is not None:
            args = [target.bound, *args]
        outer = self.site
        self.site = self.line(node)
        try:
            result = self.call_function(target.node, args, keywords, target.module.env, when,
                                        depth, foreign=True)
        finally:
            self.site = outer
        return result if result is not None else unknown(_source(node))

    def line(self, node) -> int:
        """The launch file's line of what ``node`` makes: its own, or, inside another module's
        function, that of the launch file's call into it."""
        return self.site or node.lineno

    # --- conditions -----------------------------------------------------------------------

    def judged(self, test, env: dict, depth: int) -> tuple[bool | None, Condition | None]:
        """An ``if`` test, its sides evaluated once: (its outcome, None) when it compares
        values the file gives (``arm == "no-arm"``, ``arm in ["no-arm", "none"]`` with ``arm``
        a literal: a helper called with literal arguments; no action made), else (None, the
        test as a condition: :meth:`condition`)."""
        op = test.ops[0] if isinstance(test, ast.Compare) and len(test.ops) == 1 else None
        if not isinstance(op, (ast.Eq, ast.NotEq, ast.In, ast.NotIn)):
            return None, self.condition(test, env, depth)
        made = len(self.acts)
        left = self.eval(test.left, env, (), depth)
        right = self.eval(test.comparators[0], env, (), depth)
        outcome = _outcome(op, left, right)
        if outcome is None and isinstance(op, (ast.Eq, ast.NotEq)) and \
                isinstance(left, Value) and isinstance(right, Value):
            kind = "equals" if isinstance(op, ast.Eq) else "differs"
            return None, Condition(kind, left, _source(test), right)
        del self.acts[made:]  # (decided: no action; else read again, whole, as a condition)
        if outcome is not None:
            return outcome, None
        return None, self.condition(test, env, depth)

    def condition(self, test, env: dict, depth: int) -> Condition:
        """A Python test as a condition: ``x == "c"``/``x != "c"`` on a launch argument, else
        unknown (naming the test and the arguments it reads)."""
        text = _source(test)
        if isinstance(test, ast.Compare) and len(test.ops) == 1 and \
                isinstance(test.ops[0], (ast.Eq, ast.NotEq)):
            left = self.eval(test.left, env, (), depth)
            right = self.eval(test.comparators[0], env, (), depth)
            if isinstance(left, Value) and isinstance(right, Value):
                kind = "equals" if isinstance(test.ops[0], ast.Eq) else "differs"
                return Condition(kind, left, text, right)
        reads = [v for v in _values_in(self.eval(test, env, (), depth))]
        return Condition("unknown", concat(reads) if reads else literal(""), text)

    # --- expressions ----------------------------------------------------------------------

    def eval(self, node, env: dict, when: tuple, depth: int):
        value = self.evaluated(node, env, when, depth)
        return value if isinstance(node, _BUILDS_NOTHING) else self.built(value)

    def evaluated(self, node, env: dict, when: tuple, depth: int):
        self.tick()
        if depth > MAX_DEPTH:
            return unknown(_source(node))
        depth += 1
        if isinstance(node, ast.Constant):
            if isinstance(node.value, bool):
                return literal(str(node.value).lower())
            if isinstance(node.value, (str, int, float)):
                return literal(str(node.value))
            return None
        if isinstance(node, ast.Name):
            if node.id in env:
                return env[node.id]
            return unknown(node.id)
        if isinstance(node, (ast.List, ast.Tuple, ast.Set)):
            found = []
            for element in node.elts:
                if isinstance(element, ast.Starred):
                    value = self.eval(element.value, env, when, depth)
                    found.extend(value if isinstance(value, list) else [value])
                else:
                    found.append(self.eval(element, env, when, depth))
            return found
        if isinstance(node, ast.Dict):
            result, partial = {}, False
            for key, value in zip(node.keys, node.values):
                evaluated = self.eval(value, env, when, depth)
                if key is None:
                    if isinstance(evaluated, dict):
                        result.update(evaluated)
                        partial = partial or isinstance(evaluated, _Partial)
                    else:
                        partial = True
                    continue
                name = self.eval(key, env, when, depth)
                if isinstance(name, Value) and name.literal is not None:
                    result[name.literal] = evaluated
                else:
                    partial = True
            return _Partial(result) if partial else result
        if isinstance(node, ast.JoinedStr):
            parts = []
            for value in node.values:
                part = self.eval(value.value if isinstance(value, ast.FormattedValue) else value,
                                 env, when, depth)
                parts.append(part if isinstance(part, Value) else unknown(_source(value)))
            return concat(parts, _source(node))
        if isinstance(node, ast.BinOp):
            left = self.eval(node.left, env, when, depth)
            right = self.eval(node.right, env, when, depth)
            if isinstance(node.op, ast.Add):
                if isinstance(left, Value) and isinstance(right, Value):
                    return concat([left, right])
                if isinstance(left, list) and isinstance(right, list):
                    return left + right
            if isinstance(node.op, ast.Div) and isinstance(left, Value) and isinstance(right, Value):
                return _joined([left, right])
            return unknown(_source(node))
        if isinstance(node, ast.IfExp):
            return self.eval(node.body, env, when, depth)
        if isinstance(node, ast.Subscript):
            return self.subscript(node, env, when, depth)
        if isinstance(node, ast.Attribute):
            owner = env.get(node.value.id) if isinstance(node.value, ast.Name) else None
            found = _attribute(owner, node.attr) if isinstance(owner, _DEFINING) else None
            return found if found is not None else unknown(_source(node))
        if isinstance(node, (ast.ListComp, ast.GeneratorExp)) and len(node.generators) == 1:
            generator, found = node.generators[0], []
            local = dict(env)
            for item in self.items(generator.iter, env, depth):
                self.bind(generator.target, item, local)
                found.append(self.eval(node.elt, local, when, depth))
            return found
        if isinstance(node, ast.Call):
            return self.call(node, env, when, depth)
        return unknown(_source(node))

    def subscript(self, node, env, when, depth):
        container = node.value
        # context.launch_configurations["name"]
        if isinstance(container, ast.Attribute) and container.attr == "launch_configurations":
            key = self.eval(node.slice, env, when, depth)
            if isinstance(key, Value) and key.literal:
                return Value((("arg", key.literal, None),), _source(node))
        key = self.eval(node.slice, env, when, depth)
        if _callee(container) == "os.environ":  # os.environ["NAME"]: a value given at launch
            if isinstance(key, Value) and key.literal:
                return Value((("env", key.literal, None),), _source(node))
            return unknown(_source(node))
        value = self.eval(container, env, when, depth)
        if isinstance(value, dict) and isinstance(key, Value) and key.literal in value:
            return value[key.literal]
        literal = key.literal or "" if isinstance(key, Value) else ""
        if isinstance(value, list) and len(literal) < 20 and \
                is_decimal(literal.removeprefix("-")):  # ('²': int() raised ValueError)
            index = int(literal)
            if -len(value) <= index < len(value):
                return value[index]
        return unknown(_source(node))

    def call(self, node: ast.Call, env: dict, when: tuple, depth: int):
        name = _callee(node.func)
        args = [self.eval(a.value if isinstance(a, ast.Starred) else a, env, when, depth)
                for a in node.args]
        keywords = {k.arg: self.eval(k.value, env, when, depth) for k in node.keywords if k.arg}
        line = self.line(node)
        method = node.func.attr if isinstance(node.func, ast.Attribute) else None
        if method is not None:
            found = self.method(node, method, args, keywords, env, when, depth)
            if found is not _NOT_HANDLED:
                return found
        target = env.get(name) if isinstance(node.func, ast.Name) else None
        if isinstance(target, (_Function, _Class)):  # another module's (imported)
            return self.call_target(target, args, keywords, when, depth, node)
        if name == "getattr" and len(args) >= 2 and isinstance(args[1], Value) and \
                isinstance(args[0], _DEFINING):
            found = _attribute(args[0], args[1].literal or "")
            return found if found is not None else unknown(_source(node))
        if name.rsplit(".", 1)[-1] == "load_python_launch_file_as_module" and args and \
                isinstance(args[0], Value):
            found = self.entered(self.modules.at(args[0], self.path), depth)
            return found if found is not None else unknown(_source(node))
        if name in self.functions and name != self.entry:
            function = self.functions[name]
            result = self.call_function(function, args, keywords, env, when, depth)
            return result if result is not None else unknown(_source(node))
        return self.construct(name, node, args, keywords, when, line)

    def method(self, node, method, args, keywords, env, when, depth):
        owner = self.eval(node.func.value, env, when, depth) if isinstance(node.func, ast.Attribute) \
            else None
        if isinstance(owner, _DEFINING):  # module.function(...), Class.static_method(...)
            target = _attribute(owner, method)
            if isinstance(target, (_Function, _Class)):
                return self.call_target(target, args, keywords, when, depth, node)
            return unknown(_source(node))
        if method == "find" and isinstance(owner, Value) and len(owner.parts) == 1 and \
                isinstance(owner.parts[0], tuple) and owner.parts[0][0] == "find":
            return owner  # FindPackageShare("p").find("p"): the package's share folder
        if (method, _callee(node.func.value)) in (("get", "os.environ"), ("getenv", "os")):
            name, default = (args + [None, None])[:2]  # os.environ.get / os.getenv(NAME, DEFAULT)
            default = keywords.get("default", default)
            if isinstance(name, Value) and name.literal:
                return Value((("env", name.literal,
                               default if isinstance(default, Value) else None),), _source(node))
            return unknown(_source(node))
        if method in ("add_action", "add_entity", "append") and args:
            if isinstance(owner, list):
                owner.append(args[0])
                self.built(owner)
            return None
        if method == "extend" and args and isinstance(owner, list) and isinstance(args[0], list):
            owner.extend(args[0])
            self.built(owner)
            return None
        if method == "items" and isinstance(owner, dict):
            return [[literal(k), v] for k, v in owner.items()]
        if method in ("perform", "lower", "strip", "__str__") and isinstance(owner, Value):
            return owner
        if method == "perform_substitution" and args:
            return args[0]
        if method == "join" and isinstance(owner, Value) and owner.literal is not None and args \
                and isinstance(args[0], list):
            separator, parts = literal(owner.literal), []
            for index, item in enumerate(args[0]):
                if index:
                    parts.append(separator)
                parts.append(item if isinstance(item, Value) else unknown("?"))
            return concat(parts)
        if method == "format" and isinstance(owner, Value) and owner.literal is not None and \
                owner.literal.count("{") == owner.literal.count("{}") == \
                owner.literal.count("}") == len(args) and not keywords:
            pieces, parts = owner.literal.split("{}"), []  # "{}:=".format(key)
            for index, piece in enumerate(pieces):
                parts.append(literal(piece))
                if index < len(args):
                    parts.append(args[index] if isinstance(args[index], Value) else unknown("?"))
            return concat(parts)
        if method == "join" and _callee(node.func.value) == "os.path":
            return _joined([a if isinstance(a, Value) else unknown("?") for a in args])
        if method == "read" and isinstance(owner, _Opened):  # open(path).read(): the text as it is
            return owner
        if isinstance(owner, _Opened) and method in _REWRITES:  # the text read, rewritten
            old = args[0] if method == "replace" and args else None
            return owner.rewritten(old.literal if isinstance(old, Value) else None)
        if method in ("sub", "subn") and _callee(node.func.value) == "re" and len(args) > 2 \
                and isinstance(args[2], _Opened):  # re.sub(pattern, new, text)
            return args[2].rewritten(None)
        if method == "parse" and args and isinstance(args[0], _Opened):  # xacro.parse(open(path))
            return _Parsed(args[0].path)
        if method == "process_doc" and args and isinstance(args[0], _Parsed):  # xacro.process_doc
            mappings = keywords.get("mappings")
            self.acts.append(_Act("description", when, self.line(node), file=args[0].path,
                                  args=_pairs(mappings), xacro=True, complete=_read_all(mappings)))
            return None
        if method == "process_file" and args and isinstance(args[0], Value):  # xacro.process_file
            mappings = keywords.get("mappings")
            self.acts.append(_Act("description", when, self.line(node), file=args[0],
                                  args=_pairs(mappings), xacro=True, complete=_read_all(mappings)))
            return unknown(_source(node))
        if method in ("robot_description", "robot_description_semantic") and isinstance(owner, _Builder):
            path = keywords.get("file_path") or (args[0] if args else None)
            if isinstance(path, Value):
                mappings = keywords.get("mappings")
                self.acts.append(_Act("description", when, self.line(node),
                                      file=_in_package(owner.package, path),
                                      args=_pairs(mappings), xacro=True,
                                      complete=_read_all(mappings)))
            return owner
        if isinstance(owner, _Builder):
            if method == "trajectory_execution":
                path = keywords.get("file_path") or (args[0] if args else None)
                if isinstance(path, Value):
                    self.acts.append(_Act("params", when, self.line(node),
                                          path=_in_package(owner.package, path), substitute=False))
            return owner
        if method in ("to_moveit_configs", "to_dict"):
            return owner if isinstance(owner, _Builder) else unknown(_source(node))
        return _NOT_HANDLED

    def construct(self, name: str, node, args, keywords, when, line):
        short = name.rsplit(".", 1)[-1]
        if short == "LaunchDescription":
            actions = args[0] if args and isinstance(args[0], list) else []
            _scope_remaps(_acts_in(actions))  # a SetRemap holds for what follows it
            return actions
        if short == "LaunchConfiguration":
            key = keywords.get("variable_name") or (args[0] if args else None)
            if isinstance(key, Value) and key.literal:
                default = keywords.get("default")
                return Value((("arg", key.literal, default if isinstance(default, Value) else None),),
                             _source(node))
            return unknown(_source(node))
        if short in _SHARE:
            package = keywords.get("package") or keywords.get("package_name") or (args[0] if args else None)
            if isinstance(package, Value) and (package.literal or _named_package(package)):
                return Value((("find", package.literal or package),), _source(node))
            return unknown(_source(node))
        if short in ("PathJoinSubstitution",):
            return _joined(_flat(args[0] if args else []))
        if short in ("PathSubstitution", "Path", "str", "TextSubstitution", "ParameterValue"):
            value = keywords.get("text") if short == "TextSubstitution" else \
                (args[0] if args else keywords.get("value"))
            if isinstance(value, list):
                return concat([v if isinstance(v, Value) else unknown("?") for v in value])
            return value if isinstance(value, Value) else unknown(_source(node))
        if short == "FindExecutable":
            executable = keywords.get("name") or (args[0] if args else None)
            return executable if isinstance(executable, Value) else unknown(_source(node))
        if short == "EnvironmentVariable":
            variable = keywords.get("name") or (args[0] if args else None)
            if isinstance(variable, Value) and variable.literal:
                default = keywords.get("default_value")
                return Value((("env", variable.literal, default if isinstance(default, Value) else None),),
                             _source(node))
            return unknown(_source(node))
        if short == "Command":
            command = args[0] if args else keywords.get("command")
            value = concat(_flat(command)) if isinstance(command, list) else command
            if not isinstance(value, Value):
                return unknown(_source(node))
            if "xacro" in value.text or any(isinstance(p, str) and "xacro" in p for p in value.parts):
                self.acts.append(_Act("description", when, line, command=value))
            return Value((("command", value),), _source(node))
        if short == "PythonExpression":
            inner = args[0] if args else None
            reads = concat(_flat(inner)) if isinstance(inner, list) else inner
            return Value((("unknown", _source(node)),) + (reads.parts if isinstance(reads, Value) else ()),
                         _source(node))
        if short in ("IfCondition", "UnlessCondition"):
            value = args[0] if args else keywords.get("predicate_expression")
            value = concat(_flat(value)) if isinstance(value, list) else value
            kind = "if" if short == "IfCondition" else "unless"
            if isinstance(value, Value) and any(isinstance(p, tuple) and p[0] == "unknown" for p in value.parts):
                return Condition("unknown", value, _source(node))
            return Condition(kind, value if isinstance(value, Value) else unknown("?"), _source(node))
        if short in ("LaunchConfigurationEquals", "LaunchConfigurationNotEquals"):
            key, expected = (args + [None, None])[:2]
            expected = keywords.get("expected_value", expected)
            if isinstance(key, Value) and key.literal and isinstance(expected, Value):
                kind = "equals" if short.endswith("Equals") and "Not" not in short else "differs"
                return Condition(kind, Value((("arg", key.literal, None),), key.literal), _source(node),
                                 expected)
            return Condition("unknown", literal(""), _source(node))
        if short == "DeclareLaunchArgument":
            arg = keywords.get("name") or (args[0] if args else None)
            if isinstance(arg, Value) and arg.literal:
                default = keywords.get("default_value", args[1] if len(args) > 1 else None)
                if isinstance(default, list):
                    default = concat(_flat(default))
                choices = keywords.get("choices")
                if default is None and isinstance(choices, list) and choices and \
                        isinstance(choices[0], Value) and choices[0].literal is not None:
                    # no default, but the values it may take: the robot is built with the
                    # first (UR's ur_type), as a user must choose one
                    default = literal(choices[0].literal)
                act = _Act("arg", when, line, name=arg.literal,
                           default=default if isinstance(default, Value) else None, fixed=False)
                self.acts.append(act)
                return act
            return None
        if short == "SetLaunchConfiguration":
            arg = keywords.get("name") or (args[0] if args else None)
            value = keywords.get("value", args[1] if len(args) > 1 else None)
            if isinstance(arg, Value) and arg.literal:
                act = _Act("arg", when, line, name=arg.literal,
                           default=value if isinstance(value, Value) else unknown("?"), fixed=True)
                self.acts.append(act)
                return act
            return None
        if short in ("Node", "ComposableNodeContainer", "LifecycleNode"):
            return self.node(node, keywords, when, line)
        if short == "ExecuteProcess":
            command = keywords.get("cmd") or (args[0] if args else None)
            words = [v if isinstance(v, Value) else unknown("?") for v in _flat(command)] \
                if isinstance(command, list) else []
            joined = []
            for index, word in enumerate(words):
                joined += [literal(" "), word] if index else [word]
            act = _Act("start", when, line, package=literal(""),
                       executable=concat(joined) if joined else unknown("?"), arguments=(), files=())
            self.acts.append(act)
            _add_condition(act, keywords.get("condition"))
            built = _xacro_words(words)
            if built:  # cmd=["xacro", path, "|", "ros2", "run", "gazebo_ros", "spawn_entity.py", ...]
                described = _Act("description", when, line, command=concat(built))
                self.acts.append(described)
                _add_condition(described, keywords.get("condition"))
            return act
        if short == "IncludeLaunchDescription":
            source = args[0] if args else keywords.get("launch_description_source")
            path = source.fields.get("path") if isinstance(source, _Act) else \
                (source if isinstance(source, Value) else None)
            arguments = keywords.get("launch_arguments")
            act = _Act("include", when, line, path=path if isinstance(path, Value) else unknown("?"),
                       args=_pairs(arguments))
            self.acts.append(act)
            _add_condition(act, keywords.get("condition"))
            return act
        if short in _SOURCES:
            path = args[0] if args else keywords.get("launch_file_path")
            if isinstance(path, list):
                path = concat(_flat(path))
            return _Act("source", (), line, path=path)
        if short in ("GroupAction", "TimerAction"):
            children = _acts_in(keywords.get("actions", args[0] if args and short == "GroupAction"
                                              else None))
            group = _Act("group", when, line, children=children)
            _add_group_condition(children, keywords.get("condition"), len(when))
            _scope_remaps(children)
            return group
        if short == "SetRemap":
            source, target = keywords.get("src", args[0] if args else None), \
                keywords.get("dst", args[1] if len(args) > 1 else None)
            act = _Act("remap", when, line, source=source, target=target)
            _add_condition(act, keywords.get("condition"))
            return act
        if short in ("RegisterEventHandler", "OnProcessExit", "OnProcessStart", "OnExecutionComplete"):
            return _Act("group", when, line)
        if short == "ParameterFile":
            path = keywords.get("param_file") or (args[0] if args else None)
            substitute = keywords.get("allow_substs")
            return _ParamFile(path if isinstance(path, Value) else unknown("?"),
                              isinstance(substitute, Value) and substitute.literal == "true")
        if short == "MoveItConfigsBuilder":
            package = keywords.get("package_name")
            robot = args[0] if args else keywords.get("robot_name")
            if not isinstance(package, Value) and isinstance(robot, Value):
                package = concat([robot, literal("_moveit_config")])
            return _Builder(package.literal or _named_package(package)
                            if isinstance(package, Value) else None)
        if short in ("open",) and args and isinstance(args[0], Value):
            return _Opened(args[0])
        if short == "Template" and args and isinstance(args[0], _Opened):  # string.Template(text)
            return args[0].rewritten(None)
        return unknown(_source(node))

    def node(self, node, keywords, when, line):
        package = keywords.get("package")
        executable = keywords.get("executable") or keywords.get("node_executable")
        arguments = [v if isinstance(v, Value) else unknown("?")
                     for v in _flat(keywords.get("arguments") or [])]
        files, given = [], []  # given: parameter values, for the descriptions they hold
        for entry in _flat(keywords.get("parameters") or []):
            if isinstance(entry, (Value, dict)):
                given.append(entry)
            if isinstance(entry, _ParamFile):
                files.append(ParamFile(entry.path, entry.substitute, (), line))
            elif isinstance(entry, Value) and not any(isinstance(p, tuple) and p[0] == "command"
                                                      for p in entry.parts) \
                    and not all(isinstance(p, tuple) and p[0] == "unknown" for p in entry.parts):
                files.append(ParamFile(entry, False, (), line))
            elif isinstance(entry, dict):
                for value in entry.values():
                    if isinstance(value, _Opened):
                        self.acts.append(_Act("description", when, line, file=value.path, args=(),
                                              replaced=value.replaced))
        pairs = keywords.get("remappings")  # [(from, to), ...]: each a list once read
        remaps = tuple(Remap(pair[0], pair[1], (), line) for pair in
                       (pairs if isinstance(pairs, list) else []) if isinstance(pair, list)
                       and len(pair) == 2 and all(isinstance(name, Value) for name in pair))
        act = _Act("start", when, line, package=package if isinstance(package, Value) else unknown("?"),
                   executable=executable if isinstance(executable, Value) else unknown("?"),
                   arguments=tuple(arguments), files=tuple(files), remaps=remaps,
                   given=tuple(given))
        self.acts.append(act)
        _add_condition(act, keywords.get("condition"))
        return act

    # --- conversion -----------------------------------------------------------------------

    def convert(self, act: _Act):
        when, fields = tuple(act.when), act.fields
        if act.kind == "arg":
            return Arg(fields["name"], fields["default"], fields["fixed"], when, act.line)
        if act.kind == "include":
            return Include(fields["path"], fields["args"], when, act.line,
                           remaps=fields.get("remaps", ()))
        if act.kind == "start":
            files = tuple(ParamFile(f.path, f.substitute, when, f.line) for f in fields["files"])
            return Start(fields["package"], fields["executable"], fields["arguments"], files, when,
                         act.line, fields.get("remaps", ()))
        if act.kind == "description":
            published = fields.get("published")
            return Description(fields.get("command"), fields.get("file"), fields.get("args", ()),
                               when, act.line, xacro=fields.get("xacro", False),
                               complete=fields.get("complete", True),
                               replaced=fields.get("replaced", ()),
                               published=tuple(published) if published is not None else None)
        if act.kind == "params" and isinstance(fields.get("path"), Value):
            return ParamFile(fields["path"], fields["substitute"], when, act.line)
        return None


_NOT_HANDLED = object()


class _Module:
    """A module of the repository a launch file imports, read, never run: what its top level
    defines and assigns (``env``, its functions' globals)."""

    def __init__(self, path: Path, env: dict):
        self.path, self.env = path, env


class _Function:
    """A function another module defines; ``bound``: what it is given first (a class
    method's class, an instance's method's instance)."""

    def __init__(self, node, module: _Module, bound=None, kind: str = ""):
        self.node, self.module, self.bound, self.kind = node, module, bound, kind


class _Class:
    """A class another module defines (a launch "mixin" of static methods): its functions."""

    def __init__(self, name: str, attributes: dict):
        self.name, self.attributes = name, attributes


class _Instance(Value):
    """An instance of such a class made in the launch file (an unknown value as text): the
    attributes its ``__init__`` and the launch file set (crane_plus's
    ``RobotDescriptionLoader().load()``); compared and hashed as its Value."""

    of: _Class | None
    attributes: dict

    __slots__ = ("of", "attributes")
    _compared = ("parts", "text")

    def __init__(self, parts: tuple, text: str, of: _Class | None = None,
                 attributes: dict = NEW) -> None:
        super().__init__(parts, text)
        set_field = object.__setattr__
        set_field(self, "of", of)
        set_field(self, "attributes", {} if attributes is NEW else attributes)


_DEFINING = (_Module, _Class, _Instance)


def _class(node: ast.ClassDef, module: _Module) -> _Class:
    """The functions of a class, each as its decorator makes it (``staticmethod``,
    ``classmethod``); its bases are not read."""
    found = _Class(node.name, {})
    for statement in node.body:
        if isinstance(statement, (ast.FunctionDef, ast.AsyncFunctionDef)):
            decorators = {_callee(d) for d in statement.decorator_list}
            kind = "static" if "staticmethod" in decorators else \
                "class" if "classmethod" in decorators else ""
            found.attributes[statement.name] = _Function(statement, module, kind=kind)
    return found


def _attribute(owner, name: str):
    """What ``owner.name`` is: a module's global, a class's function (a class method given its
    class), an instance's method given the instance; None when not read."""
    if isinstance(owner, _Module):
        return owner.env.get(name)
    if isinstance(owner, _Instance) and name in owner.attributes:
        return owner.attributes[name]
    of = owner.of if isinstance(owner, _Instance) else owner
    function = of.attributes.get(name) if of is not None else None
    if function is None:
        return None
    if function.kind == "class":
        return _Function(function.node, function.module, of)
    if function.kind == "" and isinstance(owner, _Instance):
        return _Function(function.node, function.module, owner)
    return function


class _Partial(dict):
    """A dict some of whose entries were not read (a key a function computes, ``**other``)."""


class _ParamFile:
    def __init__(self, path: Value, substitute: bool):
        self.path, self.substitute = path, substitute


class _Builder:
    """MoveItConfigsBuilder: the MoveIt config package its file paths are relative to (its
    name, or the Value naming it when a launch argument does: :func:`_named_package`)."""

    def __init__(self, package: str | Value | None):
        self.package = package


class _Opened:
    """A file the launch file reads into robot_description (Python's open on a path), as it is
    or with text replaced in it first: ``replaced``, the texts replaced (None for one not known
    without running the launch file: ``str.replace`` of a variable, ``format``, a
    ``string.Template``'s substitution, ``re.sub``)."""

    def __init__(self, path: Value, replaced: tuple = ()):
        self.path, self.replaced = path, replaced

    def rewritten(self, old: str | None) -> _Opened:
        return _Opened(self.path, self.replaced + (old,))


# methods of the text read that rewrite it (a Template's substitute: at Template(text))
_REWRITES = ("replace", "format", "format_map", "substitute", "safe_substitute")


class _Parsed:
    """A file ``xacro.parse`` read (opened by Python), which ``xacro.process_doc`` expands."""

    def __init__(self, path: Value):
        self.path = path


def _in_package(package: str | Value | None, path: Value) -> Value:
    if package is None or (path.literal or "").startswith("/"):
        return path
    return concat([Value((("find", package),), getattr(package, "text", package)), literal("/"),
                   path])


def _named_package(package: Value) -> Value | None:
    """``package`` when it is a package's name a launch argument gives (whole or in part:
    ``LaunchConfiguration("description_package")``, ``f"kuka_{family}_support"``), resolved in
    each configuration (:func:`~urdftool.description.launch_configs.resolve`); None when it holds
    a value not read."""
    if not package.parts or any(isinstance(p, tuple) and p[0] in ("unknown", "command")
                                for p in package.parts):
        return None
    return package


_SHELL_OPERATORS = ("|", "||", "&&", ";", ">", ">>", "<", "&")


def _xacro_words(words: list) -> list:
    """The words of an ``ExecuteProcess`` command line that run xacro, joined by spaces up to
    the first shell operator written as a word (``xacro stand.urdf | ros2 run gazebo_ros
    spawn_entity.py -stdin``: what xacro expands is what the rest reads); [] when its program
    is not xacro."""
    if not words or (words[0].literal or "").strip("'\"").rsplit("/", 1)[-1] not in ("xacro", "xacro.py"):
        return []
    built = []
    for word in words:
        if word.literal in _SHELL_OPERATORS:
            break
        built += [literal(" "), word] if built else [word]
    return built


def _described_where_used(acts: list) -> None:
    """A robot description a ``Command`` builds is built when an action given it runs (the
    substitution is evaluated then, not where it is assigned): when every action holding it
    runs under the same conditions, and under the description's own, the description has
    them. dg5f_right_moveit.launch.py builds the mock hand's xacro for a robot_state_publisher
    under ``IfCondition(use_mock)`` and the real hand's for one under ``UnlessCondition``,
    each beside the controller manager with its controllers file: one description is never
    built with the other's controllers. Held by actions of different conditions, or by none
    read, the description keeps its own."""
    for act in acts:
        command = act.fields.get("command") if act.kind == "description" else None
        if command is None:
            continue
        users = [other for other in acts if other is not act and other.kind != "description"
                 and _holds(other.fields, command, 0)]
        conditions = _common_when(users, act.when)
        if conditions is not None:
            act.when = conditions
            continue
        # given to MoveIt or RViz unconditionally, it may still reach a controller manager only
        # under a condition: the mock hand's xacro given to move_group and rviz2 and to a
        # robot_state_publisher under IfCondition(use_mock), which publishes it to the manager
        act.fields["published"] = _common_when(
            [user for user in users if user.kind == "start"
             and (user.fields["executable"].literal or "") in _PUBLISHERS], act.when)


_PUBLISHERS = ("robot_state_publisher", "ros2_control_node")  # what hands a controller manager
# its robot: the topic robot_description it subscribes to, or its own parameter


def _common_when(users: list, when: list) -> list | None:
    """The conditions every one of ``users`` runs under, when they are the same for all and
    more than ``when`` (of which they are an extension); else None."""
    if not users or any(user.when != users[0].when for user in users):
        return None
    if users[0].when[:len(when)] == when and len(users[0].when) > len(when):
        return list(users[0].when)
    return None


def _holds(value, command, depth: int) -> bool:
    """Whether ``value`` (an action's fields: Values, lists, tuples, dicts) holds the
    ``Command`` value ``command`` itself, as one of its parts."""
    if depth > MAX_DEPTH:
        return False
    if isinstance(value, Value):
        return any(isinstance(part, tuple) and len(part) > 1 and part[0] == "command"
                   and (part[1] is command or _holds(part[1], command, depth + 1))
                   for part in value.parts)
    if isinstance(value, dict):
        value = list(value.values())
    if isinstance(value, (list, tuple)):
        return any(_holds(item, command, depth + 1) for item in value)
    fields = getattr(value, "fields", None)  # a parameter file, a nested action
    return isinstance(fields, dict) and _holds(fields, command, depth + 1)


def _add_condition(act: _Act, condition) -> None:
    if isinstance(condition, Condition):
        act.when.append(condition)


def _add_group_condition(acts: list, condition, at: int) -> None:
    """Give a group's ``condition`` to ``acts`` (its actions) and to the actions of the groups
    among them, nested as deep as they are: each runs only when every enclosing group's holds.
    It goes before those of the groups inside it and the action's own, after the Python ``if``
    tests enclosing the group (``at`` of them), as ``<group if>`` nested in XML reads; not to a
    ``SetRemap``, whose condition is its own (its group's are the nodes')."""
    if not isinstance(condition, Condition):
        return
    for act in acts:
        if act.kind != "remap":
            act.when.insert(min(at, len(act.when)), condition)
        _add_group_condition(act.fields.get("children", ()) if act.kind == "group" else (),
                             condition, at)


def _scope_remaps(acts: list) -> None:
    """Give the ``SetRemap`` among ``acts`` (the actions of one scope, in order) to the nodes
    and includes after it, inside the groups after it too, before their own remaps (launch_ros
    puts the scope's remaps first); the scope's ends with it."""
    remaps: list = []
    for act in acts:
        if act.kind == "remap":
            source, target = act.fields["source"], act.fields["target"]
            if isinstance(source, Value) and isinstance(target, Value):
                remaps.append(Remap(source, target, tuple(act.when), act.line))
        elif remaps:
            _add_remaps(act, tuple(remaps))


def _add_remaps(act: _Act, remaps: tuple) -> None:
    if act.kind in ("start", "include"):
        act.fields["remaps"] = remaps + tuple(act.fields.get("remaps", ()))
    for child in act.fields.get("children", ()) if act.kind == "group" else ():
        _add_remaps(child, remaps)


def _acts_in(value) -> list:
    return [item for item in _flat(value) if isinstance(item, _Act)] if isinstance(value, list) else \
        ([value] if isinstance(value, _Act) else [])


def _outcome(op, left, right) -> bool | None:
    """Whether ``left OP right`` holds, for literal values (``right`` a list of them for
    ``in``); None when a side is not known."""
    if not (isinstance(left, Value) and left.literal is not None):
        return None
    if isinstance(op, (ast.Eq, ast.NotEq)):
        if not (isinstance(right, Value) and right.literal is not None):
            return None
        return (left.literal == right.literal) is isinstance(op, ast.Eq)
    if not (isinstance(right, list) and right and
            all(isinstance(item, Value) and item.literal is not None for item in right)):
        return None
    return (left.literal in [item.literal for item in right]) is isinstance(op, ast.In)


def _either(found, otherwise, test: Condition):
    """What a function returns from the two ways an ``if`` goes, its test not known: the same
    text either way is that text; two texts are unknown (naming the test), never the first
    one taken for both (tiago's ``get_tiago_hw_suffix``: '_no-arm' whatever the arm); other
    values (lists of actions, whose actions carry their conditions) the first found."""
    if found is None or otherwise is None:
        return found if found is not None else otherwise
    if type(found) is Value and type(otherwise) is Value and found != otherwise:
        return unknown(f"{found.text} if {test.text} else {otherwise.text}")
    return found


def _negated(condition: Condition) -> Condition:
    opposite = {"if": "unless", "unless": "if", "equals": "differs", "differs": "equals"}
    if condition.kind in opposite:
        return Condition(opposite[condition.kind], condition.value, f"not ({condition.text})",
                         condition.other)
    return Condition("unknown", condition.value, f"not ({condition.text})")


def _pairs(value) -> tuple:
    """Launch arguments given to an include (a dict, ``dict.items()``, a list of pairs)."""
    if isinstance(value, dict):
        value = [[literal(k), v] for k, v in value.items()]
    pairs = []
    for item in value if isinstance(value, list) else []:
        if isinstance(item, list) and len(item) == 2 and isinstance(item[0], Value) \
                and item[0].literal:
            second = item[1]
            if isinstance(second, list):
                second = concat(_flat(second))
            pairs.append((item[0].literal, second if isinstance(second, Value) else unknown("?")))
    return tuple(pairs)


def _read_all(mappings) -> bool:
    """Whether every xacro argument a mapping gives was read: none given, or a dict (or list of
    pairs) whose every name is a constant."""
    if mappings is None:
        return True
    if isinstance(mappings, dict):
        return not isinstance(mappings, _Partial)
    return isinstance(mappings, list) and len(_pairs(mappings)) == len(mappings)


def _flat(value) -> list:
    """Items of nested lists, in order."""
    if not isinstance(value, list):
        return [value] if value is not None else []
    found = []
    for item in value:
        found.extend(_flat(item) if isinstance(item, list) else [item])
    return found


def _joined(values) -> Value:
    parts = []
    for index, value in enumerate(values):
        if index:
            parts.append(literal("/"))
        parts.append(value if isinstance(value, Value) else unknown("?"))
    return concat(parts)


def _values_in(value):
    if isinstance(value, Value):
        yield value
    elif isinstance(value, list):
        for item in value:
            yield from _values_in(item)


def _callee(node) -> str:
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        return f"{_callee(node.value)}.{node.attr}"
    return ""


def _calls(tree):
    """The calls in ``tree``, every node looked at once, in no particular order (``ast``'s
    walk, without its three generators a node)."""
    pending, syntax, call = [tree], ast.AST, ast.Call
    while pending:
        node = pending.pop()
        if isinstance(node, call):
            yield node
        for name in node._fields:
            value = getattr(node, name, None)
            if isinstance(value, list):
                pending.extend([item for item in value if isinstance(item, syntax)])
            elif isinstance(value, syntax):
                pending.append(value)


def _source(node) -> str:
    text = _plain_source(node, 0)
    if text is None:
        try:
            text = ast.unparse(node)
        except Exception:  # noqa: BLE001 - only for messages
            return "?"
    return text if len(text) <= 200 else text[:197] + "..."


def _plain_source(node, depth: int) -> str | None:
    """``ast.unparse(node)`` of the calls a launch file writes most (``LaunchConfiguration(
    'x')``, ``FindPackageShare('p')``: names, dotted names, calls, lists, keywords, integers
    and texts of printable characters without quotes or backslashes), each as unparse writes
    it; None for any other node (unparse then: an _Unparser and a visit a node cost about
    100,000 instructions a call)."""
    kind = type(node)
    if kind is ast.Name:
        return node.id
    if depth > 8:
        return None
    if kind is ast.Constant:
        value = node.value
        if node.kind is not None:  # (u'x')
            return None
        if type(value) is str:
            return f"'{value}'" if value.isprintable() and "'" not in value and \
                '"' not in value and "\\" not in value else None
        return repr(value) if type(value) is int and 0 <= value < 1 << 64 else None
    if kind is ast.Attribute:
        if type(node.value) not in (ast.Name, ast.Attribute):
            return None
        owner = _plain_source(node.value, depth + 1)
        return None if owner is None else f"{owner}.{node.attr}"
    if kind is ast.Call:
        if type(node.func) not in (ast.Name, ast.Attribute):
            return None
        words = [_plain_source(node.func, depth + 1)]
        words += [_plain_source(argument, depth + 1) for argument in node.args]
        for keyword in node.keywords:
            if keyword.arg is None:
                return None
            value = _plain_source(keyword.value, depth + 1)
            words.append(None if value is None else f"{keyword.arg}={value}")
        return None if None in words else f"{words[0]}({', '.join(words[1:])})"
    if kind is ast.List:
        items = [_plain_source(item, depth + 1) for item in node.elts]
        return None if None in items else f"[{', '.join(items)}]"
    return None
