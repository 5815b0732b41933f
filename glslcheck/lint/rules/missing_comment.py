"""Code that no comment explains, as a TA reads the comments.

## What it does
Reads the file as a TA does, statement by statement (a signature or a call written over several
lines is one statement), and reports each run of statements that no comment explains. The
model is what three blind readings of the rubric (three labellers, 49 student files) agree on;
where they part, the finding is a possible deduction (below).

Coverage, what a comment explains:
- A comment explains the statement or small group of statements it stands above: up to
  `comment-span` statements (5 by default: the rubric's "every few related lines"), until a
  blank line, the next comment, or the end of the block it is in. A statement with a trailing
  comment of its own uses none of the group's few lines: `// PHONG` above three commented
  lines and three plain ones explains all six, and nor does a statement that repeats one of
  the two before it but for its numbers or components (`d2y = p.y - q.y;` after `d1x = p.x -
  q.x;`, `initLight(light2, vec3(0.0, 1.0, 2.0));` after `initLight(light1, vec3(2.0, 1.0,
  0.0));`: one comment for the lines written once per light). Nor does a blank line part
  such a line from the one it repeats (`col.r += ...;`, blank, `col.g += ...;`: the group's,
  as the first is). Lines of a comment block explain as one comment. A comment above an `if`
  or a loop goes on into its body, and its `else`'s, a blank line before the `else` or not
  (one right above an `if` whose body has comment lines of its own: below). A comment
  heading a list of declarations (`// Variables for the camera`) explains the whole list, up
  to the blank line. A comment that names the variable its first statement sets (`//Variable t
  based off the ray hitting the sphere` above `float t = ...;`) speaks of what it names: its
  group ends at a statement that mentions none of its words nor a variable the group's
  statements set (`float w = ...;` right after: a run of its own). A declaration with no value
  sets nothing and stays in the group, `a`, `it` or `to` in a sentence name no variable, and
  a vector's components go together (`// x and y away from zero` names `z = z | k;` too).
- A trailing comment covers its statement (`x = 1.0; // why`, on any of its lines) and the
  statements right below it written the same way but for names and numbers (`vec4 image1 =
  texture(iChannel0, uv); // declare both textures` over `vec4 image2 = texture(iChannel1,
  uv);`; a third of the tokens at most differ), and on a
  signature, a loop/`if` header or an `else`, the block it opens as a comment above would. A
  trailing comment too long for its line, continued on the line below and indented well past
  the statement (8 columns or more), is that statement's too, and so is a comment on the
  opening brace's own line right under a signature or a header (`{ // a sine wave moving
  right`).
- A function's comment (above it, or a blank line above it when it names the function:
  `// shade: ...` above `vec3 shade(...)`) explains the function: its signature, and its body whole
  when the body is simple: at most 4 statements, with no branch or loop at 4, whatever comments
  of their own some of its lines have (a few related lines under one comment). A longer body
  with no comment of its own is one run, the body; a longer body with comments of its own is
  read by them. A struct's comment covers its members; a struct whose members are commented one
  by one needs no comment of its own. Overloads written right under a commented one, with no
  blank line between (`// lengthSq: the squared length of a vector` above `lengthSq(vec2)`,
  `lengthSq(vec3)`, `lengthSq(vec4)`), are one group that comment explains; after a blank line
  an overload is a definition of its own and needs its own comment. A definition right under
  a commented one whose comment names it in words (`// hash: a random value; hashSigned maps
  it to [-1, 1)` above `hash`, then `hashSigned`; not in code: `hashSigned(`) is that
  comment's too. A body that opens with a comment saying what the function does (`vec3
  gradient(vec2 p) {`, then `// makes a magenta and green gradient`) explains its signature:
  readers take it for the function's comment; a note, no deduction, suggests moving it above
  (not for `mainImage`, the signature every Shadertoy shader starts with).
- The comments of Shadertoy's new-shader template ("Normalized pixel coordinates (from 0 to
  1)", "Time varying pixel color", "Output to screen") speak of the template's line under them:
  they cover that line, the same line written again but for its numbers (`vec3 col2 = ...`
  under `vec3 col = ...`) and, under "Output to screen", the writes of `fragColor`; an aspect
  fix added under the first (`uv.x *= iResolution.x / iResolution.y;`) needs its own comment.
- Trivial statements need no comment: returning a literal or a plain variable (`return true;`,
  `return col;`, or a vector of them: `return vec4(col, 1.0);`), `break;`, `continue;`,
  `discard;`, `else`, braces. Code in an `#ifdef`/`#if` branch the preprocessor skips is not
  compiled and not linted (where that is sure: `#ifdef`, `#ifndef`, `#if defined(X)`, `#if 0`).
- Credits and attributions ("Code from class by ...", "Code by Peter Shirley in ...", "code
  translated from ...", "function taught during Tuesday's class by ...", "Source for math:
  https://...", "following code by me", "Followed this tutorial for tone mapping https://...",
  "This is a modified version of https://..."), section markers ("// part 3", "// TEST",
  "// END CLASS MATERIAL", a `-----` rule), a bare question ("// efficient?"), a status note
  ("//Largely untested", "//WORKING!!!": how the code fares, not why it is there) or a note of
  not knowing ("//figure out what this thing is"), commented-out code (`//dp.z = r * r;`, a type
  name left alone: `//bool`) and `glslcheck:` directives explain nothing: a TA reads past them. A
  condition written out in words is not code:
  `// if (x - cx)^2 + (y - cy)^2 <= r^2 then p is inside` explains the `if` below it.

Runs, what one finding is: one finding per run of uncovered statements, at its first line and
naming its last, as the rubric deducts "per ambiguous section/block/line". A run goes on across
blank lines and commented-out code: uncommented code is one ambiguous section however it is
spaced. It ends at an explaining comment, a covered statement, a credit or a section marker
(they start another part), and the close of the block it started in (`} else {` goes on): a
run that reaches into an `if`'s or a loop's body goes on past its close, since an uncommented
stretch with a branch in it is still one section. Each
top-level function or struct is a run of its own (global declarations in a row are one region,
however blank lines space them), and a function with no explaining comment
anywhere is one run from its signature to its last line: the one ambiguous block the rubric
deducts once. That holds in a mostly uncommented file too: a few readers deduct each group a
blank line parts there, most read the stretch as one section.

A run is a certain deduction, except where the readings of the rubric part (a possible one):
- the code of a section below its heading, parted from it by a blank line, when the heading is
  a comment with a blank line below it (`// SCENE`, blank, the scene's code) or a few words
  naming a stage (`// Lambertian Reflectance`, `//sphere info`) whose own group a blank line
  ends (one reading lets a heading explain its section, one lets it explain nothing, one deducts
  each group); a credit or a marker ends a heading's section;
- the body of a function its comment above is the only comment of, when the body is more than
  simple but short (at most 8 statements) or does not branch; a longer branching body is certain;
- the first statements of a body longer than simple that has comments of its own, which the
  function's comment above would cover as a comment above a group (whether a function's
  comment reaches into its body is a reading);
- the first statements of an `if`'s body that has comment lines of its own, under a comment
  right above the `if` (not one whose group the `if` is further down in) or trailing its
  header (`else if (x < 0.75) // the middle band`): that comment speaks for the condition
  (`// if the discriminant is positive, the ray hits`), the body's comments for the rest;
  whether it reaches the body's first statements is a reading, and the group it started ends
  with the block;
- a definition with no comment at all right under another (blank lines between, nothing else),
  each after the first: one reading deducts such a region once, the others each definition.
- the lines under a bare label of their kind (`// Variables`, `// Set Variables`,
  `//Constants`): it names what the lines are, not why they are there; one reading deducts
  them, another takes the label for their comment.

Examples, all covered: the function's comment covers both signature lines and the short body,
`return true;` and `return false;` need none, the trailing comment covers its two-line call:
```glsl
// inCircle: whether p lies in the circle of centre c and radius r (no square root)
bool inCircle(in vec2 p, in vec2 c,
              in float r)
{
    vec2 d = p - c;
    if (dot(d, d) <= r * r)
    {
        return true;
    }
    return false;
}
vec4 lit = shade(position, normal, // lit colour of the surface point
                 light);
```
and not covered: one finding for the two statements after the covered one, blank line and
commented-out code notwithstanding (an attribution explains nothing), and a second after the
marker, which starts another part:
```glsl
// scene: the offset of p from the scene's origin
void scene(out vec3 dp, in vec3 p)
{
    dp = vec3(0.0); // start from the origin
    // Code from class by Daniel Buckstein
    dp = p * 2.0;

    //dp.z = p.z * p.z;
    dp.z = p.z;
    // part 3
    dp.x += 1.0;
}
```

## Why is this bad?
The course's coding standards: "Every section, block and line of code must be commented
(-1 per ambiguous section/block/line). Clearly state the intent, the 'why' behind each section,
block and even line (or every few related lines) of code."

## Example
```glsl
float d = length(p - c);
float a = 1.0 / (1.0 + d / I + d * d / (I * I));
vec3 col = a * lightColor;
```

## Use instead
```glsl
// attenuate the light with distance (constant, linear and quadratic terms)
float d = length(p - c);
float a = 1.0 / (1.0 + d / I + d * d / (I * I));
vec3 col = a * lightColor; // the light reaching the surface
```
"""

