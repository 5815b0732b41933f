"""What a comment says, as the missing-comment rule reads it (not a rule: no NAME): whether it
explains code, or only credits, marks a part, labels declarations, heads a section or keeps
code commented out; and which statements need no comment at all."""

from __future__ import annotations

import re

from ...base.regexes import compiled

# A comment that only labels declarations by their kind (`// Variables`, `// Set Variables`,
# `//Constants`): it says what the lines are, which the code says too, not why they are there.
BARE_RE = compiled(
    r"^[\s/*!-]*(?:(?:set|setting|declare|declaring|define|defining|initiali[sz]e|initiali[sz]ing)"
    r"\s+)?(?:the\s+|all\s+|my\s+|some\s+)?(?:variables?|vars?|constants?|globals?)\s*:?\s*$",
    re.IGNORECASE,
)


# A comment that only credits or marks ("code from class by ...", "// part 3", "// TEST"):
# it says where the code came from or where a part starts, not why the code is there.
ATTRIBUTION_RE = compiled(
    r"^[\s*/!-]*(?:"
    r"(?:code\s+|taken\s+|copied\s+|adapted\s+|borrowed\s+)?from\s+(?:class|the\s+starter|lecture)\b[^.;]*"
    # "Code by Dan Buckstein", "following code by me"
    r"|(?:\w+\s+){0,3}by\s+(?-i:[A-Z][\w.]*)(?:\s+(?-i:[A-Z][\w.]*)){0,3}"
    r"|(?:\w+\s+){0,3}by\s+(?:me|myself|us|ourselves)"
    r"|(?:parts?|pt|step|section|task|ch(?:apter)?)\s*[#\d.]+(?:\s*(?:and|&|,|-)\s*[#\d.]+)*"
    r"|test|todo|(?-i:(?:START|END|BEGIN)(?:\s+[A-Z]+){0,3})|(?:\w+\s+){0,2}(?:start|end|begin)"
    # a status note ("Largely untested", "WORKING!!!", "still broken"): how the code fares, not
    # why it is there
    r"|(?:\w+\s+){0,2}(?:(?:un)?tested|work(?:s|ing)?|broken|wip|fixme)"
    # a note of not knowing ("figure out what this thing is"): what is not known, not why
    r"|(?:[\w']+\s+){0,3}(?:figure\s*out|not\s+sure|(?:don'?t|do\s+not)\s+know)\s+(?:what|why|how)\b.*"
    r"|-{3,}|={3,}|\*{3,})[\s*/!.:-]*$",
    re.I,
)
# Commented-out code: a statement, a declaration, a call or a control header kept in a comment.
COMMENTED_CODE_RE = compiled(
    # a control header ends in code (`)`, `{`, a statement); `// if (d < r) then it hits` is prose
    r"^\s*(?:(?:if|else\s+if|for|while)\s*\(.*[);{}]\s*"
    r"|return\b[^;]*;"
    r"|[\w.\[\]]+\s*[-+*/]?=\s*[^=][^;]*;"
    r"|(?:const\s+)?(?:float|u?int|bool|void|[biu]?vec[234]|mat[234]|(?-i:[A-Z]\w*|s[A-Z]\w*))"
    r"\s+[A-Za-z_]\w*\s*(?:=[^;]*)?;"
    r"|[\w.]+\s*\(.*\)\s*;"
    r"|[{}]\s*;?"
    # a type or a keyword left alone (`//bool` above a function returning float)
    r"|(?:const\s+)?(?:bool|float|u?int|void|[biu]?vec[234]|mat[234](?:x[234])?|struct|return"
    r"|else|in|out|inout|uniform))\s*(?://.*)?$"
)
# Statements that need no comment: returning a literal or a plain variable, break, continue,
# discard, a bare `else`.
TRIVIAL_RE = compiled(
    r"^\s*\}?\s*(?:return\s*(?:[-+]?[\w.]+|(?:[biu]?vec[234]|float|u?int|bool)\(\s*[-+]?[\w.]+"
    r"(?:\s*,\s*[-+]?[\w.]+)*\s*\))?\s*;|break\s*;|continue\s*;|discard\s*;|else)\s*\{?\s*\}?\s*$"
)


