"""Record classes for the start-up path: `@record`, what `@dataclass` gives, made cheaply.

A record class is declared as for `@dataclass`: annotated fields in order, a default after the
annotation (`field(default_factory=list)` for a fresh value per instance, `field(repr=False,
compare=False)` to leave a field out of `__repr__` or `__eq__`). `@record` gives it
`__slots__`, an `__init__` taking the fields in order, `__repr__` (`Name(a=1, b='x')`),
`__eq__` between instances of the same class comparing the fields as one tuple, `__hash__` of
that tuple when frozen (a mutable record with `eq` is unhashable, an `eq=False` one compares
and hashes by identity) and `__match_args__`; a method the class defines itself is kept.
`frozen=True` makes assigning a field an error (a frozen record pickles by its fields).
Options: `frozen`, `eq`, `slots` (default True; False keeps a `__dict__`). A `__slots__` the
class declares holds extra slots that are not fields, kept after the fields'.

Why not `@dataclass`: it compiles the source text of six to nine methods for every class it
makes, and a one-file `glslcheck lint` makes dozens of record classes before it reads the file.
Here the methods are shared by every record class, and each `__init__` is a copy of one compiled
template per field count renamed to the class's fields (as frontend/syntax.py does for the AST's
nodes): no code is compiled per class. Importing dataclasses lazily would save nothing: every one
of those classes is on the lint path, and `import dataclasses` brings `inspect`, `ast`, `dis`
and `tokenize` with it.
"""

from __future__ import annotations

from functools import partial
from operator import attrgetter
from types import FunctionType, MemberDescriptorType

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any, dataclass_transform
else:

    def dataclass_transform(**_options):
        """`typing.dataclass_transform`, which only tells type checkers that a decorator or a
        metaclass makes dataclass-like classes (`record`, frontend/syntax.py's nodes): nothing
        to do at run time (and no import of typing)."""
        return lambda function: function


__all__ = [
    "record",
    "field",
    "field_names",
    "replace",
    "FrozenInstanceError",
    "tuple_getter",
    "dataclass_transform",
]

_MISSING = object()


class FrozenInstanceError(AttributeError):
    """A field of a frozen record was assigned or deleted (as dataclasses.FrozenInstanceError)."""


class _Field:
    __slots__ = ("default", "factory", "repr", "compare")

    def __init__(
        self, default: Any, factory: Callable[[], Any] | None, repr: bool, compare: bool
    ) -> None:
        self.default = default
        self.factory = factory
        self.repr = repr
        self.compare = compare


def field(
    *,
    default: Any = _MISSING,
    default_factory: Callable[[], Any] | None = None,
    repr: bool = True,
    compare: bool = True,
) -> Any:
    """A field's options, as `dataclasses.field` takes them (the subset glslcheck uses)."""
    if default is not _MISSING and default_factory is not None:
        raise ValueError("a field cannot have both a default and a default_factory")
    return _Field(default, default_factory, repr, compare)


class _Factory:
    """The default of a `default_factory` field: `__init__` calls `make` for each instance."""

    __slots__ = ("make",)

    def __init__(self, make: Callable[[], Any]) -> None:
        self.make = make

    def __repr__(self) -> str:
        return f"<factory {getattr(self.make, '__name__', self.make)}>"


_TEMPLATES: dict[tuple[int, bool, tuple[bool, ...]], Any] = {}


def _init_template(count: int, frozen: bool, factories: tuple[bool, ...]):
    """The code of an `__init__(self, _f0, ..., _f{count-1})` storing each argument (a
    `_Factory` default replaced by what it makes, for the fields that have one), compiled once
    per shape. A frozen record's fields are stored through `_set0`, `_set1`, ... (each the
    `__set__` of the field's slot: a third of the cost of `object.__setattr__`, which a frozen
    record's `__setattr__` leaves as the only other way; `glslcheck lint lab_shaders` makes
    13,000 `Location`s)."""
    key = (count, frozen, factories)
    code = _TEMPLATES.get(key)
    if code is None:
        params = "".join(f", _f{i}" for i in range(count))
        body = []
        for i, factory in enumerate(factories):
            value = f"_f{i}.make() if type(_f{i}) is _Factory else _f{i}" if factory else f"_f{i}"
            body.append(f"    _set{i}(self, {value})" if frozen else f"    self._f{i} = {value}")
        code = _TEMPLATES[key] = init_code(
            "\n".join([f"def __init__(self{params}):", *(body or ["    pass"])])
        )
    return code