from __future__ import annotations

import re

from ...base.diagnostics import Diagnostic
from ...base.records import record
from ...base.regexes import compiled
from ..textscan import (
    BLANK,
    BRACE,
    BRACE_COMMENT,
    CODE,
    COMMENT,
    DIRECTIVE,
    LEADING,
    TRAILING,
    LineKind,
    inactive_lines,
)
from ._comment_kinds import (
    BARE_RE,
    COMMENTED_CODE_RE,
    LIST_HEADING,
    TEMPLATE_COMMENT,
    TRIVIAL_RE,
    is_heading,
    line_explains,
)

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "missing-comment"
PENALTY = 1
STANDARD = "comments"
SEVERITY = "warning"
NEEDS = "text"

HELP = "add a comment above saying why these lines are there"
# Why a run is only a possible deduction: a reading of how far a comment reaches.
HEADING = "only a section heading explains it, parted from it by a blank line"
BODY_ONLY = "the function's first body comment says what it does, none stands above it"
REACH = "whether the function's comment above reaches into a body that has comments of its own"
IF_REACH = "whether the `if`'s comment, above or beside it, reaches a body with comments of its own"
LONG_BODY = "only the function's comment above explains its body, which is more than a few lines"
ADJACENT = "one of several uncommented definitions in a row, which a TA may deduct once"
BARE = "only a bare label ('Variables', 'Constants') stands above it, naming what it declares"


