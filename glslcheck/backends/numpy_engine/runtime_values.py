"""The Runtime's values: Struct, swizzles, constants, conversions, constructors, indexing and
masked assignment of lane arrays (the representation: runtime.py's docstring).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import numpy as np

from ..driver_profile import float_to_uint
from .llvmpipe_reference import keeps_shape
from .runtime_state import RuntimeState

I32 = np.int32
U32 = np.uint32
BOOL = np.bool_
INT_MIN = -(2**31)


_SWIZZLE_SETS = ("xyzw", "rgba", "stpq")
_SWIZZLE_CACHE: dict[str, tuple[int, ...]] = {}


class GLSLRuntimeError(RuntimeError):
    """A construct the runtime cannot evaluate (for example a texture lookup)."""


def swizzle_indices(sw: str) -> tuple[int, ...]:
    """Component indices of a swizzle string (``"xzy"`` -> ``(0, 2, 1)``); any of xyzw/rgba/stpq."""
    got = _SWIZZLE_CACHE.get(sw)
    if got is None:
        for letters in _SWIZZLE_SETS:
            if all(ch in letters for ch in sw):
                got = tuple(letters.index(ch) for ch in sw)
                break
        else:
            raise ValueError(f"bad swizzle {sw!r}")
        _SWIZZLE_CACHE[sw] = got
    return got


class Struct:
    """A GLSL struct value: a type name and an ordered set of named fields.

    Fields are read as attributes (``s.pos``) or with ``s["pos"]``. A Struct is never modified
    in place by the runtime; :meth:`Runtime.assign_field` returns a new one. An array of structs
    is a Struct whose fields carry a leading array axis (struct-of-arrays).
    """

    __slots__ = ("_name", "_fields")

    def __init__(self, _name: str, _fields: dict[str, Any] | None = None, **fields: Any) -> None:
        object.__setattr__(self, "_name", _name)
        d = dict(_fields or {})
        d.update(fields)
        object.__setattr__(self, "_fields", d)

    def __getattr__(self, key: str) -> Any:
        try:
            return self._fields[key]
        except KeyError:
            raise AttributeError(key) from None

    def __getitem__(self, key: str) -> Any:
        return self._fields[key]

    def __setattr__(self, key: str, value: Any) -> None:
        raise AttributeError("Struct values are immutable; use Runtime.assign_field")

    def __reduce__(self):  # pickled by value (globals travel to render worker processes)
        return (Struct, (self._name, self._fields))

    def replace(self, **changes: Any) -> Struct:
        d = dict(self._fields)
        d.update(changes)
        return Struct(self._name, d)

    def map(self, fn) -> Struct:
        return Struct(self._name, {k: fn(v) for k, v in self._fields.items()})

    @property
    def type_name(self) -> str:
        return self._name

    @property
    def fields(self) -> dict[str, Any]:
        return dict(self._fields)

    def __repr__(self) -> str:
        inner = ", ".join(f"{k}={v!r}" for k, v in self._fields.items())
        return f"{self._name}({inner})"


def lanes_of(*values: Any) -> int:
    n = 1
    for v in values:
        if isinstance(v, np.ndarray) and v.ndim:
            m = v.shape[-1]
            if m != 1:
                if n != 1 and n != m:
                    raise ValueError(f"lane counts differ: {n} vs {m}")
                n = m
        elif isinstance(v, Struct):
            n = max(n, lanes_of(*v._fields.values()))
    return n


# Signed integers of each item size: what `where` views its operands as.
_BITS: dict[int, np.dtype] = {
    1: np.dtype(np.int8),
    2: np.dtype(np.int16),
    4: np.dtype(np.int32),
    8: np.dtype(np.int64),
}
# Fewer result elements than this go to np.where itself (the bit select's extra calls cost more).
_WHERE_MIN = 1024


def where(cond: Any, a: Any, b: Any) -> Any:
    """``np.where(cond, a, b)``, bit for bit (NaN payloads included), for a bool ``cond`` and
    arrays of one dtype: as the bit select ``b ^ ((a ^ b) & -cond)``, three passes without a
    branch per element, 1.5-2x faster than np.where's loop on a tile's lanes whatever the mask's
    pattern (a masked copy is faster on long runs of one value but 7x slower on a scattered
    mask). Anything else, and small results, go to np.where."""
    if (
        type(cond) is not np.ndarray
        or type(a) is not np.ndarray
        or type(b) is not np.ndarray
        or cond.dtype != BOOL
        or a.dtype != b.dtype
        or max(cond.size, a.size, b.size) < _WHERE_MIN
    ):
        return np.where(cond, a, b)
    bits = _BITS.get(a.dtype.itemsize)
    if bits is None or a.dtype.kind not in "fiub":
        return np.where(cond, a, b)
    a, b = _one_lane(a, cond), _one_lane(b, cond)
    if a.size <= 16 and a.shape == b.shape and a.tobytes() == b.tobytes():
        # both sides one value of the same bits (a constant table's row against itself):
        # that value in every lane, read-only as a uniform input is (runtime_operators._const)
        return np.broadcast_to(a, np.broadcast_shapes(cond.shape, a.shape))
    bv = b.view(bits)
    r = np.bitwise_xor(a.view(bits), bv)
    m = _select_mask(cond, bits)
    r = np.bitwise_and(r, m, out=r if keeps_shape(r, m) else None)
    r = np.bitwise_xor(r, bv, out=r if keeps_shape(r, bv) else None)
    return r.view(a.dtype)


def _one_lane(v: np.ndarray, cond: np.ndarray) -> np.ndarray:
    """A value broadcast over the lanes (lane stride 0: an earlier select of one value) as its
    one lane, which the select broadcasts again over ``cond``'s lanes (NumPy's loops are 2x
    slower on such views)."""
    if v.ndim and v.strides[-1] == 0 and v.shape[-1] > 1 and cond.shape[-1] == v.shape[-1]:
        return v[..., :1]
    return v


# The last mask `where` made, as (cond, bits, mask): the selects of a struct's fields and of
# a branch's variables share one condition. One tuple, replaced whole (threads share it).
_last_mask: tuple = (None, None, None)


def _select_mask(cond: np.ndarray, bits: np.dtype) -> np.ndarray:
    """Every bit set where ``cond``, none elsewhere, in integers of dtype ``bits``."""
    global _last_mask
    last = _last_mask
    if last[0] is cond and last[1] is bits:
        return last[2]
    m = np.negative(cond.view(np.int8), dtype=bits)
    _last_mask = (cond, bits, m)
    return m


_CONVERTERS = {"float": "to_float", "int": "to_int", "uint": "to_uint", "bool": "to_bool"}


class ValueOps(RuntimeState):
    """Runtime's plumbing, constants, conversions, constructors and access (a mixin of Runtime:
    it reads the precision and constants Runtime.__init__ sets)."""

    # ------------------------------------------------------------------ plumbing
    @staticmethod
    def errstate():
        """Context manager silencing NumPy floating-point warnings for a whole render."""
        return np.errstate(all="ignore")

    def c(self, x: float) -> Any:
        """A float constant as a 0-d scalar of the active dtype (for internal formulas)."""
        return self.F(x)

    def _f(self, x: Any) -> np.ndarray:
        """Coerce to a float array of the active dtype (no copy when already right)."""
        if isinstance(x, np.ndarray):
            if x.dtype is self._dtype or x.dtype == self._dtype:
                return x
            if x.dtype == BOOL:
                return x.astype(self.F)
            return x.astype(self.F)
        return np.asarray(x, dtype=self.F)

    @staticmethod
    def _like(x: Any, ref: Any) -> Any:
        """Python number -> array of ref's dtype (arrays are returned unchanged)."""
        if isinstance(x, np.ndarray):
            return x
        if isinstance(ref, np.ndarray):
            return np.asarray(x, dtype=ref.dtype)
        if isinstance(x, bool):
            return np.asarray(x, dtype=BOOL)
        if isinstance(x, int):
            return np.asarray(x, dtype=I32)
        return np.asarray(x)

    def _pair(self, a: Any, b: Any) -> tuple[np.ndarray, np.ndarray]:
        if not isinstance(a, np.ndarray):
            a = self._like(a, b) if isinstance(b, np.ndarray) else self._num(a)
        if not isinstance(b, np.ndarray):
            b = self._like(b, a)
        return a, b

    def _num(self, x: Any) -> np.ndarray:
        if isinstance(x, (bool, np.bool_)):
            return np.asarray(x, dtype=BOOL)
        if isinstance(x, (int, np.integer)):
            return np.asarray(x, dtype=I32)
        return np.asarray(x, dtype=self.F)

    # ------------------------------------------------------------------ constants
    def const_float(self, x: float, x32: float | None = None) -> np.ndarray:
        """A float literal, uniform over lanes: shape (1,), active float dtype; in float32 `x32`
        when given (the literal's decimal rounded to float32 once, where rounding `x` is off)."""
        return np.array([x32 if x32 is not None and self.F is np.float32 else x], dtype=self.F)

    f = const_float

    @staticmethod
    def const_int(x: int) -> np.ndarray:
        """An int literal, shape (1,), int32 (values wrap to 32 bits like GLSL)."""
        return np.array([x], dtype=np.int64).astype(I32)

    @staticmethod
    def const_uint(x: int) -> np.ndarray:
        """A uint literal, shape (1,), uint32."""
        return np.array([int(x) & 0xFFFFFFFF], dtype=U32)

    @staticmethod
    def const_bool(x: bool) -> np.ndarray:
        """A bool literal, shape (1,)."""
        return np.array([bool(x)], dtype=BOOL)

    def zeros(self, shape: tuple[int, ...] = (), kind: str = "float", lanes: int = 1) -> np.ndarray:
        """A zero value (WebGL zero-initialises every variable) of GLSL shape ``shape``.

        ``kind`` is float/int/uint/bool; ``shape`` is ``()`` scalar, ``(K,)`` vector,
        ``(C, R)`` matrix, with any leading array axes.
        """
        return np.zeros(tuple(shape) + (lanes,), dtype=self.dtype_of(kind))

    def dtype_of(self, kind: str):
        return {"float": self.F, "int": I32, "uint": U32, "bool": BOOL}[kind]

    def broadcast_lanes(self, x: Any, lanes: int) -> Any:
        """``x`` with its lane axis expanded to ``lanes``: always a fresh, writable array."""
        if isinstance(x, Struct):
            return x.map(lambda v: self.broadcast_lanes(v, lanes))
        x = self._num(x) if not isinstance(x, np.ndarray) else x
        if x.ndim == 0:
            x = x.reshape(1)
        out = np.empty(x.shape[:-1] + (lanes,), dtype=x.dtype)
        out[...] = x  # always a fresh writable array: callers may write into it
        return out

    # ------------------------------------------------------------------ conversions
    def to_float(self, x: Any) -> np.ndarray:
        """``float(x)``/``vecK(x)`` conversion: bool -> 0/1, int/uint rounded to nearest."""
        return self._f(x)

    @staticmethod
    def _float_to_i64(x: np.ndarray) -> np.ndarray:
        return np.trunc(x.astype(np.float64))

    def to_int(self, x: Any) -> np.ndarray:
        """``int(x)``: float truncates toward zero; NaN, +-inf and values outside the int32
        range give INT_MIN (llvmpipe/x86 ``cvttps2dq``); uint reinterprets the bits; bool 0/1."""
        x = self._num(x) if not isinstance(x, np.ndarray) else x
        k = x.dtype.kind
        if k == "i":
            return x if x.dtype == I32 else x.astype(I32)
        if k == "u":
            return x.astype(U32).view(I32)
        if k == "b":
            return x.astype(I32)
        t = self._float_to_i64(x)
        ok = (t >= -(2.0**31)) & (t < 2.0**31)
        return where(ok, t, INT_MIN).astype(np.int64).astype(I32)

    def to_uint(self, x: Any) -> np.ndarray:
        """``uint(x)``: float truncates; negatives, NaN and values past 2**32 are undefined and
        follow the runtime's ``float_to_uint`` model (glslcheck/backends/driver_profile.py: what
        llvmpipe computes on this kind of CPU); int reinterprets the bits; bool 0/1."""
        x = self._num(x) if not isinstance(x, np.ndarray) else x
        k = x.dtype.kind
        if k == "u":
            return x if x.dtype == U32 else x.astype(U32)
        if k == "i":
            return x.astype(I32).view(U32)
        if k == "b":
            return x.astype(U32)
        return float_to_uint(x, self.float_to_uint)

    def to_bool(self, x: Any) -> np.ndarray:
        """``bool(x)``: x != 0 (NaN -> true)."""
        x = self._num(x) if not isinstance(x, np.ndarray) else x
        if x.dtype == BOOL:
            return x
        return x != 0

    def convert(self, x: Any, kind: str) -> np.ndarray:
        """Convert to ``kind`` in {"float", "int", "uint", "bool"}."""
        if kind == "float":  # the common case, without building bound methods per call
            return self._f(x)
        return getattr(self, _CONVERTERS[kind])(x)

    # ------------------------------------------------------------------ constructors
    def _components(self, args: Iterable[Any], kind: str) -> list[np.ndarray]:
        comps: list[np.ndarray] = []
        for a in args:
            a = self._num(a) if not isinstance(a, np.ndarray) else a
            a = self.convert(a, kind)
            if a.ndim <= 1:
                comps.append(a.reshape(-1) if a.ndim == 0 else a)
            elif a.ndim == 2:
                comps.extend(a)
            elif a.ndim == 3:
                for col in a:
                    comps.extend(col)
            else:
                raise ValueError(f"cannot take components of an array of shape {a.shape}")
        return comps

    @staticmethod
    def _stack(comps: list[np.ndarray]) -> np.ndarray:
        lanes = lanes_of(*comps)
        out = np.empty((len(comps), lanes), dtype=comps[0].dtype)
        for i, c in enumerate(comps):
            out[i] = c
        return out

    def _vec(self, k: int, args: tuple, kind: str) -> np.ndarray:
        comps = self._components(args, kind)
        if len(comps) == 1:
            comps = comps * k
        if len(comps) < k:
            raise ValueError(f"vec{k} constructor needs {k} components, got {len(comps)}")
        return self._stack(comps[:k])

    def vec(self, k: int, *args: Any) -> np.ndarray:
        """``vecK(...)``: one scalar splats; otherwise the components of all arguments
        (scalars, vectors, matrices column-major) in order, converted to float."""
        if len(args) == k:  # k float scalars (`vec3(p.x + e, p.y, p.z)`): what _vec makes of
            dt = self._dtype  # them, without converting each one
            for a in args:
                if not (isinstance(a, np.ndarray) and a.ndim == 1 and a.dtype == dt):
                    break
            else:
                return self._stack(list(args))
        return self._vec(k, args, "float")

    def ivec(self, k: int, *args: Any) -> np.ndarray:
        return self._vec(k, args, "int")

    def uvec(self, k: int, *args: Any) -> np.ndarray:
        return self._vec(k, args, "uint")

    def bvec(self, k: int, *args: Any) -> np.ndarray:
        return self._vec(k, args, "bool")

    def mat(self, c: int, r: int, *args: Any) -> np.ndarray:
        """``matCxR(...)``: a scalar gives scalar*identity; a matrix copies the overlapping
        part and fills the rest from the identity; otherwise C*R components column-major."""
        if len(args) == 1:
            a = args[0]
            a = self._num(a) if not isinstance(a, np.ndarray) else a
            if a.ndim <= 1:
                s = self._f(a).reshape(-1)
                out = np.zeros((c, r, s.shape[-1]), dtype=self.F)
                for i in range(min(c, r)):
                    out[i, i] = s
                return out
            if a.ndim == 3:
                a = self._f(a)
                out = np.zeros((c, r, a.shape[-1]), dtype=self.F)
                for i in range(min(c, r)):
                    out[i, i] = self._1
                cc, rr = min(c, a.shape[0]), min(r, a.shape[1])
                out[:cc, :rr] = a[:cc, :rr]
                return out
        comps = self._components(args, "float")
        if len(comps) < c * r:
            raise ValueError(f"mat{c}x{r} constructor needs {c * r} components, got {len(comps)}")
        return self._stack(comps[: c * r]).reshape(c, r, -1)

    def array(self, *elements: Any) -> Any:
        """``T[](e0, e1, ...)``: stack elements on a new leading axis (Structs field-wise)."""
        if isinstance(elements[0], Struct):
            s0 = elements[0]
            return Struct(
                s0._name, {k: self.array(*(e._fields[k] for e in elements)) for k in s0._fields}
            )
        els = [self._num(e) if not isinstance(e, np.ndarray) else e for e in elements]
        lanes = lanes_of(*els)
        shape = els[0].shape[:-1] + (lanes,) if els[0].ndim else (lanes,)
        out = np.empty((len(els),) + shape, dtype=els[0].dtype)
        for i, e in enumerate(els):
            out[i] = e
        return out

    @staticmethod
    def struct(name: str, **fields: Any) -> Struct:
        """A struct value (constructor ``S(a, b)`` -> ``rt.struct("S", a=..., b=...)``)."""
        return Struct(name, fields)

    # ------------------------------------------------------------------ access
    @staticmethod
    def swizzle(v: np.ndarray, sw: str) -> np.ndarray:
        """Read ``v.sw``: one letter gives a scalar (L,), several a vector (len, L).
        Also applies to scalars (``f.xxx``) when ``v`` is 1-D."""
        idx = swizzle_indices(sw)
        if v.ndim == 1:
            return v if len(idx) == 1 else np.stack([v] * len(idx))
        if len(idx) == 1:
            return v[idx[0]]
        step = idx[1] - idx[0]
        if (
            step
            and v.flags.writeable
            and idx == tuple(range(idx[0], idx[0] + step * len(idx), step))
        ):
            # evenly spaced (.xy, .xz, .zyx, .yz): a view, as the prefixes always were, 20x cheaper
            # than indexing with a list. A read-only value (a uniform) keeps the copy, which
            # Runtime._const takes for a constant, as before
            return v[idx[0] : (idx[-1] + step if idx[-1] + step >= 0 else None) : step]
        if idx == tuple(range(len(idx))):
            return v[: len(idx)]
        return v.take(
            idx, axis=0
        )  # (.xzy, .xxy: ndarray.take costs a third of indexing with a list)

    @staticmethod
    def _mask_lanes(mask: Any) -> Any:
        if mask is None:
            return None
        if isinstance(mask, np.ndarray) and mask.dtype != BOOL:
            mask = mask.astype(BOOL)
        return mask

    def assign(self, old: Any, new: Any, mask: Any = None) -> Any:
        """``old = new`` in lanes where ``mask`` is true (None: all lanes). Works for every
        value kind including Structs; the result has the broadcast lane count and old's dtype."""
        if isinstance(old, Struct):
            return Struct(
                old._name, {k: self.assign(v, new._fields[k], mask) for k, v in old._fields.items()}
            )
        new = self._like(new, old)
        if mask is None:
            return new if new.dtype == old.dtype else new.astype(old.dtype)
        if (
            new is old
            and isinstance(mask, np.ndarray)
            and old.ndim
            and old.shape[-1] == mask.shape[-1]
        ):
            return old  # (a struct field neither side wrote: already per lane, nothing to select.
            # A one-lane value still broadcasts: it would count as a constant in fmul)
        mask = self._mask_lanes(mask)
        out = where(mask, new, old)
        return out if out.dtype == old.dtype else out.astype(old.dtype)

    def assign_swizzle(self, old: np.ndarray, sw: str, new: Any, mask: Any = None) -> np.ndarray:
        """``old.sw = new`` under ``mask`` (``new`` is a scalar for one letter, else a vector)."""
        idx = swizzle_indices(sw)
        new = self._like(new, old)
        lanes = lanes_of(old, new, mask)
        out = self.broadcast_lanes(old, lanes)
        mask = self._mask_lanes(mask)
        if len(idx) == 1:
            comps = [new]
        else:
            comps = [new[i] for i in range(len(idx))]
        for i, c in zip(idx, comps):
            out[i] = c if mask is None else where(mask, c, out[i])
        return out

    def _clamp_index(self, idx: Any, size: int) -> Any:
        if isinstance(idx, (int, np.integer)):
            return min(max(int(idx), 0), size - 1)
        idx = np.asarray(idx)
        if idx.size == 1:
            return min(max(int(idx.reshape(-1)[0]), 0), size - 1)
        return np.clip(idx.astype(np.intp), 0, size - 1)

    def index(self, arr: Any, idx: Any) -> Any:
        """``arr[idx]`` for arrays (leading axis), vectors (component) and matrices (column).

        ``idx`` is a Python int or an int array of lanes; out-of-range indices are clamped to
        ``[0, size-1]`` per lane (ANGLE/WebGL behaviour)."""
        if isinstance(arr, Struct):
            return arr.map(lambda v: self.index(v, idx))
        size = arr.shape[0]
        if (
            arr.shape[-1] == 1
            and isinstance(idx, np.ndarray)
            and idx.ndim == 1
            and idx.shape[0] > 1
            and arr.ndim > 1
        ):
            # a uniform array (a constant table) read at lane-varying indices: one gather that
            # clamps as it reads (mode="clip"), contiguous with the lane axis last
            table = arr[..., 0]
            table = table.transpose(tuple(range(1, table.ndim)) + (0,))
            return np.take(table, idx, axis=-1, mode="clip")
        i = self._clamp_index(idx, size)
        if isinstance(i, int):
            return arr[i]
        lanes = lanes_of(arr, i)
        if size <= 4:  # a few selects beat fancy indexing for vectors and matrices
            out = arr[0]
            for k in range(1, size):
                out = where(i == k, arr[k], out)
            return (
                np.broadcast_to(out, out.shape[:-1] + (lanes,)) if out.shape[-1] != lanes else out
            )
        a = np.broadcast_to(arr, arr.shape[:-1] + (lanes,))
        i = np.broadcast_to(i, (lanes,))
        picked = a[(i, Ellipsis, np.arange(lanes))]  # shape (lanes, ...)
        return np.ascontiguousarray(np.moveaxis(picked, 0, -1))

    def assign_index(self, old: Any, idx: Any, new: Any, mask: Any = None) -> Any:
        """``old[idx] = new`` under ``mask`` with per-lane clamped ``idx``; returns the new
        value."""
        if isinstance(old, Struct):
            return Struct(
                old._name,
                {
                    k: self.assign_index(v, idx, new._fields[k], mask)
                    for k, v in old._fields.items()
                },
            )
        new = self._like(new, old)
        size = old.shape[0]
        i = self._clamp_index(idx, size)
        mask = self._mask_lanes(mask)
        lanes = lanes_of(old, new, mask, i if not isinstance(i, int) else None)
        out = self.broadcast_lanes(old, lanes)
        if isinstance(i, int):
            out[i] = new if mask is None else where(mask, new, out[i])
            return out
        if size > 4:  # one scatter, not a pass per element (float a[100000]: 100,000 passes)
            ln = np.arange(lanes)
            i = np.broadcast_to(i, (lanes,))
            new = np.broadcast_to(new, out.shape[1:])
            if mask is not None:
                on = np.broadcast_to(mask, (lanes,))
                ln, i, new = ln[on], i[on], new[..., on]
            out[(i, Ellipsis, ln)] = np.moveaxis(new, -1, 0)
            return out
        for k in range(size):
            sel = i == k
            if mask is not None:
                sel = sel & mask
            out[k] = where(sel, new, out[k])
        return out

    def assign_field(self, old: Struct, name: str, new: Any, mask: Any = None) -> Struct:
        """``s.name = new`` under ``mask``; returns a new Struct."""
        return old.replace(**{name: self.assign(old._fields[name], new, mask)})

    @staticmethod
    def field(s: Struct, name: str) -> Any:
        return s._fields[name]

    @staticmethod
    def select(cond: Any, a: Any, b: Any) -> Any:
        """``cond ? a : b`` evaluated for all lanes (Structs field-wise)."""
        if isinstance(a, Struct):
            return Struct(
                a._name, {k: ValueOps.select(cond, v, b._fields[k]) for k, v in a._fields.items()}
            )
        return where(cond, a, b)

    def any_lane(self, mask: Any) -> bool:
        """True when some lane of a bool value is true (for skipping dead branches/loops)."""
        return bool(np.any(mask))