# A credit: a comment that names where code came from (a link, the starter, a reference).
CREDIT_RE = compiled(
    r"^[\s*/!-]*(?:https?://|www\.|(?:\w+\s+){0,2}based\s+on\b.*(?:https?://|www\.)"
    r"|(?:\w+\s+){0,2}(?:referenc\w*|sources?(?:\s+used)?\s*:|credits?\b|thanks?\s+to"
    r"|starter\s+code|glsl\s+starter|original\s+code|got\s+(?:help|assistance)|help\s+from"
    r"|assistance\s+from|source\s+assistance)"
    r"|(?:(?:code|this|it|functions?)\s+(?:was\s+|is\s+)?)?(?:adapted|borrowed|inspired|taken|copied)"
    r"\s+(?:from|by)\b"
    # "code translated from ...": with its subject, not "converted from degrees to radians"
    r"|(?:code|this|it|functions?)\s+(?:was\s+|is\s+)?(?:translated|ported|converted)\s+from\b"
    # "Code by Peter Shirley in ...", "Provided by Dan Buckstein during class", "Based of code ..."
    r"|(?:(?:base|original)\s+)?(?:code|functions?|framework)\s+(?:was\s+|is\s+)?"
    r"(?:written\s+|given\s+|provided\s+)?by\s*(?-i:[A-Z])"
    r"|(?:provided|written|modified|given)\s+by\s*(?-i:[A-Z])|based\s+(?:on|of)\s+(?:of\s+)?code\b"
    # "function taught during Tuesday's class by ...": what was taught in class, credited
    r"|(?:[\w']+\s+){0,8}taught\b.*\b(?:class|lecture|by\s+(?-i:[A-Z]))"
    # "These matrices from https://...", "Source for math: ...", "Link: ...", "Copy from Sphere",
    # "Idea for the wave was gotten from ...", "Used X as math references", "NOT ORIGINAL WORK"
    r"|(?:\w+\s+){0,4}from\s+(?:https?://|www\.)|sources?\b[^:]{0,20}:|links?\s*:|cop(?:y|ied)\s+from\b"
    r"|ideas?\b.*\b(?:from|by)\b|(?:\w+\s+){0,8}as\s+(?:\w+\s+)?references?\b|not\s+(?:my\s+)?original\b"
    # "Followed this tutorial for tone mapping https://...", "a modified version of https://..."
    r"|(?:\w+\s+){0,2}(?:followed|used|watched)\s+(?:this|the|a|an)\s+(?:\w+\s+){0,2}"
    r"(?:tutorial|guide|video|article)\b"
    r"|(?:\w+\s+){0,3}modified\s+version\s+of\s+(?:https?://|www\.))",
    re.I,
)


def explains(text: str) -> bool:
    """Whether a comment's text explains code: not empty, not a credit or a marker, not code."""
    body = text.strip().strip("/*!").strip()
    return (
        bool(body)
        and not (body.endswith("?") and len(body.split()) <= 2)  # "efficient?": a question
        and not ATTRIBUTION_RE.match(text)
        and not COMMENTED_CODE_RE.match(body)
        and not CREDIT_RE.match(body)
    )


def line_explains(comments: list, number: int) -> bool:
    """Whether a comment on line `number` explains (a block comment: its text on that line);
    `comments` are the comments on that line."""
    for c in comments:
        if c.is_directive:
            continue
        text = c.text.split("\n")[number - c.line] if c.end_line > c.line else c.text
        if explains(text):
            return True
    return False


# A section heading: a few words naming a stage (`// SCENE`, `// Lambertian Reflectance`,
# `//difCo vars`, `// Variable Declarations`), not a sentence about the next line.
HEADING_WORDS = compiled(
    r"\b(?:vars?|variables|declarations?|definitions?|parameters|constants|setup|scene|init\w*"
    r"|lighting|reflectance|shading|calculations?|calcs|helpers|utilit\w+|globals?|info)\b",
    re.I,
)
# A comment that heads a list of declarations ("// Variables for the camera"): the whole list,
# up to a blank line, is the group it explains, however long.
LIST_HEADING = compiled(
    r"^[\s/*!-]*(?:\w+\s+){0,2}(?:vars?|variables|declarations?|constants)\b", re.I
)

# The comments of Shadertoy's new-shader template, each over its one line (`vec2 uv =
# fragCoord/iResolution.xy;`, the cosine colour, `fragColor = vec4(col,1.0);`): they speak of
# that line, not of what a student adds under them (an aspect-ratio fix, a texture blend).
TEMPLATE_COMMENT = compiled(
    r"^[\s/*]*(?:normalized pixel coordinates \(from 0 to 1\)|time varying pixel colou?r"
    r"|output to screen)[\s.*/]*$",
    re.I,
)


def is_heading(text: str) -> bool:
    words = text.strip(" \t/*!-=:").split()
    if not words or len(words) > 5 or text.rstrip().endswith((".", ";", ")")):
        return False
    return words[0][:1].isupper() or HEADING_WORDS.search(text) is not None