@record
class _Cover:
    """A comment's coverage: the block depth it was written at and the statements it has left."""

    depth: int
    left: int
    text: str = ""  # the comment's words (a definition's name in them: it documents it)
    shapes: tuple = ()  # the statements read under it, their numbers masked (_SHAPE_RE)
    # when it names the variable its first statement sets (`//Variable t ...` above `float t =
    # ...;`): its words and the variables its statements set, what it speaks of (speaks_of)
    names: frozenset = frozenset()


# numbers, in literals and in names (`light2`, with a component after it: `temp2y`), and a
# one-component selector (`col.r`, `p.x`)
_SHAPE_RE = compiled(r"\d+[xyzwrgba]\b|\d+(?:\.\d*)?|\.\d+|(?<=\.)[xyzwrgba]\b")
_NAME_RE = compiled(r"(\w+)\s*(?:\(|\{|$)")  # a definition's name: before its `(` or `{`
_SIGNATURE_RE = compiled(r"^(?:[A-Za-z_]\w*\s+)+[A-Za-z_]\w*\s*\([^;]*\)\s*\{?\s*$")
_SIGNATURE_START_RE = compiled(r"^(?:[A-Za-z_]\w*\s+)+[A-Za-z_]\w*\s*\(")
_HEADER_RE = compiled(r"^\}?\s*(?:if|for|while|else\s+if|switch)\s*\(")  # a control header
_IF_RE = compiled(r"^\}?\s*(?:else\s+)?if\s*\(")
_ELSE_RE = compiled(r"^\}?\s*else\b")
_STRUCT_RE = compiled(r"^struct\b")
# the variable a statement sets: `float t = ...;`, `uv.x *= ...;`, `const vec3 c[2] = ...;`
_SETS_RE = compiled(
    r"^(?:const\s+)?(?:(?:high|medium|low)p\s+)?(?:[A-Za-z_]\w*\s+)?([A-Za-z_]\w*)"
    r"(?:\[[^\]]*\])?(?:\.\w+)*\s*[-+*/]?=(?!=)"
)
_WORD_RE = compiled(r"[A-Za-z_]\w*")
_NAME_NUMBER_RE = compiled(r"(?<=[A-Za-z_])#")  # a masked number ending a name (`col#`)
_OUTPUT_RE = compiled(r"output to screen", re.I)  # the template's comment over the output
_WRITES_OUTPUT_RE = compiled(r"^fragColor\b(?:\.\w+)?\s*[-+*/]?=(?!=)")  # a write of the output
_AXES = (frozenset("xyzw"), frozenset("rgba"))  # variables named as a vector's components
# words of a sentence that may also name a variable (`// a ramp` above `float a = ...;`)
_FUNCTION_WORDS = frozenset("a an and as at by is it of on or to".split())
_BRACES_RE = compiled(r"\{+|\}+")


def _function_name(signature: str) -> str:
    name = _NAME_RE.search(signature.split("(")[0] + "(")
    return name.group(1) if name else ""


# how much deeper than its statement a comment line below it sits when it is that statement's
# trailing comment wrapped (a comment for the next block sits at its indentation, 4 deeper)
WRAPPED = 8


def _column(line: str) -> int:
    """The column a line's text starts at, tabs to 4."""
    expanded = line.expandtabs(4)
    return len(expanded) - len(expanded.lstrip())


UNLIMITED = 1 << 30  # the span of a comment heading a list: up to the blank line
SIMPLE_BODY = 4  # statements of a function its comment above explains whole, with no branch
SHORT_BODY = 8  # more, or a branching body longer than this, is a certain run under that comment
_GOES_ON = (",", "+", "-", "*", "/", "=", "&", "|", "?", ":", "<", ">", "(", "!")


_TOKEN_RE = compiled(r"[A-Za-z_]\w*|\d+(?:\.\d*)?|\.\d+|\S")


def _parallel(trailed: tuple[list[str], int], tokens: list[str], depth: int) -> bool:
    """Whether a statement (its `tokens`, at `depth`) is written as the trailing-commented one
    above it but for names and numbers: the same tokens in the same order, at most a third of
    them (and at least one) a different name or number."""
    above, at = trailed
    if at != depth or len(above) != len(tokens) or len(tokens) < 3:
        return False
    differ = 0
    for a, b in zip(above, tokens):
        if a != b:
            if not (a[0].isalnum() or a[0] in "_.") or not (b[0].isalnum() or b[0] in "_."):
                return False  # an operator or a bracket differs: another statement
            differ += 1
    return 0 < differ and 3 * differ <= len(tokens)


def _unnumbered(shape: str) -> str:
    """A statement's shape with the numbers after names dropped (`col` and `col2` alike)."""
    return _NAME_NUMBER_RE.sub("", shape)


def _template_goes_on(cover: _Cover, shape: str, text: str) -> bool:
    """Whether a statement past a template comment's one line is still its own: that line
    written again but for its numbers (`vec3 col2 = ...` under `vec3 col = ...`), or under
    "Output to screen" another write of the output."""
    if not TEMPLATE_COMMENT.match(cover.text):
        return False
    if _unnumbered(shape) in map(_unnumbered, cover.shapes[-2:]):
        return True
    return _OUTPUT_RE.search(cover.text) is not None and _WRITES_OUTPUT_RE.match(text) is not None