# The `__init__` templates of the lint path, compiled ahead of time: compiling the templates a
# `glslcheck lint FILE` makes (this module's and frontend/syntax.py's) would cost every start-up.
# `base/_init_code.py` holds them as functions, compiled into its .pyc like any module,
# keyed by the exact text `init_code` would compile; `python -m glslcheck.base.records` writes it,
# and tests/test_records.py checks that it holds exactly the lint path's templates.
_precompiled: dict[str, Any] | None = None  # template text -> its function (any arity)
_recorded: list[str] | None = None  # the texts asked for, while the generator records them


def init_code(source: str):
    """The code of `def __init__(...)` in `source` (a template: no user input), from
    `base/_init_code.py` when it holds that text, else compiled here."""
    global _precompiled
    if _recorded is not None:
        _recorded.append(source)
    if _precompiled is None:
        _precompiled = _stored_templates()
    function = _precompiled.get(source)
    if function is not None:
        return function.__code__.replace(co_name="__init__", co_qualname="__init__")
    env: dict[str, Any] = {}
    exec(source, {}, env)  # noqa: S102 - a fixed template
    return env["__init__"].__code__


def _stored_templates() -> dict[str, Any]:
    try:
        from ._init_code import SOURCES
    except ImportError:  # the generator's first run
        return {}
    return SOURCES


def lint_path_templates() -> list[str]:
    """Every template `init_code` is asked for by `glslcheck lint` and `check` of the lab's
    shaders, in a fresh interpreter (the templates are made as the modules are imported)."""
    import json
    import os
    import subprocess
    import sys

    lab = os.path.join(
        os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "lab_shaders"
    )
    script = (
        "import io, json, sys, contextlib; from glslcheck.base import records; "
        "records._recorded = []; "
        "records._precompiled = {}\n"
        "from glslcheck.cli.main import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        f"    main(['lint', {lab!r}]); main(['check', {lab!r}])\n"
        "print(json.dumps(records._recorded))\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script],
        capture_output=True,
        text=True,
        check=True,
        env={**os.environ, "GLSLCHECK_JOBS": "1"},
    )
    return sorted(set(json.loads(done.stdout)))


def init_code_source(templates: list[str]) -> str:
    """The text of `base/_init_code.py` for `templates`."""
    lines = [
        '"""The `__init__` templates of the lint path, compiled ahead of time (see `init_code` in',
        "glslcheck/base/records.py). Written by `python -m glslcheck.base.records`; do not edit.",
        '"""',
        "",
        "# `_set0`, `_set1`, ... and `_Factory` are the globals each class's `__init__` is given",
        "# where it is made (records._make_init, frontend/syntax.py), not names of this module.",
        '# mypy: disable-error-code="name-defined"',
        "",
    ]
    for i, source in enumerate(templates):
        head, sep, body = source.partition("\n")
        if not head.startswith("def __init__("):
            raise ValueError(f"not a template: {head!r}")
        lines += ["", head.replace("def __init__(", f"def _t{i}(", 1) + sep + body, ""]
    lines += ["", "SOURCES = {"]
    lines += [f"    {source!r}: _t{i}," for i, source in enumerate(templates)]
    lines.append("}")
    return "\n".join(lines) + "\n"


def main() -> int:
    from .generated import write_base_module

    write_base_module("_init_code.py", init_code_source(lint_path_templates()))
    return 0


def _make_init(cls: type, specs: dict[str, _Field], defaults: tuple, frozen: bool) -> FunctionType:
    names = tuple(specs)
    factories = tuple(specs[name].factory is not None for name in names)
    template = _init_template(len(names), frozen, factories)
    rename = {f"_f{i}": name for i, name in enumerate(names)}
    code = template.replace(
        co_varnames=tuple(rename.get(n, n) for n in template.co_varnames),
        co_names=tuple(rename.get(n, n) for n in template.co_names),
        co_consts=tuple(rename.get(c, c) if type(c) is str else c for c in template.co_consts),
        co_qualname=f"{cls.__qualname__}.__init__",
    )
    scope = {"_Factory": _Factory, "__builtins__": __builtins__}
    if frozen:
        for i, name in enumerate(names):
            slot = next((k.__dict__[name] for k in cls.__mro__ if name in k.__dict__), None)
            if type(slot) is MemberDescriptorType:
                scope[f"_set{i}"] = slot.__set__
            else:  # no slot (slots=False): through object.__setattr__
                scope[f"_set{i}"] = partial(_object_setattr_to, name)
    return FunctionType(code, scope, "__init__", defaults or None)


def _object_setattr_to(name: str, obj: Any, value: Any) -> None:
    object.__setattr__(obj, name, value)


def tuple_getter(names: tuple[str, ...]) -> Callable[[Any], tuple]:
    """`obj -> (obj.a, obj.b, ...)`, a tuple for any number of names (one C call for two or
    more)."""
    if len(names) >= 2:
        return attrgetter(*names)
    if names:
        get = attrgetter(names[0])
        return lambda obj: (get(obj),)
    return lambda obj: ()


