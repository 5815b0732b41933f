"""What the compiled engine's per-pixel module spends on values that are the same for every pixel.

    python benchmarks/bench_pixel_uniform.py [--only 01_spheres_raytraced,...] [--size 400x225]
                                             [--repeat 3] [--frames 10] [--trig FUNCTION]

The NumPy backend computes a value that is the same in every lane once a tile; the per-pixel
module computes it for every pixel. For each lab shader (default: the light ones whose per-pixel
frames lose the default program's trial against NumPy, and 07_final), in this one process:

- operations: the shader's lockstep module (8 lanes, lanes.py) counted statement by statement,
  calls followed, every loop counted as 4 passes (the loops of these shaders run over 4 spheres
  or 4 lights): the operations on one scalar for the block (the rewrite's uniform names: what
  uniforms, constants and the row's y give) and those per lane. The per-pixel module runs both
  for every pixel; "uniform share" is the first over their sum (`the row's`: those of them that
  read the row's y, the same in a row only). `a prologue's` counts those a frame prologue could
  compute once: outside every loop and branch of the entry function and of what it calls there,
  reading neither the row's y nor only literal constants (LLVM folds those already). A call of
  the scalar runtime (sin, pow) counts as one operation;
- per-pixel frames, CPU and wall time a frame on the engine's row threads, the best of --repeat
  rounds of --frames frames, the variants and the NumPy backend in turns (the default program's
  trial judges wall time): the module as generated
  (`pixel`); without the per-pixel reset of the global state (`noreset`, when no function but the
  initializer writes it); and with the globals' initial values as constants of the module
  (`const`: numba freezes a global array into the machine code, so LLVM folds and unrolls the
  work on them), frames compared bit for bit with `pixel`; `nopow` is `const` with each pow()
  replaced by x*x (other bits: timing only, what the llvmpipe pow emulation costs); `cheaptrig`
  (with --trig FUNCTION) the module with that function's sin() and cos() free (timing only: what
  a frame prologue saves where they compute uniform values); `trivial` a one-line shader (the
  per-pixel loop's own cost);
- the NumPy backend's frame as the default program renders it (threads, or worker processes
  whose CPU time is read from /proc), its frame cache emptied before each frame.

The variants are measurements, not the engine's code: they show how much a change of where the
uniform values live could gain, the same operations in the same order. Where the engine's module
reads the globals from its own constants and resets no state (constant_globals.py: no function
writes them), `noreset` and `const` are the module as generated.
"""

from __future__ import annotations

import argparse
import ast
import os
import re
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

DEFAULT = "01_spheres_raytraced,03_lambert_color,04_phong_coefficient,05_blinn_phong,07_final"
PASSES = 4  # every loop of the default shaders runs 4 passes (kSphereCount, kLightCount)
OPS = (ast.BinOp, ast.UnaryOp, ast.Compare, ast.IfExp, ast.BoolOp)
CASTS = ("F32", "I32", "U32")
LANE = re.compile(r"__\d+$")
TRIVIAL = (
    "void mainImage(out vec4 fragColor, in vec2 fragCoord)\n"
    "{\n    fragColor = vec4(fragCoord / iResolution.xy, 0.0, 1.0);\n}\n"
)
STATE_FNS = ("init_globals", "render_rows", "rows_loop", "globals_template")
TIMING_ONLY = ("numpy", "nopow", "cheaptrig")  # other bits than `pixel`: not compared


def _ops(node: ast.AST, fns: dict) -> tuple[int, list[str], bool]:
    """Operations in a statement (casts and user calls not counted), its user calls, and whether
    every operand is a literal constant (`-F_2p5`)."""
    n, calls, literal = 0, [], True
    for x in ast.walk(node):
        if isinstance(x, OPS):
            n += 1
        elif isinstance(x, ast.Call) and isinstance(x.func, ast.Name):
            if x.func.id in fns:
                calls.append(x.func.id)
            elif x.func.id not in CASTS:
                n += 1
        elif isinstance(x, ast.Name) and isinstance(x.ctx, ast.Load):
            literal &= bool(re.match(r"(_g_)?[FIU]_", x.id)) or x.id in CASTS
        elif isinstance(x, ast.Subscript):
            literal = False
    return n, calls, literal