def _simple(function: dict) -> bool:
    """Whether a function's body is "a few related lines" its comment above explains whole: at
    most SIMPLE_BODY statements, with no branch or loop at SIMPLE_BODY."""
    count = function["count"]
    return count < SIMPLE_BODY or (count == SIMPLE_BODY and not function["branches"])


class _Reader:
    """Reads a file's lines into statements and decides which are covered (see uncovered_runs)."""

    def __init__(self, scan, kinds: list[LineKind], span: int):
        self.scan, self.kinds, self.span = scan, kinds, span
        self.code = scan.code_lines
        self.on_line: dict[int, list] = {}  # line -> the comments on it (built once: linear)
        for c in scan.comments:
            for n in range(c.line, c.end_line + 1):
                self.on_line.setdefault(n, []).append(c)
        self.runs: list[tuple[int, int, int, str]] = []
        self.run: list | None = None  # [first, last, code lines, reading or ""]
        self.run_depth = 0  # the block depth the open run started at
        # the depth of a heading: an explaining comment followed by a blank line. Whether it
        # explains the groups of its section below the blank is a reading (a possible deduction)
        self.heading: int | None = None
        self.signature_run = False  # the open run is one function signature, nothing more
        # the top-level function being read: {"sig": its signature lines, "explained": whether
        # a comment explains the signature, "inner": whether one explains anything in its
        # body, "count": its body's statements, "last": its last code line, "runs": the index
        # of its first run}
        self.function: dict | None = None
        # the last signature read: its lines, whether a comment explains it, and that comment
        self.signature: tuple[list[int], bool, str] | None = None
        self.cover: _Cover | None = None
        self.above: _Cover | None = None  # a top-level comment a blank line parts from its code
        self.depth = 0
        self.blocks: list[str] = []  # per open block: "struct", "function" or "other"
        self.statement: list[int] = []  # the lines of the statement being read
        self.start_depth = 0  # the depth the statement started at
        self.parens = 0
        self.last_head = ""  # the last statement read (what a `{` on the next line opens)
        # an uncovered function or struct header, decided by its body: the body's first
        # statement explained by a comment of its own (or its members) explains it too
        self.deferred: list[int] | None = None
        self.blank = False  # a blank line was read and not yet acted on
        self.after_open = False  # the last line read ended with `{`
        self.last_comment = 0  # the last explaining comment line
        self.macro = False  # the last preprocessor line ended with a backslash
        self.number = 0  # the line being read
        self.def_start = 0  # the first line of the top-level definition being read
        self.bare_end = 0  # the last line of the last definition with no comment at all
        self.reach = 0  # body statements a function's or an if's comment above may reach
        self.reach_reading = REACH  # which of the two (REACH or IF_REACH)
        self.own_header = False  # the last statement read was a control header with its comment
        self.header_line = 0  # the first line of the last statement read
        self.closed_at = 0  # the line the last top-level definition closed on
        self.previous: tuple[str, bool] | None = None  # the last function: name, explained
        self.previous_said = ""  # the words of the comment above the last function
        self.parted: _Cover | None = None  # the group a blank line in a body just ended
        # the tokens and depth of the last statement its own trailing comment explains: the
        # statements right below it written the same way but for names and numbers share it
        self.trailed: tuple[list[str], int] | None = None

    def explains(self, number: int) -> bool:
        return line_explains(self.on_line.get(number, []), number)

    def close_run(self) -> None:
        if self.run is not None:
            self.runs.append((self.run[0], self.run[1], self.run[2], self.run[3]))
            self.run = None

    def add_to_run(self, lines: list[int], signature: bool = False) -> None:
        if self.run is None:
            under_heading = self.heading is not None and self.cover is None
            reach = self.reach > 0 and self.function is not None and self.depth > 0
            reading = self.reach_reading if reach else HEADING if under_heading else ""
            self.run = [lines[0], lines[-1], len(lines), reading]
            self.run_depth = self.depth
            self.signature_run = signature
        else:
            self.run[1] = lines[-1]
            self.run[2] += len(lines)
            self.signature_run = False

    def settle_deferred(self, explained: bool) -> None:
        if self.deferred is not None:
            if not explained:
                self.add_to_run(self.deferred)
            self.deferred = None

    def own_comment(self, lines: list[int]) -> bool:
        """A comment of the statement's own: trailing one of its lines, or a trailing comment
        wrapped to the line below it (a comment line indented well past the statement)."""
        if any(self.kinds[n - 1] in (TRAILING, LEADING) and self.explains(n) for n in lines):
            return True
        below = lines[-1] + 1
        if below > len(self.kinds):
            return False
        if self.kinds[below - 1] is BRACE_COMMENT and self.code[below - 1].strip() == "{":
            # `{ // why` under a signature or a header: its opening brace's comment is its own
            return self.explains(below)
        if self.kinds[below - 1] is not COMMENT:
            return False
        return _column(self.scan.lines[below - 1]) >= _column(
            self.scan.lines[lines[0] - 1]
        ) + WRAPPED and self.explains(below)

    def finish(self) -> None:
        """Decide the statement read so far: covered, trivial or uncovered."""
        if not self.statement:
            return
        lines = list(self.statement)
        self.statement.clear()
        self.parens = 0
        text = " ".join(self.code[n - 1].strip() for n in lines)
        self.last_head = text
        top = self.start_depth == 0
        header = top and (
            _SIGNATURE_RE.match(text) is not None or _STRUCT_RE.match(text) is not None
        )
        if header:
            self.def_start = lines[0]
        if header and self.cover is None and self.above is not None:
            name = _NAME_RE.search(text.split("(")[0] + "(")
            if name and re.search(rf"\b{re.escape(name.group(1))}\b", self.above.text):
                self.cover = self.above  # the definition's own comment, across a blank line
        self.above = None
        if TRIVIAL_RE.match(text):
            if _ELSE_RE.match(text) and self.own_comment(lines):
                # `else // why`: its comment speaks for the block it opens, as on an `if`'s header
                self.cover = _Cover(self.start_depth, self.span)
                self.close_run()
            return  # needs no comment; neither covers nor breaks a run
        in_struct = bool(self.blocks) and self.blocks[-1] == "struct"
        shape = _SHAPE_RE.sub("#", text)
        parted, self.parted = self.parted, None
        if (
            self.cover is None
            and parted is not None
            and parted.depth == self.start_depth
            and parted.shapes[-1:] == (shape,)
        ):
            # the line before the blank written again for the next channel or light: a blank
            # line between such lines does not part them from their group
            self.cover = parted
        cover = self.cover
        covered = cover is not None and (cover.left > 0 or _template_goes_on(cover, shape, text))
        if cover is not None and not covered and TEMPLATE_COMMENT.match(cover.text):
            self.cover = cover = None  # the template's line and its repeats end there
        own = self.own_comment(lines)
        trailed, self.trailed = self.trailed, None
        tokens = _TOKEN_RE.findall(text)
        if own and not header:
            self.trailed = (tokens, self.start_depth)
        elif trailed is not None and not header and _parallel(trailed, tokens, self.start_depth):
            # `vec4 image1 = ...; // declare both textures` over `vec4 image2 = ...;`
            own = True
            self.trailed = trailed
        if covered and not (in_struct or header or own) and not self.speaks_of(text, shape):
            self.cover = cover = None  # the comment's group ends: it does not speak of this
            covered = False
        bare = covered and not (in_struct or header or own)
        bare = bare and cover is not None and BARE_RE.match(cover.text) is not None
        if covered and not (in_struct or header or own):
            # a statement its own comment explains uses up none of the group above's few lines
            assert cover is not None  # covered: a cover with lines left
            if shape not in cover.shapes[-2:]:  # a line repeated but for its numbers: none
                cover.left -= 1
        if cover is not None:
            cover.shapes = (*cover.shapes, shape)
        self.own_header = own and _HEADER_RE.match(text) is not None
        self.header_line = lines[0]
        if own and (header or _HEADER_RE.match(text)):
            # `float f(float x) // why`, `for (...) // why`: it explains what the block does
            self.cover = _Cover(self.start_depth, self.span)
        if header and _STRUCT_RE.match(text) and not covered and not own:
            self.settle_deferred(False)
            self.deferred = lines  # its members' comments may explain it
            return
        if header:
            self.heading = None  # a definition with no comment of its own: certain
        if header and not _STRUCT_RE.match(text):
            self.signature = (lines, covered or own, cover.text if covered and cover else "")
        elif self.function is not None and self.start_depth > 0:
            self.function["count"] += 1
            self.function["first"] = self.function["first"] or lines[0]
            self.function["last"] = lines[-1]
            self.function["inner"] = self.function["inner"] or own
            self.function["branches"] = self.function["branches"] or bool(_HEADER_RE.match(text))
        if self.start_depth > 0 and not in_struct:
            self.reach -= 1  # as a comment above would, past trailing comments
        if bare:
            # under a bare label only: a run whose deduction is a reading
            self.settle_deferred(False)
            if self.run is not None and self.run[3] != BARE:
                self.close_run()
            self.add_to_run(lines)
            assert self.run is not None
            self.run[3] = BARE
        elif covered or own:
            self.settle_deferred(own or in_struct)
            self.close_run()
        else:
            self.settle_deferred(False)
            if self.run is not None and self.run[3] == BARE:
                self.close_run()  # the bare label's lines end: certain ones start
            self.add_to_run(lines, signature=header and not _STRUCT_RE.match(text))

    def speaks_of(self, text: str, shape: str) -> bool:
        """Whether the group comment above a statement speaks of it. A comment that names the
        variable its first statement sets (`//Variable t based off the ray` above `float t =
        ...;`) speaks of what it names: a later statement of its group that mentions none of its
        words nor a variable its group's statements set (`float w = ...;`) is not its."""
        cover = self.cover
        assert cover is not None  # covered
        if "=" not in text:
            return True  # a declaration with no value, a call: it sets nothing the comment names
        target = _SETS_RE.match(text)
        if not cover.shapes:  # the group's first statement
            named = target is not None and target.group(1) not in _FUNCTION_WORDS
            if (
                named
                and target is not None
                and re.search(rf"(?<![\w.]){re.escape(target.group(1))}\b", cover.text)
            ):
                names = {*_WORD_RE.findall(cover.text), target.group(1)}
                for axes in _AXES:  # `x` and `y` named: `z = z | k;` is one of them
                    if names & axes:
                        names |= axes
                cover.names = frozenset(names)
            return True
        if not cover.names or shape in cover.shapes[-2:]:
            return True  # a comment that names nothing, or a line repeated but for its numbers
        if cover.names.isdisjoint(_WORD_RE.findall(text)):
            return False
        if target:
            cover.names |= {target.group(1)}
        return True

    def braces(self, line: str) -> None:
        """Follow the blocks a line closes and opens, in the order written (`} else {`,
        `if (a) { b = 1; }`)."""
        for mark in _BRACES_RE.finditer(line):
            if mark.group()[0] == "}":
                self.close_blocks(line, len(mark.group()))
            else:
                self.open_blocks(len(mark.group()), line[mark.end() :])

    def close_blocks(self, line: str, closed: int) -> None:
        """Close `closed` blocks: what a comment covered in them, a run in them, a function."""
        for _ in range(closed):
            if self.blocks:
                self.blocks.pop()
            self.depth = max(self.depth - 1, 0)
            self.parted = None
            if self.cover is not None and (self.depth < self.cover.depth or self.depth == 0):
                self.cover = None  # the block ends, or the definition a top comment stood above
            if self.heading is not None and (self.depth < self.heading or self.depth == 0):
                self.heading = None  # the section's block, or its first definition, ends
            if self.depth == 0:
                self.settle_deferred(False)  # a body with nothing explained
                self.close_run()  # each top-level definition is a run of its own
                self.end_function()
                self.adjacent_definitions()
                self.closed_at = self.number
            elif not self.else_follows(line) and self.run_depth > self.depth:
                self.close_run()  # the block the run was in ends (`} else {` goes on)

    def open_blocks(self, opened: int, rest: str = "") -> None:
        """Open `opened` blocks of the statement just read (a struct, a function or other);
        `rest` is the line's code after the opening brace."""
        if opened:
            head = (
                " ".join(self.code[n - 1].strip() for n in self.statement)
                if self.statement
                else self.last_head
            )
            if _STRUCT_RE.match(head.lstrip()):
                what = "struct"
            elif self.depth == 0 and _SIGNATURE_RE.match(head.split("{")[0]):
                what = "function"
            else:
                what = "other"
            if what == "function" and (
                self.signature is None or self.signature[0][-1] < self.number - 1
            ):
                what = "other"  # a whole function on one line: one statement, a run of its own
            if what == "function" and self.signature is not None:
                lines, explained, said = self.signature
                self.signature = None
                self.function = {
                    "sig": lines,
                    "explained": explained,
                    "said": said,  # the words of the comment above it
                    "inner": False,
                    "count": 0,
                    "first": 0,
                    "branches": False,
                    "name": _function_name(" ".join(self.code[n - 1].strip() for n in lines)),
                    "after": self.closed_at == lines[0] - 1,  # right under the last definition
                    "last": lines[-1],
                    "runs": len(self.runs) - (0 if self.run is not None else 0),
                }
            if what == "function":
                # the function's comment explains the function: its signature, and its body whole
                # when that is simple and has no comment of its own (end_function). In a body with
                # comments of its own, whether it reaches the statements it would cover as a
                # comment above a group is a reading (REACH)
                self.reach = self.cover.left if self.cover is not None else 0
                self.reach_reading = REACH
                self.cover = None
            elif (
                self.cover is not None
                and (self.own_header or self.last_comment == self.header_line - 1)
                and _IF_RE.match(head.lstrip())
                and self.body_has_comments(rest)
            ):
                # a comment right above an `if`, or trailing its header, whose body has comments
                # of its own speaks for the condition: whether it reaches the body's first
                # statements is a reading, as for a function's comment (the group it started
                # ends with the block)
                self.reach, self.reach_reading = self.cover.left, IF_REACH
                self.cover = None
            self.blocks.extend([what] * opened)
            self.depth += opened

    def body_has_comments(self, rest: str) -> bool:
        """Whether the block opened on the line being read (its code after the `{`: `rest`) has
        a comment line of its own that explains, before the `}` that closes it."""
        depth, number = 1, self.number
        while True:
            for mark in _BRACES_RE.finditer(rest):
                depth += len(mark.group()) if mark.group()[0] == "{" else -len(mark.group())
                if depth <= 0:
                    return False
            number += 1
            if number > len(self.kinds):
                return False
            kind = self.kinds[number - 1]
            if kind in (COMMENT, LEADING, BRACE_COMMENT) and self.explains(number):
                return True
            rest = self.code[number - 1]

    def adjacent_definitions(self) -> None:
        """A definition with no comment at all right under another (blank lines between, nothing
        else): one reading deducts the uncommented region once, others each definition, so
        every one after the first is a possible deduction."""
        last = self.runs[-1] if self.runs else None
        bare = last is not None and last[0] == self.def_start and last[3] == ""
        if (
            last is not None
            and bare
            and self.bare_end
            and all(self.kinds[n - 1] is BLANK for n in range(self.bare_end + 1, self.def_start))
        ):
            self.runs[-1] = (*last[:3], ADJACENT)
        self.bare_end = self.number if bare or (last and last[3] == ADJACENT) else 0

    def marks(self, number: int) -> bool:
        """Whether a comment line that explains nothing marks a part: a credit or a section
        marker, not commented-out code, an empty comment or a directive."""
        for c in self.on_line.get(number, ()):
            if c.is_directive:
                continue
            text = c.text.split("\n")[number - c.line] if c.end_line > c.line else c.text
            body = text.strip().strip("/*!").strip()
            if body and not COMMENTED_CODE_RE.match(body):
                return True
        return False

    def else_follows(self, line: str) -> bool:
        """Whether the block a `}` closes goes on in an `else` (on its line or the next code
        line)."""
        rest = line.split("}")[-1].strip()
        if rest:
            return rest.startswith("else")
        following = (
            self.code[n - 1].strip()
            for n in range(self.number + 1, len(self.kinds) + 1)
            if self.kinds[n - 1] is not BLANK and self.kinds[n - 1] is not COMMENT
        )
        return next(following, "").startswith("else")

    def end_function(self) -> None:
        """A function read whole (see uncovered_runs): one with no comment anywhere is one run, the
        ambiguous block the rubric deducts once; one whose comment above is its only comment is
        explained whole when its body is simple, else its body is one run."""
        f, self.function = self.function, None
        self.reach = 0
        if f is None:
            return
        # an overload right under a commented one (no blank line): that comment speaks for both
        overload = f["after"] and self.previous == (f["name"], True)
        # ... and a definition right under one whose comment names it (`// rand: ...; random_float
        # is an alteration of it` above `rand`, then `random_float`): that comment speaks for it
        overload = overload or bool(
            f["after"]
            and self.previous is not None
            and self.previous[1]
            and f["name"]
            and re.search(rf"\b{re.escape(f['name'])}\b(?!\s*\()", self.previous_said)
        )
        self.previous = (f["name"], f["explained"] or (overload and not f["inner"]))
        self.previous_said = f["said"] if f["explained"] else ""
        mine = self.runs[f["runs"] :]
        if not f["explained"] and not f["inner"] and mine:
            first = min(f["sig"][0], mine[0][0])
            count = sum(r[2] for r in mine)
            # an overload right under a commented one, no blank line between: one group the
            # comment above explains
            self.runs[f["runs"] :] = [] if overload else [(first, f["last"], count, "")]
        elif f["explained"] and not f["inner"]:
            kept = [r for r in mine if r[1] < f["sig"][0]]
            if not _simple(f):
                # more than "a few related lines" under one comment: one run, the body; certain
                # when it is long and branches, else a reading of how far a comment reaches
                sure = f["count"] > SHORT_BODY and f["branches"]
                kept.append((f["first"], f["last"], f["count"], "" if sure else LONG_BODY))
            self.runs[f["runs"] :] = kept
        elif f["explained"] and _simple(f):
            # a simple body is "a few related lines": its function's comment explains it
            # whole, whatever comments of their own some of its lines have
            self.runs[f["runs"] :] = [r for r in mine if r[3] != REACH]

    def new_comment(self, number: int) -> None:
        """An explaining comment line: it covers the group below it (a run of comment lines is
        one comment)."""
        if self.run is not None and self.signature_run and self.after_open and self.depth == 1:
            if self.function is not None and self.function["name"] == "mainImage":
                # Shadertoy's entry point, its signature the one every new shader starts with:
                # its purpose is known, and its body's comments say what it does
                self.run = None
            else:
                self.run[3] = BODY_ONLY  # the body opens with what the function does
        if self.function is not None and self.depth > 0:
            self.function["inner"] = True
        self.close_run()
        self.heading = None
        self.reach = 0
        text = " ".join(c.text for c in self.on_line.get(number, ()))
        span = self.span
        if LIST_HEADING.match(text):
            span = UNLIMITED  # a list's heading: the whole list
        elif TEMPLATE_COMMENT.match(text):
            span = 1  # the template's comment: its own line (and its copies: _template_goes_on)
        if self.cover is not None and self.last_comment == number - 1:
            self.cover.left = max(self.span, span)
            self.cover.text += " " + text
        else:
            self.cover = _Cover(self.depth, span, text)
        self.last_comment = number

    def complete(self) -> bool:
        """Whether the statement being read can end here (a blank or comment line follows): its
        parentheses are closed and its last line does not end with an operator or a comma."""
        last = self.code[self.statement[-1] - 1].rstrip() if self.statement else ""
        return self.parens <= 0 and not last.endswith(_GOES_ON)

    def read(self) -> list[tuple[int, int, int, str]]:
        for number, kind in enumerate(self.kinds, start=1):
            self.number = number
            if kind is not CODE and kind is not TRAILING and self.statement and self.complete():
                self.finish()  # `GEN_DECLARE(float)` with no `;`, then a blank or a comment
            if kind is BLANK:
                self.blank = True
                self.macro = False
                self.trailed = None
                continue
            if kind is DIRECTIVE:
                continue  # a glslcheck directive, or code the preprocessor skips
            line = self.code[number - 1].strip()
            if self.blank and not self.statement:
                self.blank = False
                # a blank line parts groups; one next to a brace or before an `else` (the
                # `if` statement goes on) parts nothing
                if not line.startswith(("}", "else")) and not self.after_open:
                    if self.depth == 0 and self.cover is not None:
                        self.above = self.cover
                    if (
                        self.cover is not None
                        and self.last_head  # not the file's header: no code read yet
                        and (self.cover.left == self.span or is_heading(self.cover.text))
                    ):
                        # a comment with a blank line below it, or a heading naming a stage
                        # whose group a blank line ends: it may head the section below
                        self.heading = self.cover.depth
                    self.parted = self.cover if self.depth > 0 else None
                    self.cover = None
                    self.reach = 0
                    declarations = (
                        self.depth == 0
                        and self.last_head.endswith(";")
                        and not _SIGNATURE_START_RE.match(line)
                        and not _STRUCT_RE.match(line)
                    )
                    if self.depth == 0 and not declarations:
                        # between definitions (global declarations in a row, blank lines
                        # between them, are one region); in a body a run goes on
                        self.close_run()
            self.blank = False
            opened_before = self.after_open
            self.after_open = line.endswith("{")
            explaining = kind is not CODE and kind is not BRACE and self.explains(number)
            if kind is COMMENT:
                self.trailed = None
                if not explaining and not self.statement and self.marks(number):
                    self.heading = None  # a credit or a marker starts a part no heading explains
                    self.reach = 0  # ... nor the function's comment
                    self.parted = None  # ... nor the group a blank line parted
                    self.close_run()  # ... and a new run: what follows is another part
                if explaining and not self.statement:
                    self.after_open = opened_before
                    self.new_comment(number)
                    self.after_open = False
                continue
            if kind is BRACE or kind is BRACE_COMMENT:
                if self.statement and self.parens <= 0:
                    self.finish()
                self.braces(line)
                self.last_head = line
                if kind is BRACE_COMMENT and explaining:
                    self.new_comment(number)
                continue
            if kind is LEADING and explaining and not self.statement:
                self.new_comment(number)
            if not self.statement:
                self.start_depth = self.depth
            if self.macro:  # a `#define` continued with a backslash: part of its statement
                self.macro = line.endswith("\\")
                continue
            if line.startswith("#"):  # a preprocessor line: a statement of its own
                self.finish()
                self.start_depth = self.depth
                self.statement.append(number)
                self.finish()
                self.macro = line.endswith("\\")
                continue
            self.statement.append(number)
            self.parens += line.count("(") - line.count(")")
            if self.parens <= 0 and self.ends(line):
                self.finish()  # at the depth it starts at; a `{` it ends with opens after it
            self.braces(line)
        self.finish()
        self.settle_deferred(False)
        self.close_run()
        return self.runs

    def ends(self, line: str) -> bool:
        """Whether `line` ends the statement being read."""
        if line.endswith((";", "{", "}")) or line == "else" or line.endswith(" else"):
            return True
        if line.endswith(")"):  # a header ends there (its body follows); an expression goes on
            first = self.code[self.statement[0] - 1].strip()  # a header shows on its first line
            return bool(_HEADER_RE.match(first) or _SIGNATURE_START_RE.match(first))
        return False


