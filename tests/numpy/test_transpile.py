"""The generated module: snapshots, mangling and the restricted namespace, errors with
locations, runaway loops, uniform values, statistics, the frame cache, running on its own.

Snapshots live in tests/numpy/snapshots/<name>.py; regenerate them with
`pytest tests/numpy/test_transpile.py --update-snapshots` and read the diff.
"""

from __future__ import annotations

import os
import subprocess
import sys
import traceback

import numpy as np
import pytest

from glslcheck.backends.numpy_engine import program as P
from glslcheck.backends.numpy_engine import tiles as F
from glslcheck.backends.numpy_engine.transpile import LOOP_CAP, transpile_shader
from glslcheck.base.diagnostics import GlslError

HERE = os.path.dirname(os.path.abspath(__file__))
SNAPSHOTS = os.path.join(HERE, "snapshots")


def _image(body: str, helpers: str = "") -> str:
    return helpers + "\nvoid mainImage(out vec4 fragColor, in vec2 fragCoord) {\n" + body + "\n}\n"


SNAPSHOT_SHADERS = {
    "gradient": _image(
        "    vec2 uv = fragCoord / iResolution.xy;\n"
        "    fragColor = vec4(uv, 0.5 + 0.5 * sin(iTime), 1.0);"
    ),
    "raymarch": """float map(vec3 p) {
    return length(p - vec3(0.0, 0.0, 4.0)) - 1.0;
}

float shade(vec3 n) {
    if (n.y < 0.0) return 0.1;
    return n.y;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = (2.0 * fragCoord - iResolution.xy) / iResolution.y;
    vec3 rd = normalize(vec3(uv, 1.5));
    float t = 0.0;
    for (int i = 0; i < 64; i++) {
        float d = map(rd * t);
        if (d < 0.001) break;
        t += d;
    }
    fragColor = vec4(vec3(t < 10.0 ? shade(normalize(rd * t - vec3(0.0, 0.0, 4.0))) : 0.0), 1.0);
}
""",
    "struct_switch": """struct Hit { float t; vec3 n; };

void closest(inout Hit h, float t, out bool better) {
    better = t < h.t;
    if (better) h.t = t;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    Hit h = Hit(1e9, vec3(0.0));
    bool b;
    closest(h, fragCoord.x, b);
    vec3 c = vec3(0.0);
    switch (int(fragCoord.y) % 3) {
        case 0: c.r = 1.0;
        case 1: c.g = 1.0; break;
        default: c = h.n;
    }
    fragColor = vec4(c, float(b));
}
""",
}


@pytest.mark.parametrize("name", sorted(SNAPSHOT_SHADERS))
def test_generated_code_snapshot(make_shader, update_snapshots, name):
    source = transpile_shader(make_shader(SNAPSHOT_SHADERS[name])).source
    path = os.path.join(SNAPSHOTS, f"{name}.py")
    if update_snapshots:
        os.makedirs(SNAPSHOTS, exist_ok=True)
        with open(path, "w", encoding="utf-8") as f:
            f.write(source)
    assert os.path.exists(path), f"no snapshot {path}; run with --update-snapshots and review it"
    with open(path, encoding="utf-8") as f:
        assert source == f.read(), (
            f"generated code changed; rerun with --update-snapshots and review {path}"
        )


@pytest.mark.parametrize("name", sorted(SNAPSHOT_SHADERS))
def test_snapshots_are_readable_python(make_shader, name):
    source = transpile_shader(make_shader(SNAPSHOT_SHADERS[name])).source
    compile(source, name, "exec")
    lines = source.splitlines()
    assert all(
        not line.startswith("\t") and (len(line) - len(line.lstrip())) % 4 == 0 for line in lines
    )
    assert any(line.strip().startswith("# line ") for line in lines)
    assert "def f_mainImage(S, _m, v_fragCoord):" in source


def test_only_reachable_functions_are_generated(make_shader):
    src = transpile_shader(
        make_shader(
            _image(
                "fragColor = vec4(used());",
                "float used() { return 1.0; }\nfloat unused() { return 2.0; }",
            )
        )
    ).source
    assert "def f_used(" in src and "unused" not in src


# -- names ---------------------------------------------------------------------------------


HOSTILE = [
    "lambda",
    "print",
    "np",
    "self",
    "rt",
    "X",
    "S",
    "exec",
    "eval",
    "os",
    "sys",
    "None",
    "True",
    "def",
    "import",
    "open",
    "globals",
    "compile",
    "shade",
    "init_globals",
    "SHADER_META",
    "v_x",
    "f_main",
    "g_x",
    "m_x",
    "C_f_1p0",
    "Z_float",
    "_m",
    "_ret",
    "_rv",
    "builtins",
    "type",
    "getattr",
    "breakpoint",
    "yield",
    "await",
    "async",
    "pass",
    "del",
    "is",
    "not_",
    "nonlocal",
    "with",
    "except",
    "raise",
    "finally",
    "from",
    "assert",
]


