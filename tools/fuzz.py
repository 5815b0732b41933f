"""Fuzz glslcheck's command line (bad input never breaks glslcheck).

    python tools/fuzz.py --count 100000 --seed 1 [--jobs 2] [--heavy-rate 0.05] [--verify-rate 0.05]
    python tools/fuzz.py --seed 9 --show 18849          # print one input
    python tools/fuzz.py --merge a.json b.json          # combine the counts of split runs

A 100,000-input run split in two processes (2 cores) and merged:

    python tools/fuzz.py --count 50000 --start 0     --seed 9 --parse-rate 0.34 --heavy-rate 0.03 \
        --verify-rate 0.03 --json c0.json     (and --start 50000 --json c50000.json)
    python tools/fuzz.py --merge c0.json c50000.json

A long run of mixed and hostile inputs under a memory limit, in the background on a
shared machine (it checkpoints to --json after every chunk of CHUNK inputs, stops cleanly at
--max-seconds or on SIGTERM with the counts so far, and --resume continues it):

    ulimit -v 8000000; GLSLCHECK_FUZZ_NICE=0 nohup nice -n 10 python tools/fuzz.py --count 100000 \
        --seed 16 --jobs 2 --parse-rate 0.34 --heavy-rate 0.03 --verify-rate 0.03 \
        --hostile-rate 0.05 --max-seconds 5000 --json run.json [--resume run.json] \
        > fuzz.log 2>&1 &

Run on 2026-12-01 (2 cores shared by 8 agents, load average 8 to 25, 92
minutes, stopped by --max-seconds): 21,163 of the 100,000 inputs (mutate 11,029, generate 5,075,
soup 2,456, bytes 1,579, hostile 1,024; transpile 6,910, render 2,105, verify 177), 0 flagged.
Its throughput is benchmarks/bench_fuzz.py's: the harness adds nothing measurable to the cost
of the commands themselves (about 9 inputs per CPU second with these rates).

Inputs, each reproducible from (seed, index) alone:

- mutate:   token-level mutations of tests/corpus, lab_shaders, tests/hard_cases,
            tests/check/invalid and the lint fixtures (whole files or a few top-level
            declarations): delete, duplicate, swap and insert tokens, repeat or wrap a span
            (deep nesting), insert random bytes (NUL, BOM, CR, non-ASCII, invalid UTF-8),
            replace numbers by extreme ones; sometimes as a folder with a Common tab;
- generate: random *valid* GLSL ES 3.00 Shadertoy shaders from a small typed grammar
            (functions with in/out/inout parameters, structs, arrays, loops, branches on
            uniform values, built-ins); `parse` and `check` must accept them and, on a sample,
            `verify` must find the NumPy and OpenGL images equal;
- hostile:  valid programs at the limits (--hostile-rate of the inputs, drawn from a
            separate random stream so the other inputs of a seed stay the same): statements
            nested up to 250 deep (if/else/loops/switch/blocks), 40 nested loops, else-if
            chains, 900 nested parentheses, 300 nested ternaries and &&/||, sums of 3000
            terms, local arrays up to 4,000,000 floats, runaway nested loops of 99,999
            iterations, 300-deep call chains; parse and check must accept them, transpile
            and render (8x8, frame budget FRAME_SECONDS) end ok or with a located error;
- channels: folders with an Image tab and often a Buffer A sampling iChannel0..1, small images
            (PNG, JPEG, TIFF of odd sizes and modes) and a channels.json (--channels-rate, its
            own random stream too): "channels" binds everything validly with every filter, wrap
            and vflip (render must succeed and verify match), "channels-bad" carries faults
            (wrong types, unknown tabs and keys, names outside the folder, cycles, damaged
            images, cut or deeply nested JSON: a located error and exit 2, never a traceback);
- soup:     random sequences of GLSL tokens;
- bytes:    random bytes.

Each input goes through every entry point in-process via `glslcheck.cli.main.main` with stdout
and stderr captured: parse, check and lint always; transpile when check accepts the program (and
on a sample of the rest); render and verify at 8x8 on samples; `compiled` (render --backend
compiled, numba's engine, with the frame budget) on --compiled-rate of the programs check
accepts. --jobs worker processes (spawned once per run, each with a 3 GB address-space limit)
run the inputs; the parent kills and restarts one when a command exceeds its time budget (CPU
seconds of the worker).

Flagged outcomes (anything but ok / findings / usage): `exception` (escaped main), `traceback`
(in the output), `bad-exit` (not 0, 1 or 2), `timeout`, `no-location` (an error message without
file:line:col in one of the input's files, or an exit 1 that printed no error), `bad-location`
(a line outside the file), `modified` (a command changed the input file), `gen-rejected`
(a generated program that parse/check refuse), `mismatch` (a generated program that verify
finds different; a mutant's mismatch is a finding: it may compute undefined values).
Flagged inputs are written to --out with a note. Prints counts per entry point and outcome;
exits 1 when anything was flagged.
"""

from __future__ import annotations

import argparse
import collections
import contextlib
import functools
import io
import json
import multiprocessing as mp
import os
import random
import re
import shutil
import sys
import tempfile
import time
import traceback
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

LIGHT = ("parse", "check", "lint")
HEAVY = ("transpile", "render", "verify", "compiled")
NORMAL = {"ok", "findings", "usage"}
# Per-command time budgets in seconds: generous, the machine is shared (a typical call takes
# 10-100 ms; render/verify at 8x8 under a second). --timeout-scale multiplies them.
BUDGET = {
    "parse": 20,
    "check": 20,
    "lint": 20,
    "transpile": 30,
    "render": 60,
    "verify": 60,
    "compiled": 180,  # `render --backend compiled`: numba compiles the shader first
}
FRAME_SECONDS = 10  # the NumPy renderer's frame budget in the workers (GLSLCHECK_FRAME_SECONDS)
# ... and of a hostile program's render (its --frame-budget): the runaway loops run to it, so it
# bounds their wall time. The largest other hostile renders take up to 2 s of CPU at 8x8: on a
# loaded machine some of them stop too, which is an outcome they may have (a located error).
HOSTILE_FRAME_SECONDS = 2
CHUNK = 100  # inputs per chunk: a worker's unit of work, and of --json checkpoints
WALL_FACTOR = 10  # a command blocked (no CPU used) this many budgets long is a timeout too

# ---------------------------------------------------------------------------------------------
# Seeds and tokens

TOKEN_RE = re.compile(
    r"//[^\n]*|/\*.*?\*/|#[^\n]*|[A-Za-z_]\w*|\d+\.?\d*(?:[eE][+-]?\d+)?[uUfF]?|\.\d+(?:[eE][+-]?\d+)?"
    r"|<<=|>>=|\+\+|--|<<|>>|<=|>=|==|!=|&&|\|\||\^\^|[-+*/%&|^]=|\s+|.",
    re.S,
)

POOL = (
    "void float int uint bool vec2 vec3 vec4 ivec2 ivec3 bvec2 uvec4 mat2 mat3 mat4 mat2x3 "
    "sampler2D struct in out inout const uniform highp mediump lowp precision if else for while do "
    "switch case default break continue return discard true false mainImage main fragColor "
    "fragCoord iTime iResolution iMouse iFrame iChannel0 texture sin cos pow sqrt normalize length "
    "dot cross mix clamp smoothstep step fract floor mod abs min max atan exp log inversesqrt "
    "reflect refract ; ; , , . ( ) ( ) { } { } [ ] = += -= *= /= %= <<= |= + - * / % < > <= >= == "
    "!= && || ^^ ! ~ ? : ++ -- 0 1 2 0.0 1.0 .5 1e38 3.4e39 1e-45 0x7fffffff 0xffffffff "
    "4294967295u 2147483648 99999999999 007 08 1.0f x y z w xyzw rgba stpq xx xyzwxyzw a b S s i j "
    "k __LINE__ __FILE__ __VERSION__ GL_ES #define #undef #if #ifdef #ifndef #else #elif #endif "
    "#error #pragma #extension #version "
    "#line defined M(x) x## /* */ // \\"
).split() + ["\n", "\n", " ", "\t", "\r\n", "\r", '"', "'", "@", "$", "`"]