def uncovered_runs(scan, kinds: list[LineKind], span: int) -> list[tuple[int, int, int, str]]:
    """(first line, last line, number of code lines, reading) of each run of uncovered
    statements; `reading` is "" for a certain deduction, else why it is only a possible one
    (HEADING, REACH, IF_REACH, LONG_BODY, ADJACENT, BARE), or BODY_ONLY for a signature whose
    body's first comment explains it (a note, not a run).

    Statements are read whole (a signature or a call over several lines is one). A comment
    covers up to `span` statements below it, stopping at a blank line, the next explaining
    comment, or the end of its block; a function's comment covers its signature, and its body
    as end_function decides. A trailing comment covers its statement. Struct members and a
    function's signature use up none of the span; trivial statements need no comment; credits,
    markers and commented-out code explain nothing. A run ends at a covered statement, an
    explaining comment, a credit or a marker, the close of the block it started in, or (at top
    level) a blank line; in a body it goes on across blank lines and commented-out code."""
    return _Reader(scan, kinds, span).read()


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    # code the preprocessor skips (an inactive #ifdef branch) is not compiled: not linted
    inactive = inactive_lines(ctx.lines)
    kinds = (
        [DIRECTIVE if n in inactive else k for n, k in enumerate(ctx.line_kinds, start=1)]
        if inactive
        else ctx.line_kinds
    )
    for first, last, count, reading in uncovered_runs(ctx.scan, kinds, ctx.config.comment_span):
        yield _finding(ctx, first, last, count, reading)


def _finding(ctx: LintContext, first: int, last: int, count: int, reading: str) -> Diagnostic:
    if reading == BODY_ONLY:
        # advice, not a deduction: readers take the body's opening comment for the function's
        return Diagnostic(
            "the function's comment is the first line of its body, not above its signature",
            ctx.location(first),
            help="move that comment above the signature, where readers look for it",
            severity="note",
        )
    lines = f"line {first}" if first == last else f"lines {first}-{last}"
    noun = "line" if count == 1 else "lines"
    return Diagnostic(
        f"{count} {noun} of code without a comment that explains {'it' if count == 1 else 'them'}"
        f" ({lines})" + (f"; a possible deduction: {reading}" if reading else ""),
        ctx.location(first),  # the run's first line: where a suppression comment applies
        help=HELP,
        certainty="possible" if reading else None,
    )