def count_ops(lanes_source: str, width: int) -> dict:
    """Operations a pixel runs: on uniform names (once a block in lockstep, every pixel in the
    per-pixel module; `row` those that read the row's y, the same for a row only), on lanes, and
    the uniform ones a frame prologue could compute once (`prologue`: outside every loop and
    branch, reading neither the row's y nor only literal constants)."""
    tree = ast.parse(lanes_source)
    fns = {f.name: f for f in tree.body if isinstance(f, ast.FunctionDef)}
    memo: dict[tuple, list[float]] = {}

    def names(node: ast.AST) -> set[str]:
        return {x.id for x in ast.walk(node) if isinstance(x, ast.Name)}

    def total(name: str, row: frozenset, straight: bool) -> list[float]:
        key = (name, row, straight)
        if key in memo:
            return memo[key]
        acc = [0.0, 0.0, 0.0, 0.0]  # uniform, of them the row's, prologue (a block); lane (a pixel)
        rows = set(row)

        def stmt(s: ast.AST, mult: int, straight: bool) -> None:
            n, calls, literal = _ops(s, fns)
            seen = names(s)
            stores = [
                x.id
                for x in ast.walk(s)
                if isinstance(x, ast.Name) and isinstance(x.ctx, ast.Store)
            ]
            if any(LANE.search(x) for x in seen):
                acc[3] += mult * n / width
            else:
                acc[0] += mult * n
                if seen & rows:
                    acc[1] += mult * n
                    rows.update(stores)
                elif straight and not literal:
                    acc[2] += mult * n
            for c in calls:
                callee = fns[c]
                params = [a.arg for a in callee.args.args]
                call = next(
                    x
                    for x in ast.walk(s)
                    if isinstance(x, ast.Call) and getattr(x.func, "id", "") == c
                )
                tainted = frozenset(p for p, a in zip(params, call.args) if names(a) & rows)
                sub = total(c, tainted, straight)
                for k in range(3):
                    acc[k] += mult * sub[k]
                acc[3] += mult * sub[3]

        def block(stmts: list, mult: int, straight: bool) -> None:
            for s in stmts:
                if isinstance(s, ast.While):
                    stmt(s.test, mult * PASSES, False)
                    block(s.body, mult * PASSES, False)
                elif isinstance(s, ast.If):
                    stmt(s.test, mult, False)
                    block(s.body, mult, False)
                    block(s.orelse, mult, False)
                else:
                    stmt(s, mult, straight)

        block(fns[name].body, 1, straight)
        memo[key] = acc
        return acc

    entry = next(n for n in fns if n.startswith("shade"))
    u, row, pro, lane = total(entry, frozenset(("fy", "py")), True)
    return {"block": u, "row": row, "prologue": pro, "lane": lane}


def _split(source: str) -> list[str]:
    return re.split(r"(?m)^(?=@jit\n|@numba)", source)


def cheap_trig(source: str, function: str) -> str:
    """The module with every sin() and cos() of `function` (all its variants) returning its
    argument: what a frame prologue would save where that function computes uniform values
    (timing only, other bits)."""
    parts = []
    for p in _split(source):
        if re.search(rf"def f_{function}(__\w+)?\(", p):
            p = re.sub(r"\b(sin|cos)\(", "trig_cheap(", p)
        parts.append(p)
    cheap = "\n@jit\ndef trig_cheap(x, f):\n    return x\n\n\n@jit\n"
    return "".join(parts).replace("\n@jit\n", cheap, 1)


def variants(source: str, template: list) -> dict[str, str]:
    """The per-pixel module as generated, without the per-pixel state reset, and with the
    globals as module constants (only where no function but the initializer writes the state
    and the initializer reads no uniform)."""
    out = {"pixel": source}
    parts = _split(source)
    rest = [p for p in parts if not any(f"def {f}(" in p for f in STATE_FNS)]
    init = next(p for p in parts if "def init_globals(" in p)
    if any(re.search(r"\bg[fiub]\[[^\]]+\] =|aset\(g[fiub]\b", p) for p in rest):
        return out
    out["noreset"] = re.sub(r"(?m)^ *aset\(g[fiub], 0, gt[fiub]\)\n", "", source)
    if re.search(r"\bu[fi]\[", init):
        return out
    consts = "\n".join(
        f"GC{k} = np.array({arr.tolist()!r}, dtype=np.{arr.dtype.name})"
        for k, arr in zip("fiub", template)
    )
    text = "".join(
        p if any(f"def {f}(" in p for f in STATE_FNS) else re.sub(r"\bg([fiub])\[", r"GC\1[", p)
        for p in _split(out["noreset"])
    )
    out["const"] = text.replace("\n@jit\n", f"\n{consts}\n\n\n@jit\n", 1)
    if "pow_uniform(" in text or " pow(" in text:
        cheap = (
            "\n@jit\ndef pow_cheap(x, y, s, z, f):\n    return F32(x * x)\n\n\n"
            "@jit\ndef pow_cheap3(x, y, f):\n    return F32(x * x)\n\n\n@jit\n"
        )
        nopow = out["const"].replace("pow_uniform(", "pow_cheap(").replace(" pow(", " pow_cheap3(")
        out["nopow"] = nopow.replace("\n@jit\n", cheap, 1)
    return out