def _hostile_shader() -> str:
    decls = []
    uses = []
    for i, n in enumerate(HOSTILE):
        decls.append(f"float {n}(float q) {{ return q * {i + 1}.0; }}" if i % 3 == 0 else "")
        uses.append(n)
    funcs = "\n".join(d for d in decls if d)
    structs = "struct dict { float __class__; vec3 __dict__; float mro; };\n"
    body = ["    float acc = 0.0;"]
    for i, n in enumerate(HOSTILE):
        if i % 3 == 0:
            body.append(f"    acc += {n}(fragCoord.x * 0.001);")
        else:
            body.append(f"    {{ float {n} = fragCoord.y * {i}.0 * 0.001; acc += {n}; }}")
    body.append("    dict o = dict(1.0, vec3(2.0), 3.0); o.__dict__.y += acc;")
    body.append("    float lambda_ = o.__dict__.y + o.__class__ + o.mro;")
    body.append("    fragColor = vec4(fract(acc), fract(lambda_ * 0.1), 0.5, 1.0);")
    # A plain GLSL ES file: the `__` names are an error in a Shadertoy tab (no browser compiles
    # them: glslcheck/semantics/webgl_rules.py), a warning here, so they still reach the transpiler.
    return (
        "#version 300 es\nprecision highp float;\nout vec4 fragColor;\n"
        + structs
        + funcs
        + "\nvoid main() {\n    vec2 fragCoord = gl_FragCoord.xy;\n"
        + "\n".join(body)
        + "\n}\n"
    )


def test_hostile_identifiers_are_mangled(make_shader):
    src = transpile_shader(make_shader(GLSL=_hostile_shader())).source
    import re

    # code only: comments and string literals (docstrings name the GLSL functions) removed
    code = [re.sub(r'"[^"]*"', '""', line.split("#", 1)[0]) for line in src.splitlines()]

    names = {m.group(0) for line in code for m in re.finditer(r"(?<![.\w\"'])[A-Za-z_]\w*", line)}
    for n in HOSTILE:
        if n in (
            "rt",
            "X",
            "S",
            "None",
            "True",
            "def",
            "import",
            "from",
            "pass",
            "is",
            "not_",
            "_m",
            "_ret",
            "_rv",
            "SHADER_META",
            "shade",
            "init_globals",
            "globals",
        ) or re.match(r"^(C_|Z_|f_|v_|g_|m_|s_|u_)", n):
            continue  # the generator's own names: the GL comparison below shows they do not clash
        assert n not in names, n


def test_hostile_identifiers_render_like_gl(gl, make_shader):
    from glslcheck.backends.gl import compile_gl
    from glslcheck.verification.compare import compare

    shader = make_shader(GLSL=_hostile_shader())
    a = P.compile_numpy(shader).render(size=(40, 20))
    b = compile_gl(shader, gl).render(size=(40, 20))
    c = compare(a, b)
    assert c.match, (c.max_abs_error, c.mismatched_pixels)


def test_module_runs_without_builtins(make_shader):
    prog = P.compile_numpy(make_shader(_image("fragColor = vec4(1.0);")))
    ns = prog.module()
    assert ns["__builtins__"] == {}
    assert set(k for k in ns if not k.startswith(("C_", "Z_", "f_"))) <= {
        "__builtins__",
        "__name__",
        "__doc__",
        "rt",
        "X",
        "SHADER_META",
        "init_globals",
        "shade",
    }


# -- errors --------------------------------------------------------------------------------


def test_texture_lookup_is_a_located_error(make_shader):
    # iChannel0-3 are sampled (backends/numpy_engine/textures.py); a sampler uniform of the user's
    # own is not
    shader = make_shader(
        _image(
            "vec2 uv = fragCoord;\n    fragColor = texture(myTex, uv);", "uniform sampler2D myTex;"
        )
    )
    with pytest.raises(GlslError) as e:
        transpile_shader(shader)
    d = e.value.diagnostics[0]
    assert "not supported" in d.message and d.loc.line == 4 and d.loc.path == "Image.glsl"


