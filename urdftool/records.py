"""Plain records: classes of named fields (``__slots__``) with a hand-written ``__init__``,
compared, hashed, shown, copied and pickled as :mod:`dataclasses` does a dataclass of the same
fields (:class:`Record`: ``eq=True``; :class:`Frozen`: ``frozen=True``), without dataclasses'
making of each class on every start (each method's text built and run, each field's
annotation asked, the class's attributes set: r2d2's check made 82 of them, 36 M
instructions).

A record's fields are its ``__slots__`` (those of its record bases first), in order;
``_compared`` and ``_shown`` name the fields its equality and hash and its ``repr`` use when
not all of them (a dataclass's ``field(compare=False)``, ``field(repr=False)``), ``_made``
those its ``__init__`` does not take (``field(init=False)``). A default made anew for each
record (dataclasses' ``default_factory``) is written ``NEW`` in ``__init__``'s parameters.
:func:`replace` and :func:`astuple` are dataclasses' functions of the same names.
"""

from __future__ import annotations

from _thread import get_ident
from operator import attrgetter


def _values(names: tuple):
    """A function of a record giving the tuple of its fields ``names``."""
    if len(names) > 1:
        return attrgetter(*names)
    if names:
        one = attrgetter(names[0])
        return lambda record: (one(record),)
    return lambda record: ()


_SHOWING: set = set()  # (id, thread) of the records being shown (a record holding itself: ...)


class _Fields:
    """What records share: equality of the tuples of their compared fields within one class,
    ``repr``, pickling and copying by their fields (``__init__`` not run)."""

    __slots__ = ()
    # (each class's own, set as it is made: its fields, the fields its equality and hash
    # compare and its repr shows, all unless the class names them, and those its __init__
    # does not take)
    _fields: tuple = ()
    _shown: tuple = ()
    _made: tuple = ()
    _setters: tuple = ()

    def __init_subclass__(cls, **kwargs) -> None:
        super().__init_subclass__(**kwargs)
        own = cls.__dict__
        cls._fields = fields = tuple(name for kind in reversed(cls.__mro__) for name in
                                     kind.__dict__.get("__slots__", ()) if name[:2] != "__")
        cls._key = staticmethod(_values(own.get("_compared", fields)))
        cls._shown = own.get("_shown", fields)
        # each field's slot descriptor's setter, in the order of the fields: setting a field
        # through it costs half of object.__setattr__, which looks the name up first (a frozen
        # record made many times sets its fields by these: a finding and its location)
        cls._setters = tuple(getattr(cls, name).__set__ for name in fields)

    def __eq__(self, other):
        if other.__class__ is self.__class__:
            return self._key(self) == other._key(other)
        return NotImplemented

    __hash__ = None

    def __repr__(self) -> str:
        key = id(self), get_ident()
        if key in _SHOWING:
            return "..."
        _SHOWING.add(key)
        try:
            return f"{self.__class__.__qualname__}(" + ", ".join(
                f"{name}={getattr(self, name)!r}" for name in self._shown) + ")"
        finally:
            _SHOWING.discard(key)

    def __reduce__(self):
        return _rebuilt, (self.__class__, tuple(getattr(self, name) for name in self._fields)), \
            getattr(self, "__dict__", None) or None


class Record(_Fields):
    """A record of fields that may be set again, unhashable; it may be given other attributes
    (a dataclass's ``__dict__``: a rule's parsed source kept on the file it read,
    ``functools.cached_property``), and be weakly referenced, as a dataclass's instance."""

    __slots__ = ("__dict__", "__weakref__")


class Frozen(_Fields):
    """A record whose fields are set once, by ``__init__`` (``object.__setattr__``, or the
    fields' setters ``_setters`` in a record made many times): assigning or deleting an
    attribute raises dataclasses' FrozenInstanceError; hashed as the tuple of its compared
    fields. Weakly referenced as a dataclass's instance is."""

    __slots__ = ("__weakref__",)

    def __setattr__(self, name: str, value) -> None:
        from dataclasses import FrozenInstanceError

        raise FrozenInstanceError(f"cannot assign to field {name!r}")

    def __delattr__(self, name: str) -> None:
        from dataclasses import FrozenInstanceError

        raise FrozenInstanceError(f"cannot delete field {name!r}")

    def __hash__(self) -> int:
        return hash(self._key(self))


def _rebuilt(cls, values: tuple):
    """A record of ``cls`` with its fields set to ``values``, its ``__init__`` not run (as
    pickle and copy make a dataclass)."""
    record = cls.__new__(cls)
    for name, value in zip(cls._fields, values):
        object.__setattr__(record, name, value)
    return record


def replace(record, **changes):
    """A new record of ``record``'s class, made by its ``__init__`` from its fields and
    ``changes`` (dataclasses.replace)."""
    made = record._made
    return record.__class__(**{name: getattr(record, name) for name in record._fields
                               if name not in made} | changes)


def astuple(record) -> tuple:
    """The values of ``record``'s fields, copied as ``dataclasses.astuple`` copies them."""
    import copy

    return tuple(copy.deepcopy(getattr(record, name)) for name in record._fields)


class _New:
    def __repr__(self) -> str:
        return "NEW"


NEW = _New()  # a field's default: a new value made by __init__ (dataclasses' default_factory)
