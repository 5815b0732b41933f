#!/usr/bin/env python3
"""Write the lab folder's report and the screenshots docs/usage.md shows (docs/report.png,
docs/report_nan.png).

    python tools/report_screenshot.py [--out build/report.html] [--png docs/report.png]
                                      [--nan-png docs/report_nan.png]

The pages are loaded in the WebGL backend's headless Chromium
(glslcheck.verification.report.load_in_browser): any console error, page error or network request
fails the run. The first screenshot is the top of the lab folder's page: the index and the first
shader, down to its accuracy/time table and plot (bench at the report's default size, 64x36). No lab
shader makes a NaN, so the second is the top of the page of tests/hard_cases/pow_edge.glsl (pow of a
negative base on half the image): its renders, differences and the NaN origins the probe found,
under their source line.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from glslcheck.verification.report import build_report, load_in_browser  # noqa: E402


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default=str(ROOT / "build" / "report.html"))
    p.add_argument("--png", default=str(ROOT / "docs" / "report.png"))
    p.add_argument(
        "--height", type=int, default=2800, help="pixels of the lab page's top kept (default 2800)"
    )
    p.add_argument("--nan-png", default=str(ROOT / "docs" / "report_nan.png"))
    p.add_argument(
        "--nan-height",
        type=int,
        default=1560,
        help="pixels of the NaN page's top kept (default 1560)",
    )
    args = p.parse_args()
    os.chdir(ROOT)  # the page names the shaders as given: relative to the repository
    problems = shoot(
        ["lab_shaders"], args.out, args.png, args.height, title="glslcheck report: lab_shaders"
    )
    nan_out = str(Path(args.out).with_name("report_nan.html"))
    problems += shoot(
        ["tests/hard_cases/pow_edge.glsl"], nan_out, args.nan_png, args.nan_height, bench=None
    )
    return 1 if problems else 0


def shoot(paths, out: str, png: str, height: int, **options) -> list[str]:
    """Write the report of `paths` to `out`, open it in Chromium, keep the top `height` pixels in
    `png`."""
    from PIL import Image

    page = build_report(paths, size=(320, 180), time=1.7, **options)
    Path(out).parent.mkdir(parents=True, exist_ok=True)
    Path(out).write_text(page.html, encoding="utf-8")
    full = Path(out).with_suffix(".png")
    problems = load_in_browser(out, screenshot=full, height=height)
    for line in problems:
        print(line, file=sys.stderr)
    with Image.open(full) as im:
        im.convert("RGB").save(png, optimize=True)
    bad = [r.name for r in page.shaders if not r.ok]
    print(
        f"{out}: {len(page.shaders)} shaders, {len(bad)} with problems {bad}; {png} written;"
        f" {len(problems)} browser problems"
    )
    return problems


if __name__ == "__main__":
    sys.exit(main())