ODD_BYTES = [
    b"\x00",
    b"\xef\xbb\xbf",
    b"\r",
    b"\r\n",
    b"\t",
    b"\xff",
    b"\xc3",
    b"\xe2\x80\x8b",
    "é".encode(),
    "日本".encode(),
    "😀".encode(),
    b"\x0b",
    b"\x0c",
    b"\\\n",
    b"\x7f",
]

EXTREME_NUMBERS = [
    "0",
    "0.0",
    "-0.0",
    "1e38",
    "3.5e38",
    "1e-45",
    "1e-50",
    "2147483647",
    "2147483648",
    "4294967295u",
    "4294967296u",
    "0xffffffff",
    "0x100000000",
    "99999999999999999999",
    "1e999",
    "100000",
    "65536",
    "-2147483648",
    "1000000000",
]


@functools.lru_cache(maxsize=1)
def seeds_and_pool() -> tuple[list[dict[str, str]], list[str]]:
    """The seed programs and the token pool of insertions, read once per process (every chunk
    of a run used to read and tokenise the whole corpus again)."""
    seeds = seed_files()
    pool = (
        POOL
        + sorted(
            {
                t
                for s in seeds
                for text in s.values()
                for t in tokens(text)
                if re.fullmatch(r"[A-Za-z_]\w*", t)
            }
        )[:400]
    )
    return seeds, pool


def seed_files() -> list[dict[str, str]]:
    """Seed programs: {tab file name: text}; a lab folder with a Common tab gives both files."""
    seeds: list[dict[str, str]] = []
    for folder in sorted((ROOT / "lab_shaders").iterdir()):
        if folder.is_dir():
            files = {f.name: f.read_text(encoding="utf-8") for f in sorted(folder.glob("*.glsl"))}
            if files:
                seeds.append(files)
    patterns = [
        "tests/corpus/*",
        "tests/hard_cases/*.glsl",
        "tests/check/invalid/*.glsl",
        "tests/lint/fixtures/**/*.glsl",
    ]
    for pattern in patterns:
        for f in sorted(ROOT.glob(pattern)):
            if f.is_file() and f.suffix in (".glsl", ".frag"):
                try:
                    seeds.append({"shader" + f.suffix: f.read_text(encoding="utf-8")})
                except UnicodeDecodeError:
                    continue
    return seeds


def tokens(text: str) -> list[str]:
    return TOKEN_RE.findall(text)


def _declarations(toks: list[str]) -> list[tuple[int, int]]:
    """Spans of top-level declarations (up to a `;` or a closing `}` at depth 0)."""
    spans, depth, start = [], 0, 0
    for i, t in enumerate(toks):
        if t == "{":
            depth += 1
        elif t == "}":
            depth = max(depth - 1, 0)
            if depth == 0:
                spans.append((start, i + 1))
                start = i + 1
        elif t == ";" and depth == 0:
            spans.append((start, i + 1))
            start = i + 1
    if start < len(toks):
        spans.append((start, len(toks)))
    return spans


def mutate_text(rng: random.Random, text: str, pool: list[str]) -> bytes:
    toks = tokens(text)
    if rng.random() < 0.6:  # a few top-level declarations only: small inputs, fast runs
        spans = _declarations(toks)
        if len(spans) > 3:
            a = rng.randrange(len(spans))
            b = min(len(spans), a + rng.randint(1, 3))
            toks = toks[spans[a][0] : spans[b - 1][1]]
    parts: list[str | bytes] = list(toks)
    for _ in range(rng.choice((1, 1, 1, 2, 2, 3, 5))):
        n = len(parts)
        op = rng.random()
        i = rng.randrange(n) if n else 0
        if n == 0:
            parts.append(rng.choice(pool))
        elif op < 0.20:  # delete a token or a short span
            del parts[i : i + rng.choice((1, 1, 1, 2, 5))]
        elif op < 0.35:  # duplicate
            j = min(n, i + rng.choice((1, 1, 3, 10)))
            parts[i:i] = parts[i:j]
        elif op < 0.45:  # swap two tokens
            j = rng.randrange(n)
            parts[i], parts[j] = parts[j], parts[i]
        elif op < 0.70:  # insert a token
            parts.insert(i, rng.choice(pool) if rng.random() < 0.8 else rng.choice(toks or ["x"]))
        elif op < 0.80:  # insert bytes
            parts.insert(
                i,
                rng.choice(ODD_BYTES)
                if rng.random() < 0.7
                else bytes(rng.randrange(256) for _ in range(rng.randint(1, 4))),
            )
        elif op < 0.87:  # replace a number by an extreme one
            nums = [k for k, t in enumerate(parts) if isinstance(t, str) and t[:1].isdigit()]
            if nums:
                parts[rng.choice(nums)] = rng.choice(EXTREME_NUMBERS)
        elif op < 0.94:  # repeat a span many times (long chains, many functions)
            j = min(n, i + rng.randint(1, 20))
            parts[i:j] = parts[i:j] * rng.choice((10, 50, 200))
        else:  # wrap a span in k brackets (deep nesting)
            j = min(n, i + rng.randint(1, 10))
            o, c = rng.choice((("(", ")"), ("{", "}"), ("[", "]")))
            k = rng.choice((10, 100, 600))
            parts[i:j] = [o * k] + parts[i:j] + [c * k]
    return b"".join(p if isinstance(p, bytes) else p.encode("utf-8") for p in parts)


# ---------------------------------------------------------------------------------------------
# Random valid programs

FLOATS = ("float", "vec2", "vec3", "vec4")
SIZE = {"float": 1, "vec2": 2, "vec3": 3, "vec4": 4}
VEC = {1: "float", 2: "vec2", 3: "vec3", 4: "vec4"}