@pytest.mark.parametrize(
    "loop",
    [
        "for (;;) { acc += 1.0; }",
        "while (acc >= 0.0) { acc += 1.0; }",
        "for (int i = 0; i >= 0; i += 0) { acc += fragCoord.x; }",
    ],
)
def test_endless_loop_is_an_error_naming_its_line(make_shader, loop):
    shader = make_shader(_image(f"    float acc = 0.0;\n    {loop}\n    fragColor = vec4(acc);"))
    prog = P.compile_numpy(shader)
    with pytest.raises(GlslError) as e:  # the loop cap stops it: the message names the cap
        prog.render(size=(4, 4))
    d = e.value.diagnostics[0]
    assert d.loc.path == "Image.glsl" and d.loc.line == 4
    assert f"{LOOP_CAP:,}" in d.message


def test_tracebacks_show_generated_lines(make_shader, monkeypatch):
    prog = P.compile_numpy(make_shader(_image("    fragColor = vec4(fragCoord.x);")))
    ns = prog.module()

    def boom(*a):
        raise RuntimeError("boom")

    monkeypatch.setattr(ns["rt"], "vec", boom)
    with pytest.raises(RuntimeError) as e:
        prog.render(size=(2, 2))
    text = "".join(traceback.format_exception(e.value))
    assert "f_mainImage" in text and "rt.vec(4, v_fragCoord[0])" in text


# -- uniformity, compaction, stats, cache ----------------------------------------------------


class _ShapeSpy:
    def __init__(self, rt):
        self.rt = rt
        self.shapes = {}

    def __getattr__(self, name):
        fn = getattr(self.rt, name)
        if not callable(fn) or name in ("F",):
            return fn

        def spy(*a, **k):
            out = fn(*a, **k)
            if isinstance(out, np.ndarray):
                self.shapes.setdefault(name, set()).add(out.shape[-1])
            return out

        return spy


def test_uniform_values_are_computed_once_per_tile(make_shader):
    body = """
    float k = sin(iTime) * 2.0;
    vec3 base = vec3(cos(k), 0.5, 1.0);
    for (int i = 0; i < 3; i++) base.y += exp2(float(i));
    fragColor = vec4(base * (fragCoord.x / iResolution.x), 1.0);"""
    prog = P.compile_numpy(make_shader(_image(body)))
    ns = prog.module()
    spy = _ShapeSpy(ns["rt"])
    ns["rt"] = spy
    prog.render(size=(16, 8), time=0.7)
    for name in ("sin", "cos", "exp2", "to_float"):
        assert spy.shapes[name] == {1}, name
    assert 128 in spy.shapes["vec"]  # the per-pixel value (float * and + are NumPy operators)


def test_unread_uniforms_are_not_computed_and_static_frames_are_cached(make_shader, monkeypatch):
    prog = P.compile_numpy(
        make_shader(_image("fragColor = vec4(fragCoord / iResolution.xy, 0.0, 1.0);"))
    )
    assert prog.uniforms == ["iResolution"] and not prog.animated
    calls = []
    ns = prog.module()
    shade = ns["shade"]
    ns["shade"] = lambda S: calls.append(1) or shade(S)
    a = prog.render(size=(8, 8), time=0.0)
    b = prog.render(size=(8, 8), time=5.0, frame=300, mouse=(1, 2, 3, 4))
    assert len(calls) == 1 and np.array_equal(a, b)
    prog.render(size=(8, 4))
    assert len(calls) == 2
    anim = P.compile_numpy(make_shader(_image("fragColor = vec4(sin(iTime));")))
    assert anim.uniforms == ["iTime"] and anim.animated
    assert (
        anim.render(size=(1, 1), time=0.0)[0, 0, 0] != anim.render(size=(1, 1), time=1.0)[0, 0, 0]
    )


def test_sparse_branches_are_compacted_and_counted(make_shader, monkeypatch):
    body = """
    vec3 c = vec3(0.0);
    if (fragCoord.x < 8.0) { for (int i = 0; i < 4; i++) c += vec3(sin(fragCoord.y + float(i))); }
    fragColor = vec4(c, 1.0);"""
    shader = make_shader(_image(body))
    gathered = []
    real = F.LaneHelpers.gather

    def counting(self, S, idx, values):
        gathered.append(len(idx))
        return real(self, S, idx, values)

    monkeypatch.setattr(F.LaneHelpers, "gather", counting)
    prog = P.compile_numpy(shader)
    img = prog.render(size=(64, 64), stats=True)
    assert gathered and max(gathered) == 8 * 64
    stats = {(s.kind, s.line): s.lanes for s in prog.last_stats}
    assert stats[("function", 2)] == 64 * 64
    assert stats[("if", 5)] == 8 * 64
    assert stats[("loop", 5)] == 4 * 8 * 64
    uncompacted = P.compile_numpy(shader)
    uncompacted.compaction = F.Compaction(min_lanes=10**9)
    np.testing.assert_array_equal(img, uncompacted.render(size=(64, 64)))


