"""Fewer numba IR statements for the same computation: a lockstep function's text (lanes.py)
rewritten where numba would spend a statement on nothing. numba's compile time grows with its
IR statements (each is typed, lowered to LLVM in Python, and gives LLVM instructions to
optimize), and the W lanes of a lockstep function multiply them.

- Globals read from locals: each read of a module global (a constant `F_7p0`, the runtime's
  `lsel`) is a statement of numba's IR of its own (`$x = global(F_7p0)`), a local's read is
  none. A global read more than once is bound to a local once, at the function's top: the same
  value and type, so the same values computed (LLVM propagates the constant as before).
- A repeated pure expression computed once: a temporary assigned an expression of names,
  constants, operators and `lsel` that an earlier temporary of the same straight-line run holds,
  none of whose names was written since (`x <= 7.0` in every row of a sprite table, W times
  each), is that temporary: the same operation on the same values, the same bits.
- A temporary written straight into the name it is copied to: `_t5__0 = e` then `v__0 =
  _t5__0` (codegen's temporaries, a copy per lane) is `v__0 = e`, where the temporary is read
  nowhere else and the name is neither read nor written between the two: the name then holds
  the value a statement earlier, where nothing reads it.
"""

from __future__ import annotations

import ast
import builtins
from typing import Any

PREFIX = "_g_"  # the locals of hoisted globals (no name of the generated code starts so)
_NP_VALUES = ("float32", "int32", "uint32")


def hoistable_globals(tree: ast.Module) -> tuple[set[str], set[str]]:
    """(constants, own) of a generated module: the globals that hold a NumPy scalar or a NumPy
    scalar type (`F_7p0 = np.float32(7.0)`, `F32 = np.float32`), and the other names the module
    binds itself (its functions, its settings such as `FMA`, which numba folds as constants;
    the caller adds the lockstep variants' names). A called name of neither kind is the
    runtime's (`lsel`, `mod`: imported)."""
    constants: set[str] = set()
    own: set[str] = set()
    for node in tree.body:
        if isinstance(node, ast.Assign):
            for t in node.targets:
                if isinstance(t, ast.Name):
                    (constants if _np_value(node.value) else own).add(t.id)
        elif isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            own.add(node.name)
    return constants, own


def _np_value(v: Any) -> bool:
    """`np.float32(7.0)` (a literal, negated or not) or `np.float32` itself."""
    if isinstance(v, ast.Call):
        if len(v.args) != 1 or v.keywords:
            return False
        arg = v.args[0]
        if isinstance(arg, ast.UnaryOp) and isinstance(arg.op, ast.USub):
            arg = arg.operand
        if not isinstance(arg, ast.Constant):
            return False
        v = v.func
    return (
        isinstance(v, ast.Attribute)
        and isinstance(v.value, ast.Name)
        and v.value.id == "np"
        and v.attr in _NP_VALUES
    )


def slim_function(source: str, constants: set[str], own: set[str]) -> str:
    """One generated function's text (a `def`, decorators not included) with its globals read
    from locals and its temporaries' copies folded (the module docstring)."""
    fn = ast.parse(source).body[0]
    assert isinstance(fn, ast.FunctionDef)
    _common_values(fn)
    _fold_copies(fn)
    _hoist_globals(fn, constants, own)
    return ast.unparse(fn)


def _hoist_globals(fn: ast.FunctionDef, constants: set[str], own: set[str]) -> None:
    local = {a.arg for a in fn.args.args}
    index: set[str] = set()  # a name indexing a subscript: numba's static index needs a global
    called: set[str] = set()
    reads: dict[str, list[ast.Name]] = {}
    for n in walk_nodes(fn):
        if isinstance(n, ast.Name):
            if not isinstance(n.ctx, ast.Load):
                local.add(n.id)
            elif n.id not in own:
                reads.setdefault(n.id, []).append(n)
        elif isinstance(n, ast.Subscript):
            index |= {m.id for m in walk_nodes(n.slice) if isinstance(m, ast.Name)}
        elif isinstance(n, ast.Call) and isinstance(n.func, ast.Name):
            called.add(n.func.id)
    runtime = {c for c in called if c not in constants and not hasattr(builtins, c)}
    binds = []
    for name in sorted(reads):
        if name in local or name in index or not (name in constants or name in runtime):
            continue
        if len(reads[name]) < 2:  # one read: the local's binding would be a statement more
            continue
        for n in reads[name]:
            n.id = PREFIX + name
        binds.append(
            ast.Assign([ast.Name(PREFIX + name, ast.Store())], ast.Name(name, ast.Load()), lineno=0)
        )
    body = fn.body
    doc = int(
        bool(body)
        and isinstance(body[0], ast.Expr)
        and isinstance(body[0].value, ast.Constant)
        and isinstance(body[0].value.value, str)
    )
    fn.body = body[:doc] + binds + body[doc:]