class ProgramGenerator:
    """Random valid Shadertoy programs whose values stay bounded and whose branches depend only
    on uniforms, constants and loop counters, so both backends compute the same image (no
    division, no pow/log of negatives, no pixel-dependent comparisons)."""

    def __init__(self, rng: random.Random):
        self.rng = rng
        self.n = 0
        self.funcs: list[tuple[str, str, list[tuple[str, str]]]] = []  # (name, ret, [(qual, type)])
        self.structs: list[tuple[str, list[tuple[str, str]]]] = []

    def name(self, prefix: str) -> str:
        self.n += 1
        return f"{prefix}{self.n}"

    def lit(self) -> str:
        v = f"{self.rng.uniform(-1.5, 1.5):.3f}"
        return f"({v})" if v.startswith("-") else v  # never `--0.5` after a unary minus

    # Expressions: scope = list of (name, type); ints = int names (loop counters, constants).
    def expr(self, t: str, scope, ints, depth: int) -> str:
        r = self.rng
        vars_t = [v for v, vt in scope if vt == t]
        if depth <= 0 or r.random() < 0.2:
            choices = []
            if vars_t:
                choices += [lambda: r.choice(vars_t)] * 3
            bigger = [
                (v, vt) for v, vt in scope if vt in FLOATS and SIZE[vt] >= SIZE[t] and vt != "float"
            ]
            if bigger and t != "vec4":

                def swz():
                    v, vt = r.choice(bigger)
                    return v + "." + "".join(r.choice("xyzw"[: SIZE[vt]]) for _ in range(SIZE[t]))

                choices.append(swz)
            if t == "float":
                choices += [self.lit, lambda: "(0.1 * iTime)"]
                if ("uv", "vec2") in scope:
                    choices += [lambda: "uv.x", lambda: "uv.y"]
                if ints:
                    choices.append(lambda: f"(0.25 * float({r.choice(ints)}))")
                for s, fields in self.structs:
                    for v, vt in scope:
                        if vt == s:
                            fl = [f for f, ft in fields if ft == "float"]
                            if fl:
                                choices.append(lambda v=v, f=fl[0]: f"{v}.{f}")
            else:
                k = SIZE[t]
                choices.append(lambda: f"{t}({', '.join(self.lit() for _ in range(k))})")
                choices.append(lambda: f"{t}({self.expr('float', scope, ints, 0)})")
                if k == 2 and ("uv", "vec2") in scope:
                    choices.append(lambda: "uv")
            return r.choice(choices)()
        d = depth - 1
        e = lambda tt=t: self.expr(tt, scope, ints, d)  # noqa: E731
        opts = [
            lambda: f"({e()} + {e()})",
            lambda: f"({e()} - {e()})",
            lambda: f"({e()} * clamp({e()}, -1.0, 1.0))",
            lambda: f"(0.5 * {e()})",
            lambda: f"sin({e()})",
            lambda: f"cos({e()})",
            lambda: f"abs({e()})",
            lambda: f"min({e()}, {e()})",
            lambda: f"max({e()}, {e()})",
            lambda: f"clamp({e()}, -1.0, 1.0)",
            lambda: f"mix({e()}, {e()}, clamp({e('float')}, 0.0, 1.0))",
            lambda: f"exp(-abs({e()}))",
            lambda: f"sqrt(abs({e()}) + 0.25)",
            lambda: f"smoothstep(-1.0, 1.0, {e()})",
            lambda: f"(-{e()})",
        ]
        if t == "float":

            def dot_():
                vt = r.choice(FLOATS[1:])
                return f"dot({self.expr(vt, scope, ints, d)}, {self.expr(vt, scope, ints, d)})"

            opts += [dot_, lambda: f"length({self.expr(r.choice(FLOATS[1:]), scope, ints, d)})"]
        else:
            opts.append(lambda: f"({e()} * clamp({e('float')}, -1.0, 1.0))")
            if t == "vec3":
                opts.append(lambda: f"cross({e()}, {e()})")
        if ints:
            c = self.cond(ints)
            opts.append(lambda: f"({c} ? {e()} : {e()})")
        calls = [f for f in self.funcs if f[1] == t and all(q == "in" for q, _ in f[2])]
        if calls:

            def call():
                name, _, params = r.choice(calls)
                return f"{name}({', '.join(self.expr(pt, scope, ints, d) for _, pt in params)})"

            opts.append(call)
        return r.choice(opts)()

    def cond(self, ints) -> str:
        r = self.rng
        return r.choice(
            [
                lambda: f"({r.choice(ints)} > {r.randint(0, 3)})",
                lambda: f"({r.choice(ints)} % 2 == 0)",
                lambda: f"(iTime < {r.uniform(0, 2):.2f})",
                lambda: f"(iFrame >= {r.randint(0, 2)})",
                lambda: f"({r.choice(ints)} != {r.randint(0, 3)} && iTime >= 0.0)",
            ]
        )()

    def block(
        self, scope, ints, depth: int, indent: str, out: list[str], ret: str | None = None
    ) -> None:
        r = self.rng
        scope = list(scope)
        for _ in range(r.randint(1, 4)):
            k = r.random()
            writable = [
                (v, vt) for v, vt in scope if not v.startswith(("uv", "K")) and vt in FLOATS
            ]
            if k < 0.35 or not writable:
                t = r.choice(FLOATS)
                v = self.name("v")
                out.append(f"{indent}{t} {v} = {self.expr(t, scope, ints, 3)};")
                scope.append((v, t))
            elif k < 0.55:
                v, t = r.choice(writable)
                if v.startswith("g") and r.random() < 0.5:  # a global advanced by a constant
                    out.append(f"{indent}{r.choice([f'{v} += {self.lit()}', f'{v}++'])};")
                    continue
                op = r.choice(["=", "+=", "-=", "*="])
                rhs = self.expr(t, scope, ints, 3)
                out.append(f"{indent}{v} {op} {rhs};")
                if op != "=":
                    out.append(f"{indent}{v} = clamp({v}, -4.0, 4.0);")
            elif k < 0.7 and depth > 0:
                i = self.name("i")
                n = r.randint(1, 4)
                out.append(f"{indent}for (int {i} = 0; {i} < {n}; {i}++) {{")
                self.block(scope, ints + [i], depth - 1, indent + "    ", out)
                out.append(f"{indent}}}")
            elif k < 0.82 and depth > 0 and ints + ["iFrame"]:
                out.append(f"{indent}if {self.cond(ints or ['iFrame'])} {{")
                self.block(scope, ints, depth - 1, indent + "    ", out)
                if r.random() < 0.5:
                    out.append(f"{indent}}} else {{")
                    self.block(scope, ints, depth - 1, indent + "    ", out)
                out.append(f"{indent}}}")
            elif k < 0.9:
                outs = [f for f in self.funcs if any(q != "in" for q, _ in f[2])]
                if outs and writable:
                    name, rt, params = r.choice(outs)
                    args: list[str] = []
                    for q, pt in params:
                        # distinct out/inout arguments: GLSL leaves the copy-out order undefined
                        cands = [v for v, vt in writable if vt == pt and v not in args]
                        if q != "in" and not cands:
                            v = self.name("v")
                            out.append(f"{indent}{pt} {v} = {self.expr(pt, scope, ints, 1)};")
                            scope.append((v, pt))
                            cands = [v]
                        args.append(r.choice(cands) if q != "in" else self.expr(pt, scope, ints, 2))
                    call = f"{name}({', '.join(args)})"
                    out.append(
                        f"{indent}{call};"
                        if rt == "void"
                        else f"{indent}{rt} {self.name('r')} = {call};"
                    )
            else:
                a = self.name("a")
                t = r.choice(("float", "vec3"))
                n = r.randint(2, 4)
                out.append(
                    f"{indent}{t} {a}[{n}] = "
                    f"{t}[{n}]({', '.join(self.expr(t, scope, ints, 2) for _ in range(n))});"
                )
                idx = f"{r.choice(ints)} % {n}" if ints else str(r.randrange(n))
                v = self.name("v")
                out.append(f"{indent}{t} {v} = {a}[{idx}];")
                scope.append((v, t))
        if ret is not None:
            out.append(f"{indent}return {self.expr(ret, scope, ints, 3)};")

    def program(self) -> str:
        r = self.rng
        out = ["// generated by tools/fuzz.py"]
        scope: list[tuple[str, str]] = []
        for _ in range(r.randint(0, 2)):
            k = self.name("K")
            t = r.choice(FLOATS)
            init = (
                self.lit()
                if t == "float"
                else f"{t}({', '.join(self.lit() for _ in range(SIZE[t]))})"
            )
            out.append(f"const {t} {k} = {init};")
            scope.append((k, t))
        for _ in range(r.randint(0, 2) if r.random() < 0.5 else 0):
            # a global the functions change (a counter or a seed), initialized or not
            g = self.name("g")
            out.append(f"float {g}{f' = {self.lit()}' if r.random() < 0.5 else ''};")
            scope.append((g, "float"))
        if r.random() < 0.5:
            s = self.name("S")
            fields = [(f"f{j}", r.choice(FLOATS)) for j in range(r.randint(1, 3))]
            out.append(f"struct {s} {{ " + " ".join(f"{ft} {f};" for f, ft in fields) + " };")
            self.structs.append((s, fields))
        for _ in range(r.randint(0, 3)):
            name = self.name("fn")
            rt = r.choice(FLOATS + ("void",))
            params = [
                (r.choice(("in", "in", "out", "inout")), r.choice(FLOATS))
                for _ in range(r.randint(1, 3))
            ]
            if rt == "void" and all(q == "in" for q, _ in params):
                params[0] = ("out", params[0][1])
            pnames = [(f"p{j}", pt) for j, (_, pt) in enumerate(params)]
            out.append(
                f"{rt if rt != 'void' else 'void'} {name}("
                + ", ".join(f"{q} {pt} p{j}" for j, (q, pt) in enumerate(params))
                + ") {"
            )
            body: list[str] = []
            # out parameters are written first so they are never read uninitialised.
            for j, (q, pt) in enumerate(params):
                if q == "out":
                    body.append(f"    p{j} = {self.expr(pt, [], [], 1)};")
            self.block(scope + pnames, [], 2, "    ", body, None if rt == "void" else rt)
            out += body
            out.append("}")
            self.funcs.append((name, rt, params))
        out.append("void mainImage(out vec4 fragColor, in vec2 fragCoord) {")
        out.append("    vec2 uv = fragCoord / iResolution.xy;")
        body = []
        local = scope + [("uv", "vec2")]
        for s, fields in self.structs:
            v = self.name("s")
            body.append(
                f"    {s} {v} = {s}("
                + ", ".join(self.expr(ft, local, [], 2) for _, ft in fields)
                + ");"
            )
            local.append((v, s))
        self.block(local, [], 3, "    ", body)
        out += body
        out.append(f"    vec3 col = {self.expr('vec3', local, [], 3)};")
        out.append("    fragColor = vec4(0.5 + 0.5 * sin(col), 1.0);")
        out.append("}")
        return "\n".join(out) + "\n"


