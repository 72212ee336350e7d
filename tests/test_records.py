"""Records behave as the dataclasses they replaced: equality, hash, frozen fields, repr,
pickling, copying, replace and astuple, against a dataclass of the same fields; and every
record class of urdftool takes its fields in order (as a dataclass's ``__init__``) and sets
each."""

from __future__ import annotations

import copy
import dataclasses
import importlib
import inspect
import pickle
import pkgutil

import pytest

import urdftool
from urdftool import records
from urdftool.records import NEW, Frozen, Record


class Point(Frozen):
    """A frozen record."""

    __slots__ = ("x", "y", "label")
    _compared = ("x", "y")

    def __init__(self, x: float, y: float = 0.0, label: list = NEW) -> None:
        set_field = object.__setattr__
        set_field(self, "x", x)
        set_field(self, "y", y)
        set_field(self, "label", [] if label is NEW else label)


@dataclasses.dataclass(frozen=True)
class PointClass:
    """Point as a dataclass."""

    x: float
    y: float = 0.0
    label: list = dataclasses.field(default_factory=list, compare=False)


class Box(Record):
    """A mutable record with a field its repr leaves out and one its __init__ makes."""

    __slots__ = ("size", "note", "_seen")
    _shown = ("size",)
    _made = ("_seen",)

    def __init__(self, size: tuple, note: str | None = None) -> None:
        self.size = size
        self.note = note
        self._seen = {}


@dataclasses.dataclass
class BoxClass:
    """Box as a dataclass."""

    size: tuple
    note: str | None = dataclasses.field(default=None, repr=False)
    _seen: dict = dataclasses.field(default_factory=dict, init=False, repr=False)


class One(Frozen):
    """A record of one field."""

    __slots__ = ("value",)

    def __init__(self, value: float) -> None:
        object.__setattr__(self, "value", value)


@dataclasses.dataclass(frozen=True)
class OneClass:
    """One as a dataclass."""

    value: float


def test_equality_and_hash_are_the_dataclasses():
    nan = float("nan")
    for record, twin in ((Point(1.0, 2.0, ["a"]), PointClass(1.0, 2.0, ["a"])),
                         (Point(1.0, 2.0, ["b"]), PointClass(1.0, 2.0, ["b"])),
                         (Point(nan), PointClass(nan)), (One(nan), OneClass(nan)),
                         (One(3), OneClass(3))):
        assert hash(record) == hash(twin)
        assert (record == Point(1.0, 2.0)) == (twin == PointClass(1.0, 2.0))
        assert (record == record) == (twin == twin)  # (a NaN field: the same object)
    assert Point(1.0, 2.0, ["a"]) == Point(1.0, 2.0, ["b"])  # (label not compared)
    assert One(1) != OneClass(1) and One(1).__eq__(OneClass(1)) is NotImplemented
    assert Box((1,)) == Box((1,)) and Box((1,)) != Box((1,), "n")
    assert Box.__hash__ is None and BoxClass.__hash__ is None
    with pytest.raises(TypeError):
        hash(Box((1,)))


def test_a_frozen_record_refuses_assignment_and_deletion_as_a_dataclass():
    for record in (Point(1.0), PointClass(1.0)):
        with pytest.raises(dataclasses.FrozenInstanceError, match="cannot assign to field 'x'"):
            record.x = 2.0
        with pytest.raises(dataclasses.FrozenInstanceError, match="cannot assign to field 'z'"):
            record.z = 2.0
        with pytest.raises(dataclasses.FrozenInstanceError, match="cannot delete field 'y'"):
            del record.y
    box = Box((1,))
    box.size, box.other = (2,), "kept"  # (a mutable record takes other attributes too)
    assert box.size == (2,) and box.other == "kept"