# The methods every record class shares: they read the class's `_key` (the compared fields as a
# tuple), `_shown` (the fields __repr__ shows) and `_fields`.


def _repr(self) -> str:
    shown = ", ".join(f"{name}={getattr(self, name)!r}" for name in self._shown)
    return f"{type(self).__qualname__}({shown})"


def _eq(self, other):
    if other.__class__ is not self.__class__:
        return NotImplemented
    return self._key(self) == self._key(other)


def _hash(self) -> int:
    return hash(self._key(self))


def _frozen_setattr(self, name: str, value: Any) -> None:
    if name in self._fields:
        raise FrozenInstanceError(f"cannot assign to field {name!r}")
    object.__setattr__(self, name, value)


def _frozen_delattr(self, name: str) -> None:
    if name in self._fields:
        raise FrozenInstanceError(f"cannot delete field {name!r}")
    object.__delattr__(self, name)


def _reduce(self):
    return type(self), tuple(getattr(self, name) for name in self._fields)


@dataclass_transform(field_specifiers=(field,))
def record(
    cls: type | None = None, /, *, frozen: bool = False, eq: bool = True, slots: bool = True
) -> Any:
    """Make `cls` a record class (see the module's docstring); `@record` or `@record(...)`."""
    if cls is None:
        return lambda c: _process(c, frozen, eq, slots)
    return _process(cls, frozen, eq, slots)


def _process(cls: type, frozen: bool, eq: bool, slots: bool) -> type:
    ns = dict(cls.__dict__)
    own = [n for n in ns.get("__annotations__", {}) if not n.startswith("__")]
    specs: dict[str, _Field] = {}
    for base in reversed(cls.__mro__[1:]):
        specs.update(getattr(base, "_field_specs", {}))
    for name in own:
        value = ns.pop(name, _MISSING)
        specs[name] = value if isinstance(value, _Field) else _Field(value, None, True, True)
    names = tuple(specs)
    defaults = []
    for name, spec in specs.items():
        if spec.factory is not None:
            defaults.append(_Factory(spec.factory))
        elif spec.default is not _MISSING:
            defaults.append(spec.default)
        elif defaults:
            raise TypeError(
                f"{cls.__name__}: field {name!r} without a default follows one with a default"
            )
    if slots:
        # Slots the class declares itself (not fields: no __init__ parameter, not compared,
        # not shown) are kept after the fields' (diagnostics.Location's `_pending`).
        extra = tuple(n for n in ns.get("__slots__", ()) if n not in own)
        for name in extra:
            ns.pop(name, None)  # the member descriptor the class body's own __slots__ made
        ns["__slots__"] = tuple(own) + extra
        ns.pop("__dict__", None)
        ns.pop("__weakref__", None)
        cls = type(cls)(cls.__name__, cls.__bases__, ns)
    else:
        for name in own:
            if name in cls.__dict__:
                delattr(cls, name)
    made: Any = cls  # the record class: its attributes are set here, at run time
    made._field_specs = specs
    made._fields = names
    made._shown = tuple(n for n in names if specs[n].repr)
    made._key = staticmethod(tuple_getter(tuple(n for n in names if specs[n].compare)))
    setattr(made, "__match_args__", names)  # mypy allows assigning it only in a class body
    # As @dataclass: a method the class defines itself is kept.
    own_methods = {
        "__init__": _make_init(cls, specs, tuple(defaults), frozen),
        "__repr__": _repr,
        **({"__eq__": _eq} if eq else {}),
        # A frozen record cannot be unpickled field by field (its __setattr__ refuses): by value.
        **(
            {"__setattr__": _frozen_setattr, "__delattr__": _frozen_delattr, "__reduce__": _reduce}
            if frozen
            else {}
        ),
    }
    for name, method in own_methods.items():
        if name not in ns:
            setattr(cls, name, method)
    explicit_hash = ns.get("__hash__", None) is not None or (
        "__hash__" in ns and "__eq__" not in ns
    )
    if eq and not explicit_hash:
        made.__hash__ = _hash if frozen else None
    return made


def field_names(cls: type) -> tuple[str, ...]:
    """The fields of the record class `cls`, in order."""
    names: tuple[str, ...] = getattr(cls, "_fields")  # set by `record`, unseen by type checkers
    return names


def replace(obj: Any, /, **changes: Any) -> Any:
    """A copy of the record `obj` with the fields in `changes` set (as `dataclasses.replace`)."""
    unknown = set(changes) - set(obj._fields)
    if unknown:
        raise TypeError(f"{type(obj).__name__} has no field {sorted(unknown)[0]!r}")
    return type(obj)(*(changes[n] if n in changes else getattr(obj, n) for n in obj._fields))


if __name__ == "__main__":
    import sys

    sys.exit(main())