def random_program(rng: random.Random) -> str:
    return ProgramGenerator(rng).program()


# ---------------------------------------------------------------------------------------------
# Valid but hostile programs: deep nesting, long chains, huge arrays, runaway loops

MAIN = "void mainImage(out vec4 fragColor, in vec2 fragCoord) {\n"


def _cond(rng: random.Random, k: int) -> str:
    """A condition that varies across pixels (fragCoord) or is the same for all (iTime)."""
    return rng.choice(
        (
            f"fragCoord.x > {k % 9}.5",
            f"fragCoord.y < {k % 7}.0",
            f"iTime > {k % 5}.0",
            f"x < {k % 11}.0",
        )
    )


def _nest_statements(rng: random.Random, depth: int) -> str:
    """`depth` statements nested in each other, of mixed kinds (loops kept to a few iterations)."""
    head, tail = [], []
    loops = 0
    for k in range(depth):
        kind = rng.choice(("if", "if", "block", "for", "while", "switch", "else"))
        if kind in ("for", "while") and loops >= 12:
            kind = "if"  # 2**12 iterations at most
        if kind == "if":
            head.append(f"if ({_cond(rng, k)}) {{ x += 0.5; ")
            tail.append("}")
        elif kind == "else":
            head.append(f"if ({_cond(rng, k)}) {{ x -= 0.25; }} else {{ ")
            tail.append("}")
        elif kind == "block":
            head.append("{ ")
            tail.append("}")
        elif kind == "for":
            loops += 1
            head.append(
                f"for (int i{k} = 0; i{k} < {rng.choice((1, 2))}; i{k}++) {{ x += 1.0; "
                + (f"if ({_cond(rng, k)}) continue; " if rng.random() < 0.3 else "")
            )
            tail.append(f"{'if (fragCoord.x < 3.0) break; ' if rng.random() < 0.3 else ''}}}")
        elif kind == "while":
            loops += 1
            head.append(f"int w{k} = 0; while (w{k} < {rng.choice((1, 2))}) {{ w{k}++; ")
            tail.append("}")
        else:
            head.append("switch (int(fragCoord.x) % 3) { case 0: x += 1.0; case 1: { ")
            tail.append("} break; default: x -= 1.0; }")
    body = (
        "".join(head)
        + "x += 1.0; "
        + ("if (fragCoord.y > 5.0) return; " if rng.random() < 0.2 else "")
    )
    return body + " ".join(reversed(tail))


HOSTILE_SHAPES = (
    "nest",
    "loops",
    "elseif",
    "parens",
    "ternary",
    "andand",
    "sum",
    "array",
    "runaway",
    "calls",
    "switch",
)


def hostile_program(rng: random.Random, shape: str | None = None) -> str:
    """A program `check` accepts that pushes the transpiler and the renderer to their limits:
    transpile and render must succeed or stop with a located error, never crash, hang or run
    out of memory. `shape`: one of HOSTILE_SHAPES (default: a random one, "nest" twice as often)."""
    shape = shape or rng.choice(HOSTILE_SHAPES + ("nest",))
    n = rng.choice((10, 20, 30, 60, 100, 200, 300))
    pre = ""
    body = "float x = fragCoord.x * 0.1;\n"
    if shape == "nest":
        body += _nest_statements(rng, min(n, 250))
    elif shape == "loops":  # the first loops run once: 2**10 iterations at most
        m = min(n, 40)
        body += "".join(
            f"for (int i{k} = 0; i{k} < {2 if k >= m - 10 else 1}; i{k}++) {{ " for k in range(m)
        )
        body += (
            "x += 1.0; "
            + ("if (fragCoord.x < 4.0) break; " if rng.random() < 0.5 else "")
            + "}" * m
        )
    elif shape == "elseif":
        body += "if (x < 0.0) x = 0.0;" + "".join(
            f" else if ({rng.choice(('x', 'iTime', 'fragCoord.y'))} < {k}.0) x += {k}.0;"
            for k in range(1, n)
        )
        body += " else x = 1.0;"
    elif shape == "parens":
        op = rng.choice(("+", "*", "-"))
        body += "x = " + f"fragCoord.x {op} (" * (n * 3) + "1.0" + ")" * (n * 3) + ";"
    elif shape == "ternary":
        e = "x"
        for k in range(n):
            side = f"(x += {k % 3}.0)" if rng.random() < 0.2 else f"{k}.0"
            e = (
                f"({_cond(rng, k)} ? {e} : {side})"
                if rng.random() < 0.5
                else f"({_cond(rng, k)} ? {side} : {e})"
            )
        body += f"x = {e};"
    elif shape == "andand":
        ops = [rng.choice(("&&", "||")) for _ in range(n)]
        body += (
            "bool b = "
            + "".join(f"({_cond(rng, k)} {ops[k]} " for k in range(n))
            + "true"
            + ")" * n
            + ";"
        )
        body += " x += b ? 1.0 : 0.0;"
    elif shape == "sum":
        body += "x = " + " + ".join(f"sin(x * {k % 13}.0)" for k in range(n * 10)) + ";"
    elif shape == "array":
        size = rng.choice((1000, 65536, 100000, 1000000, 4000000))
        body += (
            f"float a[{size}];\na[int(fragCoord.x) % {size}] = 1.0;\n"
            f"x += a[int(fragCoord.y) % {size}] + a[{size - 1}];"
        )
    elif shape == "runaway":
        m = rng.choice((2, 3))
        body += (
            "".join(f"for (int r{k} = 0; r{k} < 99999; r{k}++) {{ " for k in range(m))
            + "x += 1.0; "
            + "}" * m
        )
    elif shape == "calls":
        pre = "float f0(float v) { return v * 0.5; }\n" + "".join(
            f"float f{k}(float v) {{ return f{k - 1}(v) + {k % 3}.0; }}\n" for k in range(1, n)
        )
        body += f"x = f{n - 1}(x);"
    else:  # switch
        m = min(n, 100)
        body += "int s = int(fragCoord.x) % 4;\n" + "switch (s) { case 0: x += 1.0; case 1: { " * m
        body += "x *= 2.0;" + " } break; default: x -= 1.0; }" * m
    return pre + MAIN + body + "\nfragColor = vec4(vec3(fract(x * 0.01)), 1.0);\n}\n"