def template(mod) -> list:
    """The globals' initial values (the initializer reads no uniform where they are used)."""
    import numpy as np

    gt = [
        np.zeros(max(1, mod.SLOTS[k]), dt)
        for k, dt in (("float", np.float32), ("int", np.int32), ("uint", np.uint32), ("bool", bool))
    ]
    uf = np.zeros(max(1, mod.USLOTS["float"]), np.float32)
    ui = np.zeros(max(1, mod.USLOTS["int"]), np.int32)
    lt = np.zeros(1 + len(mod.LOOPS), np.int64)
    lt[0] = 1 << 40
    mod.globals_template(uf, ui, *gt, lt)
    return gt


def _descendants(pid: int) -> list[int]:
    out: list[int] = []
    try:
        tasks = os.listdir(f"/proc/{pid}/task")
    except OSError:
        return out
    for tid in tasks:
        try:
            with open(f"/proc/{pid}/task/{tid}/children") as f:
                kids = [int(x) for x in f.read().split()]
        except OSError:
            continue
        for kid in kids:
            out += [kid, *_descendants(kid)]
    return out


def cpu_seconds() -> float:
    """This process's CPU time and its live child processes' (the NumPy backend's workers), in
    clock ticks of the children's (/proc: 10 ms; a round of frames is many ticks)."""
    total = time.process_time()
    tick = os.sysconf("SC_CLK_TCK")
    for pid in _descendants(os.getpid()):
        try:
            with open(f"/proc/{pid}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        total += (int(fields[11]) + int(fields[12])) / tick  # utime, stime
    return total


def measure(
    name: str, path: str, size: tuple[int, int], repeat: int, frames: int, trig: str = ""
) -> None:
    import numpy as np

    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate
    from glslcheck.backends.numpy_engine.program import compile_numpy
    from glslcheck.shadertoy.sources import load_shader

    shader = load_shader(path)
    source, where = generate(shader, lanes=0)
    lanes, _ = generate(shader, lanes=8)
    c = count_ops(lanes, 8)
    base = CompiledProgram(source, where)
    base.load()
    progs = {}
    texts = variants(source, template(base.mod))
    if trig:
        texts["cheaptrig"] = cheap_trig(source, trig)
    for key, text in texts.items():
        progs[key] = CompiledProgram(text, where)  # the engine's row threads
        progs[key].load()
    ref = progs["pixel"].render(size=size, time=1.3)
    same = {
        k: bool((p.render(size=size, time=1.3).view(np.uint32) == ref.view(np.uint32)).all())
        for k, p in progs.items()
    }
    numpy = compile_numpy(shader)
    best = dict.fromkeys([*progs, "numpy"], float("inf"))
    wall = dict(best)
    for r in range(repeat + 1):
        for key in best:
            t0, w0 = cpu_seconds(), time.perf_counter()
            for k in range(frames):
                if key == "numpy":
                    numpy._cache.clear()
                (numpy if key == "numpy" else progs[key]).render(size=size, time=1.0 + k * 0.1)
            if r:  # the first round warms up (threads, worker processes, the NumPy kernels)
                best[key] = min(best[key], (cpu_seconds() - t0) / frames)
                wall[key] = min(wall[key], (time.perf_counter() - w0) / frames)
    px = size[0] * size[1]
    print(
        f"{name:22s} ops a pixel {c['block'] + c['lane']:4.0f}: uniform {c['block']:4.0f} "
        f"({c['block'] / (c['block'] + c['lane']) * 100:2.0f}%; the row's {c['row']:3.0f}, "
        f"a prologue's {c['prologue']:3.0f}) | ns a pixel, CPU/wall: "
        + "  ".join(
            f"{k} {v * 1e9 / px:.0f}/{wall[k] * 1e9 / px:.0f}"
            + ("" if k in TIMING_ONLY or same[k] else " (bits!)")
            for k, v in best.items()
        ),
        flush=True,
    )


def main() -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--only", default=DEFAULT)
    ap.add_argument("--size", default="400x225")
    ap.add_argument("--repeat", type=int, default=3, help="rounds, the best one counts")
    ap.add_argument("--frames", type=int, default=10, help="frames a round")
    ap.add_argument(
        "--trig",
        default="",
        help="a GLSL function whose sin() and cos() the `cheaptrig` variant makes free "
        "(bonus_animated_lights: animateLights)",
    )
    args = ap.parse_args()
    w, h = (int(x) for x in args.size.lower().split("x"))
    size = (w, h)
    print(f"load average at start: {' '.join(f'{x:.1f}' for x in os.getloadavg())}")
    with tempfile.TemporaryDirectory() as d:
        trivial = os.path.join(d, "trivial.glsl")
        with open(trivial, "w") as f:
            f.write(TRIVIAL)
        measure("trivial", trivial, size, args.repeat, args.frames)
        for name in args.only.split(","):
            measure(
                name,
                os.path.join(ROOT, "lab_shaders", name),
                size,
                args.repeat,
                args.frames,
                args.trig,
            )
    print(f"load average at end: {' '.join(f'{x:.1f}' for x in os.getloadavg())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
