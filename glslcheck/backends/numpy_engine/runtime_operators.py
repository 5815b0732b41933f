"""The Runtime's operators: arithmetic with Mesa's constant folding, integer division and shifts,
comparisons, logic, and the linear algebra of vectors and matrices.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .llvmpipe_reference import daz
from .runtime_state import RuntimeState
from .runtime_values import BOOL, I32, U32, Struct, lanes_of


class ArithmeticOps(RuntimeState):
    """GLSL's operators and matrix functions (a mixin of Runtime)."""

    # ------------------------------------------------------------------ arithmetic
    def add(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.add(a, b)

    def sub(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.subtract(a, b)

    def mul(self, a: Any, b: Any) -> np.ndarray:
        """Component-wise ``*`` (scalar*x, vec*vec, mat*scalar). Use ``mat_mul_*`` for the
        linear-algebra products."""
        a, b = self._pair(a, b)
        return np.multiply(a, b)

    def fmul(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Float ``a * b`` as Mesa compiles it: NIR folds ``x * 0.0`` to ``0.0`` when the zero is
        a compile-time constant (nir_opt_algebraic's inexact ``fmul(a, 0.0) -> 0.0``), so NaN or
        Inf times a constant zero component is 0 on llvmpipe (measured: ``v * vec3(1, 0, 0)``
        keeps NaN only in x; ``mix(NaN, y, 1.0)`` is y). Here a lane-uniform operand (the same
        value in every lane: a constant, or a value built from constants) with zero components
        gives 0 there. Approximation: a uniform input that happens to be 0 (iTime at t = 0)
        also folds, where llvmpipe would give NaN for a NaN or Inf other operand; uniforms
        read directly (read-only arrays, and their swizzles) do not. Only with
        ``fold_constants`` (set for transpiled shaders).

        In float32 the product of two values that are not constants is flushed to a zero of
        its sign where it is subnormal: llvmpipe runs shaders with MXCSR.FTZ
        (lp_build_fpstate_set_denorms_zero), so such a product is 0 there and a later division
        by a small value leaves it 0 (measured: tests/gl/test_llvmpipe_subnormals.py). A
        product with a constant operand is not flushed (an approximation, docs/llvmpipe.md)."""
        r = a * b
        if self.fold_constants:
            # _const_zero of (a, b) or of (b, a): one operand constant, the other not (a hot
            # path: both tests made once)
            ca, cb = self._const(a), self._const(b)
            if ca != cb:
                z = a if ca else b
                if z.size <= 16 and np.count_nonzero(z) != z.size:  # (z.all() costs 4x that)
                    r = self._zero_rows(r, z)
            elif not ca and self.lp is not None:
                r = daz(r)  # FTZ: a subnormal product is a zero of its sign there
        return r

    def _zero_rows(self, r: Any, z: np.ndarray) -> Any:
        """``np.where(z == 0, 0.0, r)`` for the product ``r`` of a lane-uniform ``z`` (shape
        (..., 1)) and a per-lane operand: r is a fresh array of the broadcast shape, so the rows
        where z is zero are set to +0.0 in place (a fill per row, not a select per lane)."""
        rows = (z == 0).reshape(z.shape[:-1])
        if type(r) is not np.ndarray or r.ndim != rows.ndim + 1 and rows.ndim != 0:
            return np.where(z == 0, self._0, r)
        if rows.ndim == 0 or r.ndim == 1:
            if rows.all():
                r[...] = self._0
            return r
        r[np.broadcast_to(rows, r.shape[:-1])] = self._0
        return r

    def fadd(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Float ``a + b`` as Mesa 22.3 compiles it for llvmpipe: nir_opt_algebraic drops an
        addition of a constant zero, ``(('fadd(is_only_used_as_float)', 'a@32', 0.0), a)``
        (GL does not ask to preserve signed zeros), so ``x + 0.0`` keeps a -0.0 that IEEE
        addition turns into +0.0 (then ``1.0 / x`` is -inf, not +inf). NIR matches each
        component after scalarising, and sees constants through inlined function arguments
        and out parameters, as `fmul`'s constant zero does here: an operand that is
        lane-uniform and not a uniform input (`_const`) counts as a constant. Measured bit for
        bit against llvmpipe in tests/gl/test_llvmpipe_lowering.py. float32 (llvmpipe) mode
        only: float64, the accuracy reference, adds as IEEE does."""
        r = a + b
        if self.lp is not None and self.fold_constants:
            for z, other in ((a, b), (b, a)):
                if self._const_zero(z, other):
                    r = np.where(z == 0, other, r)
        return r

    def fsub(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Float ``a - b`` as Mesa compiles it: llvmpipe asks for ``lower_fsub``, so it is
        ``fadd(a, fneg(b))`` and `fadd`'s rule applies: ``0.0 - x`` is ``-x`` (-0.0 for x = +0,
        measured), ``x - 0.0`` is x. float32 (llvmpipe) mode only, as `fadd`."""
        r = a - b
        if self.lp is not None and self.fold_constants:
            if self._const_zero(a, b):
                r = np.where(a == 0, -b, r)
            if self._const_zero(b, a):
                r = np.where(b == 0, a, r)
        return r

    @staticmethod
    def _const(z: np.ndarray) -> bool:
        """z may be a compile-time constant: lane-uniform and not a uniform input (read-only)."""
        return z.ndim > 0 and z.shape[-1] == 1 and z.flags.writeable

    def _const_zero(self, z: np.ndarray, other: np.ndarray) -> bool:
        """Mesa folds z * other to 0 where z is a constant zero and other is not a constant
        (two constants are multiplied out at compile time, IEEE: 0 * inf = NaN)."""
        return (
            self.fold_constants
            and self._const(z)
            and z.size <= 16
            and not self._const(other)
            and np.count_nonzero(z) != z.size
        )

    def div(self, a: Any, b: Any) -> np.ndarray:
        """``/``: float IEEE division; int truncates toward zero (x/0 = 0, INT_MIN/-1 =
        INT_MIN); uint x/0 = 0xFFFFFFFF (llvmpipe)."""
        a, b = self._pair(a, b)
        k = a.dtype.kind
        if k == "f":
            return np.divide(a, b)
        if k == "i":
            a64, b64 = a.astype(np.int64), b.astype(np.int64)
            bz = b64 == 0
            q = np.abs(a64) // np.where(bz, 1, np.abs(b64))
            q = np.where((a64 < 0) != (b64 < 0), -q, q)
            return np.where(bz, 0, q).astype(I32)
        bz = b == 0
        q = a // np.where(bz, U32(1), b)
        return np.where(bz, U32(0xFFFFFFFF), q).astype(U32)

    def rem(self, a: Any, b: Any) -> np.ndarray:
        """``%`` as llvmpipe evaluates it at run time: the UNSIGNED remainder of the 32-bit
        patterns, also for int (so -7 % 2 == 1, 7 % -2 == 7); x % 0 == 0xFFFFFFFF (-1).
        GLSL leaves negative operands undefined; non-negative operands give the C result."""
        a, b = self._pair(a, b)
        au = a.view(U32) if a.dtype == I32 else a
        bu = b.view(U32) if b.dtype == I32 else b
        bz = bu == 0
        r = np.where(bz, U32(0xFFFFFFFF), au % np.where(bz, U32(1), bu)).astype(U32)
        return r.view(I32) if a.dtype == I32 else r

    def rem_const(self, a: Any, b: Any) -> np.ndarray:
        """``%`` as Mesa's compiler folds it when both operands are compile-time constants
        (after its constant propagation): the C remainder (sign of the dividend), -7 % 2 == -1."""
        a, b = self._pair(a, b)
        if a.dtype == U32:
            return self.rem(a, b)
        a64, b64 = a.astype(np.int64), b.astype(np.int64)
        bz = b64 == 0
        r = np.fmod(a64, np.where(bz, 1, b64))
        return np.where(bz, -1, r).astype(I32)

    def neg(self, a: Any) -> np.ndarray:
        a = self._num(a) if not isinstance(a, np.ndarray) else a
        return np.negative(a)

    def pos(self, a: Any) -> Any:
        return a

    def inc(self, a: np.ndarray) -> np.ndarray:
        """``a + 1`` in a's type (for ++/--; the transpiler handles pre/post order)."""
        return np.add(a, np.asarray(1, dtype=a.dtype))

    def dec(self, a: np.ndarray) -> np.ndarray:
        return np.subtract(a, np.asarray(1, dtype=a.dtype))

    # integer bit operations -------------------------------------------------------
    @staticmethod
    def _shift_count(a: np.ndarray, b: Any) -> np.ndarray:
        b = np.asarray(b)
        if b.size == 1:  # a uniform count, usually a constant (xorshift's << 13): no array steps
            return np.array(int(b.reshape(-1)[0]) & 31, a.dtype).reshape(b.shape)
        return (b.astype(np.int64) & 31).astype(a.dtype)

    def shl(self, a: Any, b: Any) -> np.ndarray:
        """``a << b``; the count is taken mod 32 (llvmpipe: 1 << 32 == 1, 1 << -1 == INT_MIN)."""
        a = self._num(a) if not isinstance(a, np.ndarray) else a
        n = self._shift_count(a, b)
        if a.dtype == I32:
            return np.left_shift(a.view(U32), n.view(U32)).view(I32)
        return np.left_shift(a, n)

    def shr(self, a: Any, b: Any) -> np.ndarray:
        """``a >> b``: arithmetic for int, logical for uint; the count is taken mod 32."""
        a = self._num(a) if not isinstance(a, np.ndarray) else a
        return np.right_shift(a, self._shift_count(a, b))

    def bit_and(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.bitwise_and(a, b)

    def bit_or(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.bitwise_or(a, b)

    def bit_xor(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.bitwise_xor(a, b)

    def bit_not(self, a: Any) -> np.ndarray:
        a = self._num(a) if not isinstance(a, np.ndarray) else a
        return np.invert(a)

    # comparisons and logic -------------------------------------------------------
    def lt(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.less(a, b)

    def le(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.less_equal(a, b)

    def gt(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.greater(a, b)

    def ge(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.greater_equal(a, b)

    def eq(self, a: Any, b: Any) -> np.ndarray:
        """Scalar ``==`` (NaN == NaN is false). For vectors/matrices/arrays/structs use
        :meth:`equal_all`."""
        a, b = self._pair(a, b)
        return np.equal(a, b)

    def ne(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.not_equal(a, b)

    def equal_all(self, a: Any, b: Any) -> np.ndarray:
        """Aggregate ``==`` on any value (vector, matrix, array, struct): one bool per lane."""
        if isinstance(a, Struct):
            res = None
            for k, v in a._fields.items():
                e = self.equal_all(v, b._fields[k])
                res = e if res is None else res & e
            assert res is not None  # a struct has a field
            return res
        a, b = self._pair(a, b)
        e = np.equal(a, b)
        if e.ndim > 1:
            e = e.reshape(-1, e.shape[-1]).all(axis=0)
        return e

    def nequal_all(self, a: Any, b: Any) -> np.ndarray:
        return ~self.equal_all(a, b)

    @staticmethod
    def and_(a: Any, b: Any) -> np.ndarray:
        """``&&`` with both operands evaluated (the transpiler masks side effects)."""
        return np.logical_and(a, b)

    @staticmethod
    def or_(a: Any, b: Any) -> np.ndarray:
        return np.logical_or(a, b)

    @staticmethod
    def xor_(a: Any, b: Any) -> np.ndarray:
        """``^^``."""
        return np.not_equal(np.asarray(a, dtype=BOOL), np.asarray(b, dtype=BOOL))

    @staticmethod
    def not_(a: Any) -> np.ndarray:
        """``!`` on bool and the built-in ``not(bvec)``."""
        return np.logical_not(a)

    # ------------------------------------------------------------------ linear algebra
    def dot(self, a: Any, b: Any) -> np.ndarray:
        """Sum of products RIGHT to left, each rounded (no FMA), as llvmpipe:
        ``x0*y0 + (x1*y1 + (x2*y2 + x3*y3))`` (measured bit-exact on 60,000 random vec3/vec4
        pairs, constant or not; left to right matches only 56-76%). Mesa's factoring of products
        that share an operand (``dot(v, v.zxy)``: a*c + b*a -> a*(c + b)) is not copied."""
        a, b = self._f(a), self._f(b)
        if a.ndim == 1 and b.ndim == 1:
            return self.fmul(a, b)
        n = a.shape[0]
        ca, cb = (
            self._const(a),
            self._const(b),
        )  # (_const_zero of (a, b) and of (b, a), each test once)
        if (
            self.fold_constants
            and ca != cb
            and (a if ca else b).size <= 16
            and (np.count_nonzero(a if ca else b) != (a if ca else b).size)
        ):
            # a constant zero component drops its product (NIR folds x * 0.0 to 0.0), so a NaN
            # there does not reach the sum: dot(vec3(NaN, 1, 2), vec3(0, 1, 1)) = 3 on llvmpipe
            s = self.fmul(a[n - 1], b[n - 1])
            for i in range(n - 2, -1, -1):
                s = self.fmul(a[i], b[i]) + s
            return s
        # every product in one call (each rounded, as one at a time), then the sum from the
        # right, in place (t + s == s + t): n ufunc calls instead of 2n - 1
        p = np.multiply(a, b)
        if n == 1:
            return p[0]
        s = np.add(p[n - 1], p[n - 2])
        for i in range(n - 3, -1, -1):
            s += p[i]
        return s

    def ray_dot(self, x: Any, p: Any, rq: Any, ks: tuple) -> np.ndarray:
        """``dot(x, p)`` with x a constant of Mesa's and p a ray ``v * rq`` whose component i
        is the constant ``ks[i]`` times rq (None where not): those products are ``(x[i] *
        ks[i]) * rq`` (``#a * (b * #c) -> (a*c) * b``, nir_fold/ray_dots.py), the others as
        written, summed right to left as :meth:`dot`."""
        x, p = self._f(x), self._f(p)
        terms = [
            self.fmul(x[i], p[i]) if k is None else (x[i] * self._f(k)) * self._f(rq)
            for i, k in enumerate(ks)
        ]
        s = terms[-1]
        for t in terms[-2::-1]:
            s = t + s
        return s

    def dot_add(self, a: Any, b: Any, k: Any) -> np.ndarray:
        """``dot(a, b) + k`` for a constant ``k`` as Mesa compiles it (nir_fold): the constant
        joins the innermost addition, ``x0*y0 + (x1*y1 + (x2*y2 + k))``."""
        a, b = self._f(a), self._f(b)
        if a.ndim == 1 and b.ndim == 1:
            return self.fmul(a, b) + self._f(k)
        n = max(a.shape[0], b.shape[0])
        a, b = (np.broadcast_to(v, (n,) + v.shape[1:]) if v.ndim == 1 else v for v in (a, b))
        s = self.fmul(a[n - 1], b[n - 1]) + self._f(k)
        for i in range(n - 2, -1, -1):
            s = self.fmul(a[i], b[i]) + s
        return s

    def mat_mul_vec(self, m: np.ndarray, v: np.ndarray) -> np.ndarray:
        """``m * v``: matCxR (C,R,L) times vecC (C,L) -> vecR (R,L); sum of m[c]*v[c] in c order."""
        m, v = self._f(m), self._f(v)
        s = np.multiply(m[0], v[0])
        for c in range(1, m.shape[0]):
            s = np.add(s, np.multiply(m[c], v[c]))
        return s

    def vec_mul_mat(self, v: np.ndarray, m: np.ndarray) -> np.ndarray:
        """``v * m``: vecR (R,L) times matCxR (C,R,L) -> vecC; component c is dot(v, m[c])."""
        m, v = self._f(m), self._f(v)
        return self._stack([self.dot(v, m[c]) for c in range(m.shape[0])])

    def mat_mul_mat(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """``a * b``: matKxR (K,R,L) times matCxK (C,K,L) -> matCxR; column c is a * b[c]."""
        a, b = self._f(a), self._f(b)
        cols = [self.mat_mul_vec(a, b[c]) for c in range(b.shape[0])]
        lanes = lanes_of(*cols)
        out = np.empty((len(cols), a.shape[1], lanes), dtype=self.F)
        for i, col in enumerate(cols):
            out[i] = col
        return out

    def matrixCompMult(self, a: Any, b: Any) -> np.ndarray:
        return np.multiply(self._f(a), self._f(b))

    def outerProduct(self, c: np.ndarray, r: np.ndarray) -> np.ndarray:
        """``outerProduct(c, r)``: matrix with r.length() columns, m[i][j] = c[j] * r[i]."""
        c, r = self._f(c), self._f(r)
        return np.multiply(c[None, :, :], r[:, None, :])

    @staticmethod
    def transpose(m: np.ndarray) -> np.ndarray:
        return np.ascontiguousarray(np.swapaxes(m, 0, 1))

    def determinant(self, m: np.ndarray) -> np.ndarray:
        """Cofactor expansion along the first column, as Mesa's GLSL built-in."""
        m = self._f(m)
        n = m.shape[0]
        if n == 2:
            return m[0][0] * m[1][1] - m[1][0] * m[0][1]
        if n == 3:
            return (
                m[0][0] * (m[1][1] * m[2][2] - m[2][1] * m[1][2])
                - m[1][0] * (m[0][1] * m[2][2] - m[2][1] * m[0][2])
                + m[2][0] * (m[0][1] * m[1][2] - m[1][1] * m[0][2])
            )
        # 4x4: Mesa's _determinant_mat4 (2x2 sub-determinants of the lower rows)
        SubFactor00 = m[2][2] * m[3][3] - m[3][2] * m[2][3]
        SubFactor01 = m[2][1] * m[3][3] - m[3][1] * m[2][3]
        SubFactor02 = m[2][1] * m[3][2] - m[3][1] * m[2][2]
        SubFactor03 = m[2][0] * m[3][3] - m[3][0] * m[2][3]
        SubFactor04 = m[2][0] * m[3][2] - m[3][0] * m[2][2]
        SubFactor05 = m[2][0] * m[3][1] - m[3][0] * m[2][1]
        c0 = m[1][1] * SubFactor00 - m[1][2] * SubFactor01 + m[1][3] * SubFactor02
        c1 = -(m[1][0] * SubFactor00 - m[1][2] * SubFactor03 + m[1][3] * SubFactor04)
        c2 = m[1][0] * SubFactor01 - m[1][1] * SubFactor03 + m[1][3] * SubFactor05
        c3 = -(m[1][0] * SubFactor02 - m[1][1] * SubFactor04 + m[1][2] * SubFactor05)
        return m[0][0] * c0 + m[0][1] * c1 + m[0][2] * c2 + m[0][3] * c3

    def inverse(self, m: np.ndarray) -> np.ndarray:
        """Adjugate divided by the determinant (singular -> inf/NaN, as on the GPU)."""
        m = self._f(m)
        n = m.shape[0]
        if n == 2:
            det = self.determinant(m)
            adj = np.empty_like(np.broadcast_to(m, m.shape))
            adj[0][0], adj[0][1] = m[1][1], -m[0][1]
            adj[1][0], adj[1][1] = -m[1][0], m[0][0]
            return adj / det
        # general cofactor formula: inv[c][r] = cof(r, c) / det, cof on the transposed
        lanes = m.shape[-1]
        adj = np.empty((n, n, lanes), dtype=self.F)
        idx = list(range(n))
        for c in range(n):
            for r in range(n):
                cols = [i for i in idx if i != r]
                rows = [j for j in idx if j != c]
                sub = m[np.ix_(cols, rows)]
                minor = self.determinant(sub)
                adj[c][r] = minor if (r + c) % 2 == 0 else -minor
        det = self.determinant(m)
        return adj / det