# ---------------------------------------------------------------------------------------------
# Inputs


HOSTILE_RATE = 0.05  # share of inputs replaced by hostile programs (the others stay as they were)
CHANNELS_RATE = 0.05  # share of inputs replaced by channel folders (from their own stream too)

CHANNEL_IMAGE = (
    "void mainImage(out vec4 fragColor, in vec2 fragCoord) {\n"
    "    vec2 uv = fragCoord / iResolution.xy;\n"
    "    fragColor = texture(iChannel0, uv) + texture(iChannel1, uv * 2.0);\n"
    "}\n"
)
CHANNEL_BUFFER = (
    "void mainImage(out vec4 fragColor, in vec2 fragCoord) {\n"
    "    vec2 uv = fragCoord / iResolution.xy;\n"
    "    fragColor = 0.5 * texture(iChannel0, uv) + vec4(uv, sin(iTime), 1.0);\n"
    "}\n"
)
# Texture names a channels.json may give: the folder's own files, and names that leave it.
TEXTURE_NAMES = ("tex.png", "tex.jpg", "missing.png", "../tex.png", "/etc/passwd", "", "sub/t.png")
CHANNEL_VALUES = (
    None, 0, -1, 1.5, True, "", "nearest", "mipmap", "repeat", "clamp", [], {}, [1, 2],
    {"buffer": "Buffer A"}, "x" * 300,
)  # fmt: skip


def _image_bytes(rng: random.Random, damage: bool) -> bytes:
    """A small image file: a PNG, JPEG or TIFF of an odd size and mode; with `damage`, sometimes
    cut short or with a byte changed."""
    from PIL import Image

    w, h = rng.choice((1, 2, 3, 17, 64)), rng.choice((1, 2, 5, 33))
    mode = rng.choice(("RGB", "RGBA", "L", "LA", "P", "I;16", "F"))
    fmt = "JPEG" if mode in ("RGB", "L") and rng.random() < 0.3 else "PNG"
    if mode == "F":
        fmt = "TIFF"
    image = Image.frombytes("L", (w, h), bytes(rng.randrange(256) for _ in range(w * h))).convert(
        mode
    )
    buf = io.BytesIO()
    image.save(buf, fmt)
    data = buf.getvalue()
    if damage and rng.random() < 0.2:
        cut = rng.randrange(len(data))
        data = (
            data[:cut]
            if rng.random() < 0.5
            else data[:cut] + bytes([rng.randrange(256)]) + data[cut + 1 :]
        )
    return data


def channels_input(rng: random.Random) -> tuple[str, dict[str, bytes]]:
    """A folder with an Image tab (and often a Buffer A) sampling iChannel0..1, images, and a
    channels.json that binds them: valid bindings with every filter, wrap and vflip, and values
    of the wrong type, names that leave the folder, unknown tabs and keys, cycles, bad JSON."""
    valid = rng.random() < 0.7  # most folders are valid, the rest carry faults
    files = {"Image.glsl": CHANNEL_IMAGE.encode()}
    if rng.random() < 0.6:
        files["Buffer A.glsl"] = CHANNEL_BUFFER.encode()
    if valid or rng.random() < 0.8:
        files["tex.png"] = _image_bytes(rng, damage=not valid)

    def binding() -> object:
        if valid:
            spec: dict[str, object] = (
                {"buffer": "Buffer A"}
                if "Buffer A.glsl" in files and rng.random() < 0.5
                else {"texture": "tex.png"}
            )
            for key, values in (
                ("filter", ("nearest", "linear", "mipmap")),
                ("wrap", ("clamp", "repeat")),
                ("vflip", (True, False)),
            ):
                if rng.random() < 0.5:
                    spec[key] = rng.choice(values)
            return spec
        x = rng.random()
        if x < 0.15:
            return rng.choice(CHANNEL_VALUES)
        spec = (
            {"buffer": rng.choice(("Buffer A", "Buffer B", "Image", "buffer a", 3))}
            if x < 0.5
            else {"texture": rng.choice(TEXTURE_NAMES)}
        )
        for key, values in (
            ("filter", ("nearest", "linear", "mipmap", "trilinear", 1)),
            ("wrap", ("clamp", "repeat", "mirror", None)),
            ("vflip", (True, False, "yes")),
            ("type", ("cubemap", "2d")),
        ):
            if rng.random() < 0.4:
                spec[key] = rng.choice(values)
        return spec

    tabs = {}
    for tab in ("Image", "Buffer A", "Buffer Z", "Common"):
        if tab == "Image" or (tab == "Buffer A" and "Buffer A.glsl" in files):
            # a valid folder binds every channel its tabs read; a faulty one may leave one out
            tabs[tab] = {f"iChannel{n}": binding() for n in (0, 1) if valid or rng.random() < 0.8}
        elif not valid and rng.random() < 0.1:
            tabs[tab] = {f"iChannel{rng.choice((0, 1, 4))}": binding()}
    text = json.dumps(tabs)
    y = 1.0 if valid else rng.random()
    if y < 0.05:
        text = text[: rng.randrange(len(text) + 1)]  # cut short
    elif y < 0.08:
        text = "[" * 5000 + "]" * 5000  # deep
    elif y < 0.1:
        text = json.dumps(rng.choice(CHANNEL_VALUES))
    files["channels.json"] = text.encode()
    return ("channels" if valid else "channels-bad"), files


def make_input(
    seed: int,
    index: int,
    seeds: list[dict[str, str]],
    pool: list[str],
    hostile_rate: float = HOSTILE_RATE,
    channels_rate: float = CHANNELS_RATE,
) -> tuple[str, dict[str, bytes]]:
    """(kind, {file name: bytes}) for input `index` of run `seed`."""
    pick = random.Random(f"{seed}:{index}:hostile")
    if pick.random() < hostile_rate:
        return "hostile", {"shader.glsl": hostile_program(pick).encode()}
    chan = random.Random(f"{seed}:{index}:channels")
    if chan.random() < channels_rate:
        return channels_input(chan)
    rng = random.Random(f"{seed}:{index}")
    x = rng.random()
    if x < 0.55:
        files = rng.choice(seeds)
        if len(files) > 1 and rng.random() < 0.3:  # a folder with Common + Image, one mutated
            target = rng.choice(sorted(files))
            return "mutate", {
                n: (mutate_text(rng, t, pool) if n == target else t.encode())
                for n, t in files.items()
            }
        name = "Image.glsl" if "Image.glsl" in files else next(iter(files))
        return "mutate", {
            "shader.glsl" if name != "shader.frag" else name: mutate_text(rng, files[name], pool)
        }
    if x < 0.80:
        return "generate", {"shader.glsl": random_program(rng).encode()}
    if x < 0.92:
        n = rng.choice((1, 5, 20, 100, 400))
        return "soup", {"shader.glsl": " ".join(rng.choice(pool) for _ in range(n)).encode()}
    n = rng.choice((0, 1, 8, 64, 512))
    data = bytes(rng.randrange(256) for _ in range(n))
    if rng.random() < 0.5:  # mostly ASCII with a few odd bytes: gets past the UTF-8 check
        data = bytes(b & 0x7F for b in data)
    return "bytes", {"shader.glsl": data}


# ---------------------------------------------------------------------------------------------
# Running one command in-process and judging its output

LOC_RE = re.compile(r"^(?P<path>.+?):(?P<line>\d+):(?P<col>\d+):? ")


def _line_lengths(data: bytes) -> list[int]:
    text = data.decode("utf-8", "replace")
    if text.startswith("\ufeff"):
        text = text[1:]
    text = text.replace("\r\n", "\n").replace("\r", "\n")
    return [len(line) for line in text.split("\n")]


