"""Score `glslcheck verify` on real public Shadertoy shaders that read channels (textures, Buffer
A-D).

The repository keeps only tests/real_channels/manifest.json: each shader's Shadertoy JSON
(repository, path, commit; chosen by its inputs before any was run) and, for the preset textures
they sample, where a public repository keeps the file (`media`, keyed by the file name of
Shadertoy's `/media/a/<hash>.<ext>` path). Shaders and textures are third-party: `fetch`
re-reads them into tests/real_channels/texts/<id>/ (git-ignored) as glslcheck reads a Shadertoy
export: `shader.json` and its textures in `media/` beside it (glslcheck/shadertoy/channels.py
`load_shadertoy_json`). `score` verifies each one over consecutive frames, buffers carried:

    python tools/real_channels.py fetch [--mirror DIR]     # as tools/real_verify.py fetch
    python tools/real_channels.py score [--size 64x36] [--frames 3] [--timeout 300]
                                        [--only ID,...] [--json out.json]

Verdicts, one per shader, each in its own process (as tools/real_verify.py):

- match: every frame verifies (verification/compare.py's tolerance model, as the CLI);
- mismatch: some frame does not (the reason names the frame and the pixel counts);
- does not compile: the GL driver rejects a pass;
- unsupported: glslcheck refuses an input (a cube map, a missing texture: exit-2 errors) or the
  NumPy backend refuses or stops the shader;
- timeout / error: the process took longer than --timeout or failed otherwise.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from real_verify import ORDER, _from_github, _from_mirror, arguments, run_child  # noqa: E402

ROOT = HERE.parent
MANIFEST = ROOT / "tests" / "real_channels" / "manifest.json"
TEXTS = ROOT / "tests" / "real_channels" / "texts"


def load_manifest() -> dict:
    return json.loads(MANIFEST.read_text())


def shader_path(entry: dict) -> Path:
    return TEXTS / entry["id"] / "shader.json"


def _read(entry: dict, mirror: Path | None) -> bytes | None:
    data = _from_mirror(mirror, entry) if mirror else None
    if data is None:
        try:
            data = _from_github(entry)
        except OSError as e:
            print(
                f"cannot read {entry['repo']}:{entry['path']}@{entry['commit'][:10]} ({e})",
                file=sys.stderr,
            )
            return None
    return data


def texture_sources(shader_json: bytes) -> set[str]:
    """The file names of the textures a Shadertoy JSON's passes read (`/media/a/<name>`)."""
    data = json.loads(shader_json)
    data = data[0] if isinstance(data, list) and data else data
    data = data.get("Shader", data) if isinstance(data, dict) else {}
    names = set()
    for rp in data.get("renderpass", []):
        for inp in rp.get("inputs") or ():
            if inp.get("ctype", inp.get("type")) == "texture":
                names.add(Path(str(inp.get("src", inp.get("filepath", "")))).name)
    return names


def fetch(mirror: Path | None) -> int:
    manifest = load_manifest()
    missing = 0
    for entry in manifest["shaders"]:
        target = shader_path(entry)
        if not target.exists():
            data = _read(entry, mirror)
            if data is None:
                missing += 1
                continue
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(data)
        for name in sorted(texture_sources(target.read_bytes())):
            media = target.parent / "media" / name
            source = manifest["media"].get(name)
            if media.exists():
                continue
            if source is None:  # the shader then fails with glslcheck's own error naming the file
                print(
                    f"{entry['id']}: no source for Shadertoy's /media/a/{name} in the manifest",
                    file=sys.stderr,
                )
                continue
            data = _read(source, mirror)
            if data is None:
                missing += 1
                continue
            media.parent.mkdir(exist_ok=True)
            media.write_bytes(data)
    print(
        f"{len(manifest['shaders'])} shaders in {TEXTS.relative_to(ROOT)}, {missing} files missing"
    )
    return 1 if missing else 0


def verify_one(path: str, size: tuple[int, int], frames: int) -> dict:
    """The verdict of one shader (run inside the child process)."""
    from glslcheck.base.diagnostics import GlslError, InputError
    from glslcheck.shadertoy.sources import load_shader
    from glslcheck.verification.verify import compile_backend, verify_frames

    def first(e) -> str:
        return "; ".join(d.message for d in e.diagnostics)[:200]

    try:
        shader = load_shader(path)
        gl = compile_backend(shader, "gl")
    except InputError as e:
        return {"verdict": "unsupported", "reason": str(e).replace(str(TEXTS) + "/", "")[:200]}
    except GlslError as e:
        return {"verdict": "does not compile", "reason": first(e)}
    try:
        numpy = compile_backend(shader, "numpy")
        results = list(verify_frames(shader, size=size, frames=frames, programs=[numpy, gl]))
    except GlslError as e:
        return {"verdict": "unsupported", "reason": first(e)}
    bad = [r for r in results if not r.match]
    worst = max(r.comparison.max_abs_error for r in results)
    if not bad:
        return {"verdict": "match", "reason": f"{len(results)} frames, max abs error {worst:.3g}"}
    j = bad[0].comparison.to_json()
    return {
        "verdict": "mismatch",
        "reason": (
            f"{len(bad)}/{len(results)} frames; frame {bad[0].spec.frame}: "
            f"{j['mismatched_pixels']} over "
            f"tolerance, {j['edge_pixels']} edge, NaN/Inf numpy {j['nan_numpy']} gl {j['nan_gl']}, "
            f"max err {j['max_abs_error']:.3g}"
        ),
    }


def score(size: str, frames: int, timeout: float, only: set[str] | None, out: Path | None) -> int:
    entries = [e for e in load_manifest()["shaders"] if not only or e["id"] in only]
    absent = [e["id"] for e in entries if not shader_path(e).exists()]
    if absent:
        print(
            f"{len(absent)} shaders are missing ({', '.join(absent[:5])} ...): run "
            "`python tools/real_channels.py fetch`",
            file=sys.stderr,
        )
        return 2
    results = []
    for entry in entries:
        started = time.perf_counter()
        result = run_child(
            [sys.executable, __file__, "_one", str(shader_path(entry)), size, str(frames)], timeout
        )
        result.update(
            id=entry["id"], kind=entry["kind"], seconds=round(time.perf_counter() - started, 1)
        )
        results.append(result)
        print(
            f"{entry['id']:<32} {entry['kind']:<17} {result['verdict']:<17} "
            f"{result['seconds']:6.1f}s  "
            f"{result['reason']}",
            flush=True,
        )
    counts = {v: sum(r["verdict"] == v for r in results) for v in ORDER}
    ran = counts["match"] + counts["mismatch"]
    print()
    print("  ".join(f"{v}: {n}" for v, n in counts.items()))
    print(f"match among the {ran} shaders both backends rendered: {counts['match']}/{ran}")
    if out:
        out.write_text(json.dumps(results, indent=1))
    return 0


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["_one"]:
        path, size, frames = argv[1:4]
        from glslcheck.base.limits import parse_size

        print(json.dumps(verify_one(path, parse_size(size), int(frames))))
        return 0
    p = arguments(
        __doc__, "tests/real_channels/texts/", "64x36", "--frames", {"type": int, "default": 3}
    )
    args = p.parse_args(argv)
    if args.command == "fetch":
        return fetch(args.mirror)
    return score(
        args.size,
        args.frames,
        args.timeout,
        set(filter(None, args.only.split(","))) or None,
        args.json,
    )


if __name__ == "__main__":
    sys.exit(main())
