"""The fix of `missing-header`: a header template whose fields the student fills in.

The template says only what is known (the file's name) and leaves each other field empty after
its label: `// Image.glsl:` (the purpose goes after the colon) and `// Contributors:` (each
name with what they did). A fix never writes a purpose or a contributor for the student, and
no placeholder text is written that the rule could take for one: the rule keeps reporting the
header until the student fills the fields in, so the fix is never safe."""

from __future__ import annotations

from ...shadertoy.sources import path_name
from . import Edit, Fix

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..engine import LintContext

WHY = (
    "a template: fill in the purpose after the file's name and the contributors with what each "
    "did; the rule reports the header until you do"
)


def header_fix(ctx: LintContext, missing: list[str] | None, header_end: int | None) -> Fix | None:
    """The lines to add: the whole template at the top when the file has no header comment
    (`missing` None), else a line for each part the header lacks, after its last line
    (`header_end`). Contributors listed without what each did have no template (only the
    student knows who did what): no fix for that part."""
    name = path_name(ctx.source.path)
    if missing is None:
        lines = [f"// {name}:", "// Contributors:"]
        at = 1
    else:
        lines = []
        if any(m.startswith("does not name the file") or m == "states no purpose" for m in missing):
            lines.append(f"// {name}:")
        if any(m.startswith("lists no contributors") for m in missing):
            lines.append("// Contributors:")
        if not lines or header_end is None:
            return None
        at = header_end + 1
    text = "".join(line + "\n" for line in lines)
    if at > len(ctx.lines):  # a file that is only its header: add after its last line
        last = len(ctx.lines)
        end = len(ctx.lines[last - 1]) + 1
        return Fix(
            "add a header template",
            ctx.path,
            (Edit(last, end, last, end, "\n" + text),),
            "unsafe",
            WHY,
        )
    return Fix("add a header template", ctx.path, (Edit(at, 1, at, 1, text),), "unsafe", WHY)