# -- the module on its own, the API and the CLI ----------------------------------------------


def test_generated_module_runs_on_its_own(tmp_path, make_shader):
    src = transpile_shader(make_shader(SNAPSHOT_SHADERS["gradient"])).source
    module = tmp_path / "shader.py"
    module.write_text(src)
    out = tmp_path / "out.npy"
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(HERE)))
    subprocess.run(
        [sys.executable, str(module), "-o", str(out), "--size", "6x4", "--time", "1.5"],
        check=True,
        env=env,
        cwd=tmp_path,
    )
    img = np.load(out)
    expected = P.compile_numpy(make_shader(SNAPSHOT_SHADERS["gradient"])).render(
        size=(6, 4), time=1.5
    )
    np.testing.assert_array_equal(img, expected)
    np.testing.assert_array_equal(
        P.load_module(str(module)).render(size=(6, 4), time=1.5), expected
    )


def test_public_api(tmp_path):
    import glslcheck

    path = tmp_path / "Image.glsl"
    path.write_text(_image("fragColor = vec4(fragCoord / iResolution.xy, iTime, 0.5);"))
    prog = glslcheck.compile(str(path))
    img = prog.render(size=(4, 2), time=0.5)
    assert img.shape == (2, 4, 4) and img.dtype == np.float32 and img[0, 0, 2] == 0.5
    assert prog.render(size=(4, 2), precision="float64").dtype == np.float32
    with pytest.raises(ValueError):
        prog.render(precision="float8")
    with pytest.raises(ValueError):
        glslcheck.compile(str(path), backend="vulkan")


def test_cli_render_and_transpile(tmp_path):
    from PIL import Image

    from glslcheck.cli.main import main

    path = tmp_path / "Image.glsl"
    path.write_text(_image("fragColor = vec4(fragCoord.x / iResolution.x, 2.0, -1.0, 0.2);"))
    assert main(["render", str(path), "-o", str(tmp_path / "a.png"), "--size", "4x2"]) == 0
    px = np.asarray(Image.open(tmp_path / "a.png"))
    assert px.shape == (2, 4, 4) and px[0, 0].tolist() == [32, 255, 0, 255]
    assert (
        main(["render", str(path), "-o", str(tmp_path / "a.npy"), "--size", "4x2", "--stats"]) == 0
    )
    assert np.load(tmp_path / "a.npy")[0, 0, 1] == 2.0
    assert (
        main(
            [
                "render",
                str(path),
                "-o",
                str(tmp_path / "a.gif"),
                "--size",
                "4x2",
                "--frames",
                "3",
                "--fps",
                "10",
            ]
        )
        == 0
    )
    assert Image.open(tmp_path / "a.gif").n_frames >= 1
    assert main(["render", str(path), "-o", str(tmp_path / "a.bmp")]) == 2
    assert main(["render", str(tmp_path / "missing.glsl")]) == 2
    bad = tmp_path / "bad" / "Image.glsl"
    bad.parent.mkdir()
    bad.write_text(_image("fragColor = vec4(undefined_name);"))
    assert main(["render", str(bad), "-o", str(tmp_path / "b.png")]) == 1
    assert main(["transpile", str(path), "-o", str(tmp_path / "s.py")]) == 0
    assert "def f_mainImage" in (tmp_path / "s.py").read_text()


def test_products_with_nonzero_literals_are_plain_and_fold_as_before(make_shader):
    """A float product with a nonzero literal is the `*` operator (Runtime.fmul has no zero to
    fold there); a zero literal, and one that is zero in float16 (1e-10), keep rt.fmul, whose
    constant zero turns NaN into 0 (Mesa folds x * 0.0). The pixels in every precision are what
    rt.fmul gives: NaN times 0.0 (and times 1e-10 in float16) is 0, times 0.5 stays NaN."""
    shader = make_shader(
        _image(
            "    float n = sqrt(fragCoord.x - 1e9);   // NaN in every pixel\n"
            "    fragColor = vec4(n * 0.5, n * 0.0, 1e-10 * n, 1.0);"
        )
    )
    source = transpile_shader(shader).source
    assert "(v_n * C_f_0p5)" in source
    assert "rt.fmul(v_n, C_f_0p0)" in source and "rt.fmul(C_f_1em10, v_n)" in source
    prog = P.compile_numpy(shader)
    for precision, tiny_folds in (("float32", False), ("float64", False), ("float16", True)):
        img = prog.render(size=(4, 2), precision=precision)
        assert np.isnan(img[..., 0]).all() and (img[..., 1] == 0).all(), precision
        assert (img[..., 2] == 0).all() if tiny_folds else np.isnan(img[..., 2]).all(), precision