def judge(
    command: str, rc, out: str, err: str, files: dict[str, Path], data: dict[str, bytes]
) -> tuple[str, str]:
    """(outcome, detail) for one command's result."""
    if "Traceback" in out or "Traceback" in err:
        return "traceback", (err or out)[-2000:]
    if not isinstance(rc, int) or rc not in (0, 1, 2):
        return "bad-exit", f"exit {rc!r}: {err[-500:]}"
    paths = {str(p): name for name, p in files.items()}
    lines = (out + "\n" + err).splitlines() if command == "lint" else err.splitlines()
    errors = 0
    for line in lines:
        if not line or line.startswith((" ", "\t")):
            continue  # quoted source lines, carets, help
        is_error = ": error:" in line or line.startswith("error:")
        m = LOC_RE.match(line)
        located = m is not None and m.group("path") in paths
        if is_error:
            errors += 1
            if not located:
                if rc == 2 and any(line.startswith(p + ":") for p in paths):
                    continue  # a file-level I/O error (exit 2): the file, no position needed
                return "no-location", line
        if located:
            lens = _line_lengths(data[paths[m.group("path")]])
            ln, col = int(m.group("line")), int(m.group("col"))
            if not (1 <= ln <= len(lens)) or not (1 <= col <= lens[ln - 1] + 2):
                return "bad-location", f"{line} (the file has {len(lens)} lines)"
    if rc == 1 and errors == 0 and command in ("parse", "check", "transpile", "render", "compiled"):
        return "no-location", f"exit 1 without an error message: {err[-500:]}"
    if command == "verify" and rc == 1 and "MISMATCH" in out:
        return "mismatch", out[-1500:]
    return {0: "ok", 1: "findings", 2: "usage"}[rc], ""


def run_command(
    command: str,
    folder: Path,
    files: dict[str, Path],
    data: dict[str, bytes],
    extra: tuple[str, ...] = (),
) -> tuple[str, str]:
    from glslcheck.cli.main import main

    target = str(files[next(iter(files))]) if len(files) == 1 else str(folder)
    argv = [command, target, *extra]
    if command == "transpile":
        argv += ["-o", str(folder / "out.py")]
    elif command == "render":
        argv += ["--size", "8x8", "-o", str(folder / "out.npy")]
    elif command == "verify":
        argv += ["--size", "8x8"]
    elif command == "compiled":
        argv = ["render", target, "--backend", "compiled", "--size", "8x8"]
        argv += [*extra, "-o", str(folder / "out.npy")]
    out, err = io.StringIO(), io.StringIO()
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            rc = main(argv)
    except SystemExit as e:
        rc = e.code
    except BaseException as e:  # noqa: BLE001 - the point: nothing may escape main
        return "exception", "".join(traceback.format_exception(e))[-3000:]
    outcome = judge(command, rc, out.getvalue(), err.getvalue(), files, data)
    for name, p in files.items():
        if p.read_bytes() != data[name]:
            return "modified", f"{command} changed {name}"
    return outcome


def _worker(conn, workdir: str) -> None:
    """Run (command, files, extra arguments) jobs sent by the parent until it sends None."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C stops the parent, which stops the workers
    try:
        os.nice(
            int(os.environ.get("GLSLCHECK_FUZZ_NICE", "10"))
        )  # the machine is shared: yield to others
    except (OSError, ValueError):
        pass
    try:
        import resource

        # Bound a runaway allocation (3 GB of address space): it must surface as a clean
        # error, not take the machine down. Only without GL (llvmpipe maps large areas).
        if os.environ.get("GLSLCHECK_FUZZ_RLIMIT", "1") == "1":
            resource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30))
    except (ImportError, ValueError, OSError):
        pass
    # a runaway frame stops (a located error) well inside the render budget below
    os.environ.setdefault("GLSLCHECK_FRAME_SECONDS", str(FRAME_SECONDS))
    import glslcheck.backends.numpy_engine.program  # noqa: F401

    # loaded before the first job, whose budget it would spend
    import glslcheck.cli.main  # noqa: F401

    folder = Path(workdir)
    while True:
        try:
            job = conn.recv()
        except (EOFError, OSError):  # the parent is gone: so is this worker
            return
        if job is None:
            return
        command, data, extra = job
        conn.send(run_command(command, folder, _write_input(folder, data), data, extra))


def _write_input(folder: Path, data: dict[str, bytes]) -> dict[str, Path]:
    """The input's files, alone in `folder` (what a command left there before is removed)."""
    for f in folder.iterdir():
        if f.is_dir():
            shutil.rmtree(f, ignore_errors=True)
        else:
            f.unlink()
    files = {}
    for name, raw in data.items():
        p = folder / name
        p.write_bytes(raw)
        files[name] = p
    return files


class InProcess:
    """Runs each command in this process, with no time budget and no memory limit: the reference
    of benchmarks/bench_fuzz.py (the same commands without the worker's pipe and watchdog).
    For inputs known to end; a `Worker` for anything else."""

    def __init__(self) -> None:
        self.dir = tempfile.mkdtemp(prefix="glslcheck-fuzz-")

    def run(
        self, command: str, data: dict[str, bytes], budget: float, extra: tuple[str, ...] = ()
    ) -> tuple[str, str]:
        folder = Path(self.dir)
        return run_command(command, folder, _write_input(folder, data), data, extra)

    def close(self) -> None:
        shutil.rmtree(self.dir, ignore_errors=True)


