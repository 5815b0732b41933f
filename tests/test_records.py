"""glslcheck/base/records.py: `@record` must give what `@dataclass` gave the classes that use it
(fields, defaults, factories, equality, hashing, frozenness, repr, pickling), since it replaced
it on the start-up path (importing dataclasses costs start-up time)."""

from __future__ import annotations

import dataclasses
import pickle

import pytest

from glslcheck.base.records import FrozenInstanceError, field, record, replace
from glslcheck.language import glsl_types as T


@record(frozen=True)
class Point:
    """A frozen record."""

    x: int
    y: int = 0
    tag: str = field(default="", compare=False, repr=False)


@record
class Bag:
    name: str
    items: list = field(default_factory=list)


@record(eq=False, slots=False)
class Ident:
    name: str

    def __repr__(self) -> str:
        return f"<{self.name}>"


@dataclasses.dataclass(frozen=True)
class DataPoint:
    x: int
    y: int = 0
    tag: str = dataclasses.field(default="", compare=False, repr=False)


def test_init_takes_the_fields_in_order_by_position_or_name_with_defaults():
    assert (Point(1).x, Point(1).y) == (1, 0)
    assert (Point(1, 2).y, Point(y=3, x=4).x) == (2, 4)
    with pytest.raises(TypeError):
        Point()
    with pytest.raises(TypeError):
        Point(1, 2, "t", 4)
    assert Point.__match_args__ == ("x", "y", "tag")


def test_replace_copies_with_the_given_fields_changed_as_dataclasses_replace():
    p = Point(1, 2, "t")
    q = replace(p, y=5)
    assert (q.x, q.y, q.tag) == (1, 5, "t") and (p.x, p.y) == (1, 2)
    d = dataclasses.replace(DataPoint(1, 2, "t"), y=5)
    assert (q.x, q.y, q.tag) == (d.x, d.y, d.tag)
    bag = Bag("a", [1])
    assert replace(bag, name="b").items is bag.items  # a shallow copy, as dataclasses.replace
    with pytest.raises(TypeError):
        replace(p, z=1)


def test_a_factory_default_is_made_fresh_for_each_instance():
    a, b = Bag("a"), Bag("b")
    a.items.append(1)
    assert b.items == [] and a.items == [1]
    assert Bag("c", [2]).items == [2]


def test_equality_and_hash_are_those_of_the_same_dataclass():
    assert Point(1, 2, "a") == Point(1, 2, "b")  # tag: compare=False
    assert Point(1, 2) != Point(2, 1) and Point(1) != DataPoint(1)
    assert hash(Point(1, 2, "a")) == hash(DataPoint(1, 2, "b")) == hash((1, 2))
    assert Bag("a") == Bag("a") and Bag("a") != Bag("b")
    with pytest.raises(TypeError):
        hash(Bag("a"))  # mutable with eq: unhashable, as a dataclass
    x = Ident("x")
    assert x != Ident("x") and x == x and hash(x) == object.__hash__(x)


def test_repr_matches_the_dataclass_repr_and_keeps_an_own_repr():
    assert repr(Point(1, 2, "t")) == repr(DataPoint(1, 2, "t")).replace("DataPoint", "Point")
    assert repr(Bag("a")) == "Bag(name='a', items=[])"
    assert repr(Ident("x")) == "<x>"


def test_frozen_fields_cannot_be_assigned_or_deleted():
    p = Point(1)
    with pytest.raises(FrozenInstanceError):
        p.x = 2
    with pytest.raises(FrozenInstanceError):
        del p.y
    assert isinstance(FrozenInstanceError(), AttributeError)
    b = Bag("a")
    b.name = "b"
    assert b.name == "b"


def test_slots_unless_asked_otherwise():
    assert Point.__slots__ == ("x", "y", "tag") and not hasattr(Point(1), "__dict__")
    with pytest.raises(AttributeError):
        Bag("a").other = 1
    ident = Ident("x")
    ident.other = 1  # slots=False keeps a __dict__
    assert ident.other == 1


def test_slots_the_class_declares_are_kept_and_are_not_fields():
    @record(frozen=True)
    class Spot:
        __slots__ = ("_note",)
        x: int
        y: int = 0

    spot = Spot(1)
    assert Spot.__slots__ == ("x", "y", "_note") and Spot._fields == ("x", "y")
    assert not hasattr(spot, "_note") and spot == Spot(1, 0) and repr(spot) == "Spot(x=1, y=0)"
    Spot.__dict__["_note"].__set__(spot, "n")
    assert spot._note == "n" and spot == Spot(1) and hash(spot) == hash(Spot(1))


def test_records_pickle_by_value():
    for value in (Point(1, 2, "t"), Bag("a", [1, 2]), T.VEC3, T.MAT2, T.ArrayType(T.FLOAT, 3)):
        assert pickle.loads(pickle.dumps(value)) == value
    assert pickle.loads(pickle.dumps(Point(1, 2, "t"))).tag == "t"


def test_a_field_without_default_after_one_with_a_default_is_an_error():
    with pytest.raises(TypeError, match="follows one with a default"):

        @record
        class Bad:
            a: int = 0
            b: int


def test_the_type_objects_keep_their_dataclass_semantics():
    assert T.vector("float", 3) is T.VEC3 and T.VectorType("float", 3) == T.VEC3
    assert hash(T.VectorType("float", 3)) == hash(T.VEC3) and T.VEC3 != T.IVEC3
    assert T.VoidType() == T.VOID
    s1 = T.StructType("S", (("a", T.FLOAT),))
    assert s1 != T.StructType("S", (("a", T.FLOAT),)) and s1 == s1  # nominal: by identity
    with pytest.raises(AttributeError):
        T.VEC3.n = 4


def test_the_precompiled_templates_are_the_lint_paths():
    """glslcheck/base/_init_code.py holds exactly the `__init__` templates `glslcheck lint` and
    `check` make (a new shape of record fails here until `python -m glslcheck.base.records` writes
    the file again), each compiled from its own text: the same code `init_code` compiles."""
    from glslcheck.base import _init_code, records

    assert sorted(_init_code.SOURCES) == records.lint_path_templates()
    for source, function in _init_code.SOURCES.items():
        env: dict = {}
        exec(source, {}, env)
        fresh, stored = env["__init__"].__code__, records.init_code(source)
        for part in (
            "co_code",
            "co_consts",
            "co_names",
            "co_varnames",
            "co_argcount",
            "co_kwonlyargcount",
            "co_name",
        ):
            assert getattr(stored, part) == getattr(fresh, part), (part, source)


def test_a_template_not_precompiled_is_compiled():
    from glslcheck.base import records

    code = records.init_code(
        "def __init__(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6, _f7, _f8, _f9, _f10):\n    pass"
    )
    assert code.co_argcount == 12 and code.co_name == "__init__"
