"""The grades page (`glslcheck grade -o grades.html`) in the real browser: it opens from disk
with no error and no request, every image inline, and a click on a column head sorts the rows."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

from glslcheck.verification.grade import Options, from_paths, grade_class, page_html
from glslcheck.verification.grade.grading import render_reference
from glslcheck.verification.report import load_in_browser

ROOT = Path(__file__).resolve().parents[2]
FINAL = ROOT / "lab_shaders" / "07_final"
OPTIONS = Options(size=(64, 36), times=(0.0, 1.7))


def _class(tmp_path: Path) -> list:
    bug = tmp_path / "bug"
    shutil.copytree(FINAL, bug)
    common = bug / "Common.glsl"
    common.write_text(
        common.read_text().replace("max(dot(normal, lightDir), 0.0)", "dot(normal, lightDir)")
    )
    broken = tmp_path / "broken<b>"  # a name the page must escape
    broken.mkdir()
    (broken / "Image.glsl").write_text("void mainImage(out vec4 c, in vec2 p) { c = vec4(p) }\n")
    paths = [str(FINAL), str(bug), str(ROOT / "lab_shaders" / "bonus_cel_shading"), str(broken)]
    return from_paths(paths)


def test_the_grades_page_opens_clean_and_sorts(tmp_path, webgl):
    reference = render_reference(FINAL, OPTIONS)
    grades = grade_class(_class(tmp_path), OPTIONS, reference, jobs=1)
    page = tmp_path / "grades.html"
    text = page_html(grades, OPTIONS, reference, "Lab 4 <grades>")
    page.write_text(text, encoding="utf-8")
    assert "<title>Lab 4 &lt;grades&gt;</title>" in text and "broken&lt;b&gt;" in text
    assert not re.search(r"""(src|href)=["'](?!data:|#)""", text)
    # three graded teams: a render and a diff per frame; the reference's renders; none of the
    # team that does not compile
    assert text.count('src="data:image/png;base64,') == 3 * 2 * 2 + 2
    assert load_in_browser(page) == []

    browser_page = webgl.new_page()
    try:
        browser_page.goto(page.resolve().as_uri())
        order = 'Array.from(document.querySelectorAll("table.grades tbody tr")).map(r => r.id)'
        ranked = browser_page.evaluate(order)
        assert ranked == ["team-07_final", "team-bug", "team-bonus_cel_shading", "team-broken<b>"]
        browser_page.click("th:text('team')")
        by_name = browser_page.evaluate(order)
        assert by_name == sorted(ranked, key=str.lower)
        browser_page.click("th:text('team')")
        assert browser_page.evaluate(order) == by_name[::-1]
        browser_page.click("th:text('#')")
        assert browser_page.evaluate(order) == ranked
    finally:
        browser_page.close()