class Worker:
    def __init__(self, ctx):
        self.ctx = ctx
        self.start()

    def start(self) -> None:
        self.dir = tempfile.mkdtemp(prefix="glslcheck-fuzz-")
        self.conn, child = self.ctx.Pipe()
        self.proc = self.ctx.Process(target=_worker, args=(child, self.dir), daemon=True)
        self.proc.start()

    def run(
        self, command: str, data: dict[str, bytes], budget: float, extra: tuple[str, ...] = ()
    ) -> tuple[str, str]:
        """The command's (outcome, detail); "timeout" when the worker spends `budget` seconds of
        CPU on it (a loop), or WALL_FACTOR times that of wall-clock time (blocked). CPU time, not
        wall time: on a shared machine a niced worker may wait minutes for a core. `extra`:
        more arguments for the command line."""
        self.conn.send((command, data, tuple(extra)))
        cpu0, start = self.cpu_seconds(), time.monotonic()
        while not self.conn.poll(1.0):
            cpu = self.cpu_seconds() - cpu0
            wall = time.monotonic() - start
            if cpu > budget or wall > budget * WALL_FACTOR:
                self.restart()
                return (
                    "timeout",
                    f"{command} ran longer than {budget:g} s (CPU {cpu:.0f} s, wall {wall:.0f} s)",
                )
        try:
            return self.conn.recv()
        except EOFError:
            pass
        self.restart()
        return "exception", "the worker process died (a crash in C code?)"

    def cpu_seconds(self) -> float:
        """CPU seconds the worker process has used (Linux /proc; elsewhere 0: wall time only)."""
        try:
            with open(f"/proc/{self.proc.pid}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
            return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
        except (OSError, ValueError, IndexError):
            return 0.0

    def restart(self) -> None:
        self.proc.kill()
        self.proc.join()
        shutil.rmtree(self.dir, ignore_errors=True)
        self.start()

    def close(self) -> None:
        try:
            self.conn.send(None)
            self.proc.join(5)
        finally:
            if self.proc.is_alive():
                self.proc.kill()
            shutil.rmtree(self.dir, ignore_errors=True)


def commands_for(
    kind: str,
    rng: random.Random,
    results: dict[str, str],
    heavy_rate: float,
    verify_rate: float,
    compiled_rate: float = 0.0,
) -> list[str]:
    """Which heavy commands an input gets, once its light results are known."""
    checked = results.get("check") == "ok"
    # numba's compile takes seconds a shader: the compiled engine gets a share of the programs
    # that check accepts (the hostile ones included: its frame budget must hold)
    compiled = ["compiled"] if checked and rng.random() < compiled_rate else []
    if kind.startswith(
        "channels"
    ):  # textures and buffers: the renderers read what channels.json binds
        return ["render", *(["verify"] if rng.random() < verify_rate else []), *compiled]
    if (
        kind == "hostile"
    ):  # the NumPy path only: Mesa's compile time on such nesting is the driver's
        return ["transpile", "render", *compiled]
    cmds = compiled
    if checked or rng.random() < heavy_rate:
        cmds.append("transpile")
    if rng.random() < heavy_rate * (4 if checked else 1):
        cmds.append("render")
    if (kind == "generate" and rng.random() < verify_rate) or (
        checked and rng.random() < heavy_rate / 4
    ):
        cmds.append("verify")
    return cmds


def fuzz_range(
    seed: int,
    start: int,
    stop: int,
    *,
    heavy_rate: float,
    verify_rate: float,
    timeout_scale: float = 1.0,
    out_dir: Path | None = None,
    commands=LIGHT + HEAVY,
    parse_rate: float = 1.0,
    progress=None,
    worker: Worker | None = None,
    deadline: float | None = None,
    hostile_rate: float = HOSTILE_RATE,
    channels_rate: float = CHANNELS_RATE,
    compiled_rate: float = 0.0,
    halt=None,
) -> tuple[collections.Counter, list[dict]]:
    """Fuzz inputs start..stop-1 of run `seed` in one worker; (counts, flagged). With
    `deadline` (a time.monotonic() value), stop after the input running at that time; with
    `halt` (a threading.Event), once it is set."""
    seeds, pool = seeds_and_pool()
    own = worker is None
    # Spawn, not fork: a process that already holds an OpenGL (EGL) context (pytest, after the GL
    # tests) cannot hand it to a forked child, whose renders then hang or fail to compile.
    worker = worker or Worker(mp.get_context("spawn"))
    counts: collections.Counter = collections.Counter()
    flagged: list[dict] = []
    try:
        for index in range(start, stop):
            if (
                deadline is not None
                and time.monotonic() > deadline
                or halt is not None
                and halt.is_set()
            ):
                break
            kind, data = make_input(seed, index, seeds, pool, hostile_rate, channels_rate)
            counts[("input", kind)] += 1
            rng = random.Random(f"{seed}:{index}:heavy")
            results: dict[str, str] = {}
            # `check` runs the whole parse path too; `parse` itself runs on a share of inputs.
            todo = [
                c for c in LIGHT if c in commands and (c != "parse" or rng.random() < parse_rate)
            ]
            while todo:
                command = todo.pop(0)
                t0 = time.perf_counter()
                extra = (
                    ("--frame-budget", f"{HOSTILE_FRAME_SECONDS:g}")
                    if kind == "hostile" and command in ("render", "compiled")
                    else ()
                )
                outcome, detail = worker.run(command, data, BUDGET[command] * timeout_scale, extra)
                counts[("seconds", command)] += time.perf_counter() - t0
                if (
                    kind == "generate"
                    and command in ("parse", "check", "transpile", "render")
                    or kind == "hostile"
                    and command in ("parse", "check")
                    or kind == "channels"
                    and command in ("render", "verify")
                ) and outcome != "ok":
                    if outcome in NORMAL:
                        outcome = "gen-rejected"
                if outcome == "mismatch" and kind not in ("generate", "channels"):
                    # A mutant may compute undefined values (smoothstep(e, e, x), 0/0, ...):
                    # different images are verify's finding there, only generated programs must
                    # match.
                    outcome = "findings"
                results[command] = outcome
                counts[(command, outcome)] += 1
                if outcome not in NORMAL:
                    flagged.append(
                        {
                            "seed": seed,
                            "index": index,
                            "kind": kind,
                            "command": command,
                            "outcome": outcome,
                            "detail": detail,
                        }
                    )
                    if out_dir is not None:
                        _save(out_dir, seed, index, command, outcome, detail, data)
                if command == "lint":
                    todo += [
                        c
                        for c in commands_for(
                            kind, rng, results, heavy_rate, verify_rate, compiled_rate
                        )
                        if c in commands
                    ]
            if progress:
                progress(index)
    finally:
        if own:
            worker.close()
    return counts, flagged


def _save(out_dir: Path, seed, index, command, outcome, detail, data) -> None:
    folder = out_dir / f"{outcome}-{command}-{seed}-{index}"
    folder.mkdir(parents=True, exist_ok=True)
    for name, raw in data.items():
        (folder / name).write_bytes(raw)
    (folder / "NOTE.txt").write_text(
        f"glslcheck {command}: {outcome}\n\n{detail}\n", encoding="utf-8"
    )


def print_counts(
    counts: collections.Counter, flagged: list[dict], elapsed: float, file=sys.stdout
) -> None:
    kinds = {k: n for (c, k), n in counts.items() if c == "input"}
    secs = {k: n for (c, k), n in counts.items() if c == "seconds"}
    total = sum(kinds.values())
    print(
        f"inputs: {total} ({', '.join(f'{k} {n}' for k, n in sorted(kinds.items()))}) in "
        f"{elapsed:.0f} s",
        file=file,
    )
    outcomes = sorted(
        {o for (c, o) in counts if c not in ("input", "seconds", "elapsed")},
        key=lambda o: (o not in NORMAL, o),
    )
    cmds = [c for c in LIGHT + HEAVY if any((c, o) in counts for o in outcomes)]
    print(
        f"{'command':<10}" + "".join(f"{o:>13}" for o in outcomes) + f"{'seconds':>10}", file=file
    )
    for c in cmds:
        print(
            f"{c:<10}"
            + "".join(f"{counts.get((c, o), 0):>13}" for o in outcomes)
            + f"{secs.get(c, 0):>10.0f}",
            file=file,
        )
    bad = len(flagged)
    print(
        f"flagged: {bad}"
        + (
            " (crashes, hangs, unlocated errors or rejected generated programs)"
            if bad
            else " - zero crashes"
        ),
        file=file,
    )


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--count", type=int, default=1000, help="number of inputs (default 1000)")
    p.add_argument(
        "--seed", type=int, default=0, help="run seed: input i is a function of (seed, i)"
    )
    p.add_argument(
        "--start", type=int, default=0, help="first input index (to resume or split a run)"
    )
    p.add_argument("--jobs", type=int, default=1, help="worker processes (default 1)")
    p.add_argument(
        "--heavy-rate",
        type=float,
        default=0.05,
        help="share of inputs that get render (x4 when check passes) and transpile though check "
        "failed",
    )
    p.add_argument(
        "--verify-rate",
        type=float,
        default=0.05,
        help="share of generated programs that get verify",
    )
    p.add_argument(
        "--hostile-rate",
        type=float,
        default=HOSTILE_RATE,
        help=f"share of inputs that are hostile valid programs (default {HOSTILE_RATE})",
    )
    p.add_argument(
        "--channels-rate",
        type=float,
        default=CHANNELS_RATE,
        help=f"share of inputs that are folders with channels.json (default {CHANNELS_RATE})",
    )
    p.add_argument(
        "--compiled-rate",
        type=float,
        default=0.01,
        help="share of checked programs also rendered by the compiled engine (default 0.01)",
    )
    p.add_argument(
        "--parse-rate",
        type=float,
        default=1.0,
        help="share of inputs that also get `parse` (check runs the parser on all; default 1)",
    )
    p.add_argument("--commands", default=",".join(LIGHT + HEAVY), help="entry points to run")
    p.add_argument(
        "--timeout-scale", type=float, default=1.0, help="multiply the per-command time budgets"
    )
    p.add_argument(
        "--out", default="fuzz-findings", help="folder for flagged inputs (default fuzz-findings)"
    )
    p.add_argument(
        "--json", metavar="FILE", help="also write the counts and flagged inputs as JSON"
    )
    p.add_argument(
        "--merge",
        nargs="+",
        metavar="JSON",
        help="print the combined counts of --json files and exit",
    )
    p.add_argument("--show", type=int, metavar="INDEX", help="print input INDEX of --seed and exit")
    p.add_argument(
        "--max-seconds",
        type=float,
        metavar="S",
        help="stop after S seconds (the inputs in flight finish; the counts so far are printed)",
    )
    p.add_argument(
        "--resume", metavar="JSON", help="continue the run a --json file recorded (same --seed)"
    )
    args = p.parse_args(argv)

    if args.merge:
        counts: collections.Counter = collections.Counter()
        flagged: list[dict] = []
        ranges = []
        for name in args.merge:
            doc = json.loads(Path(name).read_text(encoding="utf-8"))
            counts.update({tuple(k.split("/", 1)): v for k, v in doc["counts"].items()})
            flagged += doc["flagged"]
            spans = doc.get("chunks") or [[doc["start"], doc["start"] + doc["count"]]]
            ranges.append(
                f"seed {doc['seed']}: {doc['count']} inputs in {min(b for b, _ in spans)}.."
                f"{max(e for _, e in spans) - 1}"
            )
        print("merged: " + "; ".join(ranges))
        print_counts(counts, flagged, counts.get(("elapsed", "total"), 0))
        return 1 if flagged else 0

    if args.show is not None:
        seeds, pool = seeds_and_pool()
        kind, data = make_input(
            args.seed, args.show, seeds, pool, args.hostile_rate, args.channels_rate
        )
        for name, raw in data.items():
            print(f"== {kind}: {name} ({len(raw)} bytes)")
            sys.stdout.write(raw.decode("utf-8", "backslashreplace"))
        return 0

    commands = tuple(c.strip() for c in args.commands.split(",") if c.strip())
    opts = dict(
        heavy_rate=args.heavy_rate,
        verify_rate=args.verify_rate,
        timeout_scale=args.timeout_scale,
        parse_rate=args.parse_rate,
        out_dir=Path(args.out),
        commands=commands,
        hostile_rate=args.hostile_rate,
        channels_rate=args.channels_rate,
        compiled_rate=args.compiled_rate,
    )
    return run(args, opts)


def run(args, opts: dict) -> int:
    """Inputs --start .. --start+--count-1 in chunks of CHUNK on --jobs worker processes that
    live for the whole run; the counts go to --json after every chunk (with the chunks done, so
    --resume continues a stopped run), and the run stops cleanly (counts printed) at
    --max-seconds, on SIGTERM or on Ctrl-C."""
    import queue
    import signal
    import threading
    from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait

    t0 = time.time()
    stop = args.start + args.count
    counts: collections.Counter = collections.Counter()
    flagged: list[dict] = []
    done_chunks: list[list[int]] = []
    if args.resume:
        doc = json.loads(Path(args.resume).read_text(encoding="utf-8"))
        if doc.get("seed") != args.seed:
            print(
                f"fuzz: --resume {args.resume} is a run of seed {doc.get('seed')}, not {args.seed}",
                file=sys.stderr,
            )
            return 2
        counts.update(
            {tuple(k.split("/", 1)): v for k, v in doc["counts"].items() if k != "elapsed/total"}
        )
        flagged += doc["flagged"]
        done_chunks += doc.get("chunks", [])
        t0 -= doc["counts"].get("elapsed/total", 0)
    chunks = [
        (s, min(s + CHUNK, e))
        for b, e in _todo(args.start, stop, done_chunks)
        for s in range(b, e, CHUNK)
    ]
    halt = threading.Event()
    deadline = None if args.max_seconds is None else time.monotonic() + args.max_seconds

    def on_term(signum, frame):  # SIGTERM: finish the inputs in flight, write the counts, exit
        halt.set()

    signal.signal(signal.SIGTERM, on_term)
    ctx = mp.get_context("spawn")
    workers: queue.Queue = queue.Queue()
    started = [Worker(ctx) for _ in range(max(1, args.jobs))]
    for w in started:
        workers.put(w)

    def chunk(span):
        w = workers.get()
        try:
            return span, fuzz_range(
                args.seed, *span, worker=w, deadline=deadline, halt=halt, **opts
            )
        finally:
            workers.put(w)

    status = 0
    try:
        with ThreadPoolExecutor(len(started)) as pool:
            pending = {pool.submit(chunk, span) for span in chunks[: len(started)]}
            rest = iter(chunks[len(started) :])
            while pending:
                try:
                    finished, pending = wait(pending, timeout=5, return_when=FIRST_COMPLETED)
                except KeyboardInterrupt:
                    halt.set()
                    continue
                for fut in finished:
                    span, (c, f) = fut.result()
                    counts.update(c)
                    flagged.extend(f)
                    n = sum(v for (k, _), v in c.items() if k == "input")
                    if n:  # a chunk stopped early did its first n inputs (--resume does the rest)
                        done_chunks.append([span[0], span[0] + n])
                    if not halt.is_set() and (deadline is None or time.monotonic() < deadline):
                        nxt = next(rest, None)
                        if nxt is not None:
                            pending.add(pool.submit(chunk, nxt))
                    total = sum(v for (k, _), v in counts.items() if k == "input")
                    print(
                        f"[{time.time() - t0:6.0f} s] {total} inputs "
                        f"({total / max(time.time() - t0, 1e-9):.1f}/s), "
                        f"{len(flagged)} flagged",
                        file=sys.stderr,
                        flush=True,
                    )
                    if args.json:  # after every chunk, so a stopped run keeps what it did
                        _write_json(args, counts, flagged, done_chunks, t0)
    finally:
        for w in started:
            w.close()
    total = sum(v for (k, _), v in counts.items() if k == "input")
    print(
        f"python tools/fuzz.py --count {args.count} --seed {args.seed}"
        + (f" --start {args.start}" if args.start else "")
        + (f" --jobs {args.jobs}" if args.jobs > 1 else "")
        + (f" ({total} inputs done: stopped early)" if total < args.count else "")
    )
    print_counts(counts, flagged, time.time() - t0)
    for f in flagged[:20]:
        print(
            f"  {f['outcome']} {f['command']} seed {f['seed']} input {f['index']} ({f['kind']}): "
            f"{f['detail'].strip().splitlines()[-1][:200] if f['detail'].strip() else ''}"
        )
    if args.json:
        _write_json(args, counts, flagged, done_chunks, t0)
    return 1 if flagged else status


def _todo(start: int, stop: int, done: list[list[int]]) -> list[tuple[int, int]]:
    """The index ranges of start..stop-1 that no span of `done` covers."""
    todo, at = [], start
    for b, e in sorted(done):
        if b > at:
            todo.append((at, min(b, stop)))
        at = max(at, e)
    if at < stop:
        todo.append((at, stop))
    return [(b, e) for b, e in todo if b < e]


def _write_json(args, counts, flagged, chunks: list[list[int]], t0: float) -> None:
    """The run so far, written to a temporary file and renamed (a kill mid-write keeps the last)."""
    done = sum(n for (k, _), n in counts.items() if k == "input")
    path = Path(args.json)
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(
        json.dumps(
            {
                "seed": args.seed,
                "start": args.start,
                "count": done,
                "requested": args.count,
                "chunks": sorted(chunks),
                "counts": {
                    **{f"{c}/{o}": n for (c, o), n in sorted(counts.items())},
                    "elapsed/total": time.time() - t0,
                },
                "flagged": flagged,
            },
            indent=1,
        ),
        encoding="utf-8",
    )
    os.replace(tmp, path)


if __name__ == "__main__":
    sys.exit(main())