def _fold_copies(fn: ast.FunctionDef) -> None:
    stores: dict[str, int] = {a.arg: 1 for a in fn.args.args}
    loads: dict[str, int] = {}
    for n in walk_nodes(fn):
        if isinstance(n, ast.Name):
            counts = loads if isinstance(n.ctx, ast.Load) else stores
            counts[n.id] = counts.get(n.id, 0) + 1

    def temporary(name: str) -> bool:  # written once, read once (by the copy)
        return stores.get(name) == 1 and loads.get(name) == 1

    def fold(stmts: list) -> list:
        names: list[set[str] | None] = [None] * len(stmts)  # each statement's names, when asked
        defs: dict[str, int] = {}  # a temporary -> the index of its write in stmts
        drop: set[int] = set()
        for i, s in enumerate(stmts):
            for block in ("body", "orelse"):
                inner = getattr(s, block, None)
                if isinstance(inner, list) and inner and isinstance(inner[0], ast.stmt):
                    setattr(s, block, fold(inner))
            if not (isinstance(s, ast.Assign) and len(s.targets) == 1):
                continue
            t, v = s.targets[0], s.value
            if not isinstance(t, ast.Name):
                continue
            if isinstance(v, ast.Name) and v.id in defs and t.id != v.id:
                j = defs.pop(v.id)
                between = range(j + 1, i)
                if all(t.id not in _names_at(stmts, names, k) for k in between):
                    first = stmts[j]
                    first.targets = [ast.Name(t.id, ast.Store())]
                    names[j] = None
                    drop.add(i)
                    continue
            if temporary(t.id):
                defs[t.id] = i
        out = [s for i, s in enumerate(stmts) if i not in drop]
        return out or [ast.Pass()]

    fn.body = fold(fn.body)


def names_in(node: Any) -> set[str]:
    """The names node reads or writes (node included)."""
    return {n.id for n in walk_nodes(node) if isinstance(n, ast.Name)}


def walk_nodes(node: Any) -> Any:
    """Every node under node (node included), as ast.walk but depth first and without its
    per-node generators: for what counts and collects, in no order."""
    todo = [node]
    while todo:
        n = todo.pop()
        yield n
        for field in n._fields:
            x = getattr(n, field, None)
            if isinstance(x, list):
                todo += [y for y in x if isinstance(y, ast.AST)]
            elif isinstance(x, ast.AST):
                todo.append(x)


def _names_at(stmts: list, cache: list, k: int) -> set[str]:
    got = cache[k]
    if got is None:
        got = cache[k] = {n.id for n in walk_nodes(stmts[k]) if isinstance(n, ast.Name)}
    return got


# the nodes of a value computed again to the same bits from the same names (a duplicate is
# dropped, never a computation added: what raises raised the first time)
_PURE = (
    *(ast.Compare, ast.BinOp, ast.UnaryOp, ast.BoolOp, ast.Name, ast.Constant, ast.Load),
    *(ast.Add, ast.Sub, ast.Mult, ast.Div, ast.Mod, ast.BitAnd, ast.BitOr, ast.USub, ast.Not),
    *(ast.Eq, ast.NotEq, ast.Lt, ast.LtE, ast.Gt, ast.GtE, ast.And, ast.Or),
)