def test_repr_is_the_dataclasses():
    assert repr(Point(1.0, 2.0, ["a"])) == repr(PointClass(1.0, 2.0, ["a"])).replace(
        "PointClass", "Point")
    assert repr(Box((1,), "n")) == repr(BoxClass((1,), "n")).replace("BoxClass", "Box")
    box, twin = Box(None), BoxClass(None)
    box.size, twin.size = box, twin
    assert repr(box) == "Box(size=...)" and repr(twin) == "BoxClass(size=...)"


def test_pickle_and_copy_keep_every_field_and_attribute_without_init():
    point = Point(1.0, 2.0, ["a"])
    box = Box((1,), "n")
    box._seen["k"] = 1
    box.extra = "kept"
    for made in (pickle.loads(pickle.dumps(point)), copy.copy(point), copy.deepcopy(point)):
        assert made == point and made.label == ["a"] and type(made) is Point
        with pytest.raises(dataclasses.FrozenInstanceError):
            made.x = 0
    for made in (pickle.loads(pickle.dumps(box)), copy.deepcopy(box)):
        assert made == box and made._seen == {"k": 1} and made.extra == "kept"


def test_a_record_is_weakly_referenced_as_a_dataclass_instance():
    import weakref

    for made in (Point(1.0), Box((1,)), One(2.0), PointClass(1.0), BoxClass((1,))):
        assert weakref.ref(made)() is made


def test_replace_and_astuple_are_the_dataclasses():
    point = Point(1.0, 2.0, ["a"])
    assert records.replace(point, y=3.0) == Point(1.0, 3.0)
    assert records.replace(point, y=3.0).label == ["a"]
    assert records.astuple(point) == dataclasses.astuple(PointClass(1.0, 2.0, ["a"]))
    assert records.astuple(point)[2] is not point.label  # (copied, as astuple copies)
    box = records.replace(Box((1,), "n"), note="m")
    assert (box.size, box.note, box._seen) == ((1,), "m", {})


def _record_classes() -> list[type]:
    found = {}
    for module in pkgutil.walk_packages(urdftool.__path__, "urdftool."):
        if module.name.endswith(("__main__", "pytest_plugin", ".records")):
            continue
        try:
            loaded = importlib.import_module(module.name)
        except ImportError:  # (an optional library absent)
            continue
        for value in vars(loaded).values():
            if isinstance(value, type) and issubclass(value, (Record, Frozen)) and \
                    value.__module__ == module.name:
                found[f"{value.__module__}.{value.__qualname__}"] = value
    return [found[name] for name in sorted(found)]


RECORDS = _record_classes()


def test_urdftools_records_are_found():
    assert len(RECORDS) >= 75  # (79 in session 15)


@pytest.mark.parametrize("cls", RECORDS, ids=lambda cls: f"{cls.__module__}.{cls.__name__}")
def test_a_record_takes_its_fields_in_order_and_sets_each(cls):
    """As a dataclass's ``__init__``: one parameter per field its __init__ takes, in the order
    of the fields; every field set once made; a frozen record refuses to change."""
    parameters = list(inspect.signature(cls.__init__).parameters)[1:]
    taken = [name for name in cls._fields if name not in cls._made]
    assert parameters == taken
    assert set(cls._made) <= set(cls._fields)
    marks = {name: f"<{name}>" for name in taken}
    if hasattr(cls, "__post_init__"):  # (it may convert or refuse the marks)
        try:
            made = cls(**marks)
        except Exception:
            made = records._rebuilt(cls, tuple(marks.get(name) for name in cls._fields))
    else:
        made = cls(**marks)
        assert [getattr(made, name) for name in taken] == list(marks.values())
    for name in cls._fields:
        assert hasattr(made, name)
    assert pickle.loads(pickle.dumps(made)) == made
    assert len(cls._setters) == len(cls._fields)
    for name, set_field in zip(cls._fields, cls._setters):  # (each field's own setter)
        set_field(made, f"[{name}]")
        assert getattr(made, name) == f"[{name}]"
    if issubclass(cls, Frozen):
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(made, cls._fields[0], None)
        assert not hasattr(made, "__dict__")
