#!/usr/bin/env python3
"""Write the lab folder's report and the screenshot the README shows (docs/report.png).

    python tools/report_screenshot.py [--out build/report.html] [--png docs/report.png]

The page is loaded in the WebGL backend's headless Chromium (glslcheck.report.load_in_browser):
any console error, page error or network request fails the run. The screenshot is the top of
the page: the index and the first shader.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from glslcheck.report import build_report, load_in_browser  # noqa: E402


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default=str(ROOT / "build" / "report.html"))
    p.add_argument("--png", default=str(ROOT / "docs" / "report.png"))
    p.add_argument("--height", type=int, default=1500, help="pixels of the page's top kept (default 1500)")
    args = p.parse_args()
    os.chdir(ROOT)  # the page names the shaders as given: relative to the repository
    page = build_report(["lab_shaders"], size=(320, 180), time=1.7, title="glslcheck report: lab_shaders")
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(page.html, encoding="utf-8")
    full = Path(args.out).with_suffix(".png")
    problems = load_in_browser(args.out, screenshot=full, height=args.height)
    for line in problems:
        print(line, file=sys.stderr)
    from PIL import Image

    with Image.open(full) as im:
        im.convert("RGB").save(args.png, optimize=True)
    bad = [r.name for r in page.shaders if not r.ok]
    print(f"{args.out}: {len(page.shaders)} shaders, {len(bad)} with problems {bad}; {args.png} written;"
          f" {len(problems)} browser problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