def _pure_value(v: Any, names: set[str]) -> Any:
    """An expression of names and constants with operators and lsel calls only (no effect, and
    its value a function of its names' values): a key equal for two such expressions exactly
    when their `ast.dump`s are (constants by their repr, as the dump: 0.0 is not -0.0, nor 1
    1.0), its names added to `names`; None for any other expression."""
    if isinstance(v, ast.Name):
        if not isinstance(v.ctx, ast.Load):
            return None
        names.add(v.id)
        return v.id
    if isinstance(v, ast.Constant):
        return (ast.Constant, repr(v.value), v.kind)
    if isinstance(v, ast.Call):
        if not (isinstance(v.func, ast.Name) and v.func.id == "lsel" and not v.keywords):
            return None
        parts: list = [ast.Call, _pure_value(v.func, names)]
        parts += [_pure_value(a, names) for a in v.args]
        return None if None in parts else tuple(parts)
    if not isinstance(v, _PURE):
        return None
    parts = [type(v)]
    for field in v._fields:
        x = getattr(v, field)
        for y in x if isinstance(x, list) else [x]:
            if isinstance(y, _OPERATORS):
                if not isinstance(y, _PURE):
                    return None
                parts.append(type(y))
            elif isinstance(y, ast.AST):
                k = _pure_value(y, names)
                if k is None:
                    return None
                parts.append(k)
            else:
                return None  # (no field of these nodes but Constant's holds a plain value)
    return tuple(parts)


_OPERATORS = (ast.operator, ast.unaryop, ast.cmpop, ast.boolop)


def _common_values(fn: ast.FunctionDef) -> None:
    stores: dict[str, int] = {a.arg: 1 for a in fn.args.args}
    first_read: dict[str, int] = {}  # a name's first read in the text (its line)
    for n in walk_nodes(fn):
        if isinstance(n, ast.Name) and not isinstance(n.ctx, ast.Load):
            stores[n.id] = stores.get(n.id, 0) + 1
        elif isinstance(n, ast.Name):
            first_read[n.id] = min(first_read.get(n.id, n.lineno), n.lineno)
    same: dict[str, str] = {}  # a dropped temporary -> the one that holds its value

    def run(stmts: list) -> list:
        held: dict[Any, str] = {}  # the key of a value (_pure_value) -> its temporary
        reading: dict[str, set] = {}  # a name -> the keys held of the values that read it
        out = []
        for s in stmts:
            _rename(s, same)
            for block in ("body", "orelse"):
                inner = getattr(s, block, None)
                if isinstance(inner, list) and inner and isinstance(inner[0], ast.stmt):
                    setattr(s, block, run(inner))
            if isinstance(s, (ast.If, ast.While)):
                held.clear()  # a value of the run before it is not known to be computed after
                reading.clear()
            elif (
                isinstance(s, ast.Assign)
                and len(s.targets) == 1
                and isinstance(s.targets[0], ast.Name)
                and stores.get(s.targets[0].id) == 1
                # read nowhere before its write (a loop's next pass would read the old value)
                and first_read.get(s.targets[0].id, s.lineno + 1) > s.lineno
                and not isinstance(s.value, (ast.Name, ast.Constant))
            ):
                names: set[str] = set()
                key = _pure_value(s.value, names)
                if key is not None:
                    got = held.get(key)
                    if got is not None:
                        same[s.targets[0].id] = got
                        continue
                    held[key] = s.targets[0].id
                    for name in names:
                        reading.setdefault(name, set()).add(key)
            if held:
                for name in _targets(s):
                    for key in reading.pop(name, ()):
                        held.pop(key, None)
            out.append(s)
        return out or [ast.Pass()]

    fn.body = run(fn.body)


def _rename(s: Any, same: dict[str, str]) -> None:
    """The reads of dropped temporaries in s (its own statements, not nested blocks', which the
    walk renames when it reaches them) read the temporaries that hold their values."""
    if not same:
        return
    nodes = [s]
    while nodes:
        n = nodes.pop()
        for field, value in ast.iter_fields(n):
            if isinstance(n, (ast.If, ast.While)) and field in ("body", "orelse"):
                continue
            for child in value if isinstance(value, list) else [value]:
                if isinstance(child, ast.Name) and isinstance(child.ctx, ast.Load):
                    child.id = same.get(child.id, child.id)
                elif isinstance(child, ast.AST):
                    nodes.append(child)


def _targets(s: Any) -> set[str]:
    """The names a simple statement writes (a compound one clears what is held anyway)."""
    if isinstance(s, ast.Assign):
        out = set()
        for t in s.targets:
            for x in t.elts if isinstance(t, ast.Tuple) else [t]:
                if isinstance(x, ast.Name):
                    out.add(x.id)
        return out
    if isinstance(s, ast.AugAssign) and isinstance(s.target, ast.Name):
        return {s.target.id}
    return set()
