"""Reading shaders from disk: Shadertoy tab files, folders of them, and plain GLSL files.

A shader is given as one file per Shadertoy tab (`Image`, `Common`, `Buffer A`..`Buffer D`,
`Sound`, `Cube A`; extension `.glsl`, `.frag`, `.txt` or none; names matched case-insensitively
with spaces, `_` and `-` ignored, so `Buffer A.glsl` and `buffer_a.glsl` are the same tab) or a
folder of such files. A file whose name is not a tab name is taken as an Image tab. A folder
walk takes a `.txt` or extension-less file with another name when its text is shader code
(`looks_like_shader`: students name their tab files as they like, `Lab 4.txt` or `code.txt`).
A file with its own `#version` line and a `main()` is a plain GLSL ES fragment shader, taken as
it is. A `.json` file is Shadertoy's own export of a whole shader (`load_shadertoy_json`): its
passes become the tabs and its inputs the channel bindings.

Text is decoded as UTF-8 (a BOM is dropped) and line endings are normalised to `\n` (CRLF and
lone CR), which keeps every line and column of the user's file. Anything that cannot be read
raises `InputError` (exit 2) with the path and, for bad bytes, the line and column.
"""

from __future__ import annotations

import errno
import os
import re
import stat

from ..base.diagnostics import InputError, register_source
from ..base.records import field, record
from ..base.regexes import compiled

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable
    from pathlib import Path
    from typing import Any, NoReturn

    from .bindings import Binding

SHADER_EXTENSIONS = (".glsl", ".frag", ".txt", "")
# Canonical tab names in the order Shadertoy shows them.
TAB_NAMES = ("Common", "Buffer A", "Buffer B", "Buffer C", "Buffer D", "Cube A", "Sound", "Image")
BUFFER_TABS = tuple(t for t in TAB_NAMES if t.startswith("Buffer "))
_SEPARATORS = compiled(r"[\s_\-]")  # spaces, `_` and `-` in a tab file's name
_TAB_KEYS = {_SEPARATORS.sub("", t).lower(): t for t in TAB_NAMES}
# a bracketed part of a tab file's name: a description (`Buffer C (FIREBENDING)`), or the tab
# itself after the project's name (`GPR-200 Midterm (Buffer A)`)
_BRACKETS = compiled(r"\s*\(([^()]*)\)")
# a pass's word in a file's name (`Image`, `BufA`, `Buffer_A`, `CubeMap`), and Common's
_PASS_WORD = r"(?:image|buf(?:fer)?[\s_\-]?[a-d]|cube(?:[\s_\-]?map)?(?:[\s_\-]?a)?|sound)"
_TAB_WORD_ONLY = compiled(rf"(?i){_PASS_WORD}|common")
# the pass or Common first, then the project's name (`bufferB_lab6_name`, `common_lab6_name`)
_PASS_FIRST = compiled(rf"(?i){_PASS_WORD}[\s_\-]+(?=\S)")
_COMMON_FIRST = compiled(r"(?i)common[\s_\-]+(?=\S)")
_TAB_WORD = compiled(r"(?i)[\s_\-]+tab$")  # `Common Tab`, `midterm_common_tab`
MAX_FILE_BYTES = 1_000_000


# Paths as strings, without `pathlib`: importing it, with the `urllib.parse` and `ipaddress` it
# loads, would cost every `glslcheck lint` start-up. Each helper gives what the same
# `pathlib.Path` expression gives on POSIX, so every path a message names is spelt the same.


def posix_path(path: str | os.PathLike) -> str:
    """`str(PurePosixPath(path))`: empty and `.` parts and a trailing `/` dropped, `..` kept,
    a leading `//` kept as POSIX allows."""
    text = os.fspath(path)
    if text.startswith("/"):
        lead = "//" if text.startswith("//") and not text.startswith("///") else "/"
    else:
        lead = ""
    return lead + "/".join(part for part in text.split("/") if part and part != ".") or "."


def path_name(path: str | os.PathLike) -> str:
    """`PurePosixPath(path).name`."""
    text = posix_path(path)
    name = text[text.rfind("/") + 1 :]
    return "" if name == "." else name


def path_suffix(path: str | os.PathLike) -> str:
    """`PurePosixPath(path).suffix`: from the name's last dot, unless the name starts or ends
    there."""
    name = path_name(path)
    i = name.rfind(".")
    return name[i:] if 0 < i < len(name) - 1 else ""


def path_stem(path: str | os.PathLike) -> str:
    """`PurePosixPath(path).stem`."""
    name = path_name(path)
    suffix = path_suffix(name)
    return name[: len(name) - len(suffix)] if suffix else name


def folder_entries(folder: str) -> list[str]:
    """`sorted(Path(folder).iterdir())` as strings, for a folder spelt as `posix_path` spells it."""
    base = "" if folder == "." else folder if folder.endswith("/") else folder + "/"
    return [base + name for name in sorted(os.listdir(folder))]


@record
class Source:
    """One file's text: `path` is how the user named it (used in every message)."""

    path: str
    text: str
    tab: str = "Image"  # one of TAB_NAMES, or "GLSL" for a plain GLSL file

    @property
    def is_plain_glsl(self) -> bool:
        return self.tab == "GLSL"


@record
class Shader:
    """A Shadertoy shader: its tabs by canonical name (or one plain GLSL file)."""

    tabs: dict[str, Source] = field(default_factory=dict)
    root: str = ""
    channels: list[Binding] | None = (
        None  # bindings.Binding list of a Shadertoy JSON export (else channels.json)
    )

    @property
    def image(self) -> Source | None:
        return self.tabs.get("Image") or self.tabs.get("GLSL")

    @property
    def common(self) -> Source | None:
        return self.tabs.get("Common")

    def units_for(self, tab: str = "Image") -> list[Source]:
        """The texts compiled for a pass, in order: Common first (as Shadertoy does), then the
        tab."""
        src = self.tabs.get(tab)
        if src is None:
            raise InputError(f"{self.root}: no {tab} tab")
        if src.is_plain_glsl or tab == "Common" or self.common is None:
            return [src]
        return [self.common, src]

    def sources(self) -> list[Source]:
        return [self.tabs[t] for t in (*TAB_NAMES, "GLSL") if t in self.tabs]


def tab_name(path: str | os.PathLike) -> str | None:
    """The canonical tab a file name denotes, or None when it names no tab."""
    return _TAB_KEYS.get(_name_key(path))


def decode(data: bytes, path: str) -> str:
    """UTF-8 text with the BOM dropped and line endings normalised; InputError on bad bytes."""
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        before = (
            data[: e.start].decode("utf-8", "replace").replace("\r\n", "\n").replace("\r", "\n")
        )
        line = before.count("\n") + 1
        col = len(before) - (before.rfind("\n") + 1) + 1
        raise InputError(
            f"{path}:{line}:{col}: error: the file is not UTF-8 text (byte 0x{data[e.start]:02x}); "
            "save it as UTF-8"
        ) from None
    return text.replace("\r\n", "\n").replace("\r", "\n")


def read_source(path: str | os.PathLike, tab: str | None = None) -> Source:
    """Read one file as a Source; InputError when it is missing, unreadable, not a regular file,
    too big or not UTF-8."""
    spath = str(path)
    try:
        # O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused just below.
        fd = os.open(spath, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
        with os.fdopen(fd, "rb") as f:
            mode = os.fstat(f.fileno()).st_mode
            if not stat.S_ISREG(mode):
                raise InputError(
                    f"{spath}: error: {_not_regular(mode)}, not a regular file; "
                    "glslcheck reads shader files"
                )
            data = f.read(MAX_FILE_BYTES + 1)  # never more, whatever the file's size claims
        if len(data) > MAX_FILE_BYTES:
            size = max(os.path.getsize(spath), len(data))
            raise InputError(
                f"{spath}: error: the file is {size} bytes; glslcheck reads shader files up to "
                f"{MAX_FILE_BYTES} bytes"
            )
    except InputError:
        raise
    except OSError as e:
        raise InputError(f"{spath}: error: {os_error_text(e)}") from None
    text = decode(data, spath)
    register_source(spath, text)
    if tab is None:
        tab = tab_name(spath) or "Image"
    if _is_plain_glsl(text):
        tab = "GLSL"
    return Source(spath, text, tab)


def os_error_text(e: OSError) -> str:
    """What an OSError on opening a path means, in words ("no such file", "a symlink loop", ...)."""
    if e.errno == errno.ENOENT:
        return "no such file"
    if e.errno == errno.ELOOP:
        return "a loop of symbolic links (or too many of them in a row); it names no file"
    if e.errno == errno.EISDIR:
        return "is a directory"
    if e.errno in (errno.EACCES, errno.EPERM):
        return "permission denied"
    if e.errno == errno.ENOTDIR:
        return "a part of the path is not a folder"
    if e.errno == errno.ENAMETOOLONG:
        return "the file name is too long"
    return f"cannot read the file ({e.strerror or e})"


def check_path(path: str | os.PathLike) -> None:
    """InputError unless `path` names something (a file or folder): missing, a symlink loop, ..."""
    try:
        os.stat(path)
    except OSError as e:
        text = os_error_text(e)
        raise InputError(
            f"{path}: error: {'no such file or directory' if text == 'no such file' else text}"
        ) from None


def _not_regular(mode: int) -> str:
    for test, what in (
        (stat.S_ISFIFO, "is a FIFO (named pipe)"),
        (stat.S_ISCHR, "is a character device"),
        (stat.S_ISBLK, "is a block device"),
        (stat.S_ISSOCK, "is a socket"),
        (stat.S_ISDIR, "is a directory"),
    ):
        if test(mode):
            return what
    return "is a special file"


_VERSION_RE = compiled(r"^[ \t]*#[ \t]*version\b", re.M)
_MAIN_RE = compiled(r"\bvoid\s+main\s*\(\s*(void\s*)?\)")
_COMMENT_RE = compiled(r"/\*.*?(\*/|\Z)|//[^\n]*", re.S)


def _is_plain_glsl(text: str) -> bool:
    """Own `#version` and `main()` in the code: a `main()` or `#version` kept in a comment (the
    wrapper a student pasted as a note) does not make a Shadertoy tab a plain GLSL file."""
    code = _COMMENT_RE.sub(" ", text)
    return bool(_VERSION_RE.search(code)) and bool(_MAIN_RE.search(code))


def _is_tab_file(p: str) -> bool:
    return os.path.isfile(p) and name_says_shader(p) is True and tab_name(p) is not None


# Which files hold shader code. The name decides for `.glsl`/`.frag` files and Shadertoy tab
# names (`Image.txt`, `Common`); students name their other tab files as they like (`Lab 4.txt`,
# `code.txt`, `Lab4/main.txt`), so a `.txt` or extension-less file is a shader when its text is
# one: a `mainImage`, or GLSL declarations, in a text that reads as code rather than prose. A
# README, a licence, notes or Markdown is never taken for GLSL.
SNIFF_BYTES = 65_536  # how much of a file the sniff reads: a shader shows itself in its start
_NOT_SHADER_STEMS = frozenset(
    ("readme", "license", "licence", "copying", "changelog", "authors", "notice", "contributing")
)
_MAIN_IMAGE_RE = compiled(r"\bvoid\s+mainImage\s*\(")
_GLSL_TYPE = r"(?:void|bool|u?int|float|[biu]?vec[234]|mat[234](?:x[234])?|sampler\w+)"
_DECLARATION_RE = compiled(
    rf"^[ \t]*(?:(?:const|uniform|highp|mediump|lowp)\s+)*{_GLSL_TYPE}\s+[A-Za-z_]\w*\s*[(=;\[,]"
    r"|^[ \t]*struct\s+[A-Za-z_]\w*\s*(?:\{|$)"
    r"|^[ \t]*#[ \t]*(?:define|version|ifdef|ifndef)\b",
    re.M,
)
_FENCE_RE = compiled(r"^[ \t]*(?:```|~~~)", re.M)  # Markdown code fences: never in GLSL
_CODE_END = (";", "{", "}", ")", ",", "(")


def name_says_shader(path: str | os.PathLike) -> bool | None:
    """True: the name makes a file a shader file (.glsl, .frag, a Shadertoy tab name); None: its
    text decides (`looks_like_shader`: a `.txt` or extension-less file); False: it is not one
    (another extension, a hidden file, a README or licence by its name)."""
    name = path_name(path)
    suffix = path_suffix(name).lower()
    if name.startswith(".") or suffix not in SHADER_EXTENSIONS:
        return False
    if suffix in (".glsl", ".frag") or tab_name(name) is not None:
        return True
    stem = path_stem(name).lower().replace("-", "_").split("_")[0]
    return False if stem in _NOT_SHADER_STEMS else None


def looks_like_shader(text: str) -> bool:
    """Whether a text is shader code: a `mainImage` or a GLSL declaration outside comments, no
    Markdown fence, and no more lines of prose than lines of code."""
    if "\0" in text or _FENCE_RE.search(text):
        return False
    code = _COMMENT_RE.sub(" ", text)
    if not (_MAIN_IMAGE_RE.search(code) or _DECLARATION_RE.search(code)):
        return False
    code_lines = prose_lines = 0
    for line in code.splitlines():
        line = line.strip()
        if not line:
            continue
        if line.endswith(_CODE_END) or line.startswith("#") or _DECLARATION_RE.match(line):
            code_lines += 1
        elif len(line.split()) >= 3:
            prose_lines += 1
    return code_lines >= prose_lines


def sniff_shader_file(path: str | os.PathLike) -> bool:
    """`looks_like_shader` of a file's first SNIFF_BYTES bytes. A file that cannot be read is
    taken as a shader: reading it then reports why (a file that may be a shader is never skipped
    in silence)."""
    try:
        fd = os.open(str(path), os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
        with os.fdopen(fd, "rb") as f:
            if not stat.S_ISREG(os.fstat(f.fileno()).st_mode):
                return True
            data = f.read(SNIFF_BYTES)
    except OSError:
        return True
    return looks_like_shader(data.decode("utf-8", "replace"))


def _is_shader_file(p: str) -> bool:
    """A regular file that is a shader file by its name or, when the name leaves it open, by its
    text."""
    if not os.path.isfile(p):
        return False
    by_name = name_says_shader(p)
    return by_name if by_name is not None else sniff_shader_file(p)


def load_shader(path: str | os.PathLike) -> Shader:
    """A file (one tab; a sibling Common tab is picked up for an Image tab) or a folder of tabs."""
    p = posix_path(path)
    spath = str(path)
    check_path(spath)
    if path_suffix(p).lower() == ".json" and os.path.isfile(
        p
    ):  # Shadertoy's export of a whole shader
        from pathlib import Path

        return load_shadertoy_json(Path(p))
    shader = Shader(root=spath)
    if os.path.isdir(p):
        files = [f for f in folder_entries(p) if _is_tab_file(f)]
        if not files:
            raise InputError(
                f"{spath}: error: the folder holds no Shadertoy tab files (Image.glsl, "
                "Common.glsl, ...)"
            )
        for f in files:
            src = read_source(f)
            if src.tab in shader.tabs:
                raise InputError(
                    f"{f}: error: a second file for the {src.tab} tab (first: "
                    f"{shader.tabs[src.tab].path})"
                )
            shader.tabs[src.tab] = src
        return shader
    parent = _parent(p)
    siblings = folder_entries(parent) if os.path.exists(parent) else []
    return _file_shader(p, spath, _commons(siblings))


def _file_shader(p: str, root: str, siblings: list[str]) -> Shader:
    """One tab file as a shader, with the Common tab among its folder's `siblings` (Shadertoy
    prepends it to every pass)."""
    shader = Shader(root=root)
    src = read_source(p, "Common" if _named_common(p) else None)
    shader.tabs[src.tab] = src
    if src.tab not in ("Common", "GLSL"):
        common = common_sibling(p, siblings)
        if common is not None and os.path.isfile(common):
            shader.tabs["Common"] = read_source(common, "Common")
    return shader


def _commons(entries: list[str]) -> list[str]:
    """The entries of a folder named as a Common tab (`Common.txt`, `Lab06Common.txt`)."""
    return [f for f in entries if tab_name(f) == "Common" or _named_common(f)]


def _stem(path: str | os.PathLike) -> str:
    """A file's name without its shader extension."""
    stem = path_name(path)
    for ext in SHADER_EXTENSIONS[:-1]:
        if stem.lower().endswith(ext):
            return stem[: -len(ext)]
    return stem


def _bracket(m: re.Match) -> str:
    """A bracketed part of a name: kept when it names a tab, dropped as a description."""
    return m.group(1) if _TAB_WORD_ONLY.fullmatch(m.group(1).strip()) else ""


def _key(stem: str) -> str:
    """A name as tab names are compared: no separators or case, nor what students add to a
    tab's name: a description in brackets (`Buffer A (Cube Map).txt`) or the word "tab"
    (`Common Tab.txt`, `midterm_image_tab.txt`); a tab named in brackets after the project's
    name is kept (`GPR-200 Midterm (Common).txt`)."""
    stem = _TAB_WORD.sub("", _BRACKETS.sub(_bracket, stem))
    return _SEPARATORS.sub("", stem).lower()


def _name_key(path: str | os.PathLike) -> str:
    """A file's name as tab names are compared (`_key`), without its extension."""
    return _key(_stem(path))


def _named_common(path: str) -> bool:
    """A file named as a Common tab with a project's name before or after the word
    (`Lab06Common.txt`, `lab 6 common.txt`, `common_lab6_name.txt`)."""
    return _common_project(path) is not None and name_says_shader(path) is not False


def _common_project(path: str) -> str | None:
    """The project a Common tab file is named for: the rest of its name, marked by the side the
    word Common is on (`Lab06Common` -> "<lab06", `common_lab6_x` -> ">lab6x"); None for a
    name that is not such a Common."""
    key = _name_key(path)
    if key.endswith("common") and key != "common":
        return "<" + key[: -len("common")]
    stem = _stem(path)
    first = _COMMON_FIRST.match(stem)
    return ">" + _key(stem[first.end() :]) if first else None


# the pass a prefixed tab file names after its prefix (`Lab06Image`, `midTermBufA`)
_PASS_SUFFIX = compiled(rf"{_PASS_WORD}$")


def common_sibling(path: str, siblings: list[str]) -> str | None:
    """Which of a pass file's siblings is its Common tab: a file named `Common`, else the one
    named for the pass file's project, the rest of its name (`Lab06Common.txt` beside
    `Lab06Image.txt` or `Lab06.txt`, `midTermCommon.txt` beside `midTermBufA.txt`,
    `common_lab6_x.txt` beside `bufferB_lab6_x.txt`); None when there is none, or several."""
    stem = _stem(path)
    projects = {"<" + _PASS_SUFFIX.sub("", _key(stem))}
    first = _PASS_FIRST.match(stem)
    if first:
        projects.add(">" + _key(stem[first.end() :]))
    prefixed = []
    for f in siblings:
        if f == path:
            continue
        if tab_name(f) == "Common" and name_says_shader(f) is True:
            return f
        if _named_common(f) and _common_project(f) in projects:
            prefixed.append(f)
    return prefixed[0] if len(prefixed) == 1 else None


def find_shaders(paths: list[str]) -> list[Shader]:
    """Expand command-line paths. A file is one shader; a folder holding tab files (Image.glsl,
    Common.glsl, ...) is one shader; any other folder is walked: each of its sub-folders with
    tab files is a shader, and each loose shader file (.glsl, .frag, or a .txt or extension-less
    file whose text is GLSL: `looks_like_shader`) is a shader of its own. A symbolic
    link to a folder is followed only when the walk has not been in that real folder yet, so links
    back to the folder itself or above it (or many links to one folder) cost one visit."""
    out: list[Shader] = []
    for path in paths:
        p = posix_path(path)
        if os.path.isdir(p) and not any(_is_tab_file(f) for f in folder_entries(p)):
            found = _walk(p, {os.path.realpath(p)})
            if not found:
                raise InputError(f"{path}: error: no shader files found")
            out.extend(found)
        else:
            out.append(load_shader(p))
    return out


def _parent(p: str) -> str:
    """`str(PurePosixPath(p).parent)` of a path spelt as `posix_path` spells it."""
    i = p.rfind("/")
    if i < 0:
        return "."
    return p[:i] if p[:i].strip("/") else p[: i + 1]  # the root `/` (or `//`) keeps its slashes


def _walk(folder: str, visited: set[str]) -> list[Shader]:
    """The shaders under `folder`; `visited` holds the real folders this walk has entered (a
    real sub-folder is always entered, a symbolic link only to a real folder not in it)."""
    found: list[Shader] = []
    entries = folder_entries(folder)
    commons = _commons(entries)  # (once a folder: each loose file looks for its Common here)
    for f in entries:
        name = path_name(f)
        if name.startswith(".") or name == "__pycache__":
            continue
        if os.path.isdir(f):
            real = os.path.realpath(f)
            if os.path.islink(f) and real in visited:
                continue
            visited.add(real)
            if any(_is_tab_file(g) for g in folder_entries(f)):
                found.append(load_shader(f))
            else:
                found.extend(_walk(f, visited))
        elif _is_shader_file(f):
            found.append(_file_shader(f, f, commons))
    return found


# Shadertoy's export: pass types and input kinds (ctype) -> glslcheck's tabs and binding kinds.
_ST_TABS = {"image": "Image", "common": "Common", "sound": "Sound", "cubemap": "Cube A"}
_ST_INPUTS = {"texture": "texture", "buffer": "buffer", "cubemap": "cubemap"}


def read_json(path: str | os.PathLike) -> object:
    """The JSON value in the file at `path` (channels.json, a Shadertoy export); InputError (exit 2)
    naming the file when it cannot be read, is not JSON, or nests deeper than the parser
    recurses."""
    import json

    spath = str(path)
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except (OSError, UnicodeDecodeError) as e:
        raise InputError(f"{spath}: error: cannot read the file ({e})") from None
    try:
        return json.loads(text)
    except json.JSONDecodeError as e:
        raise InputError(f"{spath}:{e.lineno}:{e.colno}: error: not valid JSON: {e.msg}") from None
    except RecursionError:
        raise InputError(
            f"{spath}: error: too deeply nested JSON (arrays or objects inside each other "
            "deeper than the JSON reader goes)"
        ) from None


def json_kind(value) -> str:
    """What a JSON value is, as a message names it: `an object`, `a list`, `a string`, ..."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if value is None:
        return "null"
    kinds: dict[type, str] = {dict: "an object", list: "a list", str: "a string"}
    return kinds.get(type(value), "a number")


def load_shadertoy_json(path) -> Shader:
    """A shader from Shadertoy's JSON export (`{"Shader": {"renderpass": [...]}}`, or a list of
    such shaders holding one): each pass's `code` becomes its tab (diagnostics name
    `<file> [<tab>]`), each input a Binding: a `/media/...` path is the file of the same name in
    the `media/` folder beside the JSON, a buffer input the Buffer tab whose output id it names.
    InputError (exit 2) naming the file and the JSON field path (or the pass and channel) for
    anything else, a field of the wrong type included."""
    from pathlib import Path

    spath = str(path)
    data = read_json(path)

    def fail(where: str, message: str) -> NoReturn:
        raise InputError(f"{spath}: error: {where}: {message}")

    def typed(value: Any, types: tuple[type, ...], where: str, expected: str) -> Any:
        """`value` when it is one of `types` (null counting as absent: None); else the error."""
        if value is None or (isinstance(value, types) and not isinstance(value, bool)):
            return value
        fail(where, f"must be {expected}, not {json_kind(value)}")

    base = ""
    if isinstance(data, list) and len(data) == 1:
        data, base = data[0], "[0]"
    if isinstance(data, dict) and "Shader" in data:
        data, base = data["Shader"], f"{base}.Shader".lstrip(".")
    passes = data.get("renderpass") if isinstance(data, dict) else None
    if not isinstance(passes, list):
        fail("the top level", 'not a Shadertoy export: expected {"Shader": {"renderpass": [...]}}')
    base = f"{base}.renderpass".lstrip(".")
    channels: list[Binding] = []
    shader = Shader(root=spath, channels=channels)
    outputs: dict[str, str] = {}  # output id -> Buffer tab
    buffers = iter(BUFFER_TABS)
    placed: list[tuple[str, str, list]] = []  # each pass's tab, field path and inputs
    for i, rp in enumerate(passes):
        at = f"{base}[{i}]"
        if not isinstance(rp, dict):
            fail(at, f'must be an object with a "code" string, not {json_kind(rp)}')
        if rp.get("code") is None:
            fail(at, 'needs a "code" string')
        code = typed(rp["code"], (str,), f"{at}.code", "a string")
        kind = typed(rp.get("type"), (str,), f"{at}.type", "a string") or "image"
        name = typed(rp.get("name"), (str,), f"{at}.name", "a string") or ""
        tab = _ST_TABS.get(kind)
        if kind == "buffer":  # named "Buffer A" or, in older exports, "Buf A"
            m = re.fullmatch(r"Buf(?:fer)? ?([A-D])", name.strip())
            name = f"Buffer {m.group(1)}" if m else ""
            tab = name if name in BUFFER_TABS and name not in shader.tabs else next(buffers, None)
        if tab is None or tab in shader.tabs:
            fail(
                f"{at} ({rp.get('name') or kind})",
                f"a pass of type {kind!r} glslcheck cannot place",
            )
        src = Source(f"{spath} [{tab}]", code.replace("\r\n", "\n"), tab)
        register_source(src.path, src.text)
        shader.tabs[tab] = src
        for j, out in enumerate(typed(rp.get("outputs"), (list,), f"{at}.outputs", "a list") or ()):
            typed(out, (dict,), f"{at}.outputs[{j}]", "an object")
            if out and "id" in out:
                outputs[str(out["id"])] = tab
        placed.append((tab, at, typed(rp.get("inputs"), (list,), f"{at}.inputs", "a list") or []))
    for tab, at, inputs in placed:
        for j, inp in enumerate(inputs):
            where = f"{at}.inputs[{j}]"
            typed(inp, (dict,), where, "an object")
            channels.append(
                _export_binding(
                    shader, tab, inp or {}, outputs, Path(path).parent, fail, typed, where
                )
            )
    return shader


def _export_binding(
    shader: Shader,
    tab: str,
    inp: dict,
    outputs: dict[str, str],
    folder: Path,
    fail: Callable[[str, str], NoReturn],
    typed: Callable[[Any, tuple[type, ...], str, str], Any],
    at: str,
) -> Binding:
    import json
    from pathlib import Path

    from .bindings import FILTERS, KIND_DEFAULTS, WRAPS, Binding

    channel = inp.get("channel")
    if type(channel) is not int or channel not in (0, 1, 2, 3):
        fail(
            f"{at}.channel (the {tab} pass)",
            f"an input without a channel 0-3: {json.dumps(inp, default=str)[:80]}",
        )
    where = f"the {tab} pass, iChannel{channel}"
    ctype = typed(inp.get("ctype", inp.get("type")), (str,), f"{at}.ctype", "a string")
    kind = _ST_INPUTS.get(ctype)
    if kind is None:
        fail(where, f"{ctype} inputs are not supported yet")
    sampler = typed(inp.get("sampler"), (dict,), f"{at}.sampler", "an object") or {}
    filt, wrap, vflip = KIND_DEFAULTS[kind]
    filt = sampler.get("filter", filt)
    wrap = sampler.get("wrap", wrap)
    vflip = str(sampler.get("vflip", vflip)).lower() == "true"
    if filt not in FILTERS or wrap not in WRAPS:
        fail(
            where,
            f"filter {filt!r} / wrap {wrap!r} (expected {', '.join(FILTERS)} / {', '.join(WRAPS)})",
        )
    src = inp.get("src", inp.get("filepath"))
    src = typed(src, (str,), f"{at}.{'src' if 'src' in inp else 'filepath'}", "a string") or ""
    if kind == "buffer":
        buffer = outputs.get(str(inp.get("id")))
        m = re.search(r"buffer0([0-3])", src)
        if buffer is None and m is not None:
            buffer = BUFFER_TABS[int(m.group(1))]
        if buffer is None or buffer not in shader.tabs:
            fail(
                where, f"the buffer it reads ({src or inp.get('id')}) is not a pass of this export"
            )
        # vflip is Shadertoy's UNPACK_FLIP_Y at an image's upload: it never applies to a buffer
        return Binding(tab, channel, buffer, None, filt, wrap, False)
    if not src:
        fail(f"{at}.src ({where})", f'an input of type {ctype} needs a "src" path (/media/...)')
    if kind == "cubemap":
        if "previz" in src:  # Shadertoy's name for the Cube A pass's output
            fail(where, "the Cube A pass's cube map is not supported yet (a media cube map is)")
        wrap = "clamp"  # WebGL 2 filters cube maps seamlessly: Shadertoy's wrap does not apply
    local = f"media/{Path(src).name}"
    if not (folder / local).is_file():
        fail(
            where,
            f"no such file {str(folder / local)!r} (Shadertoy's {src}: download it into the media/ "
            "folder beside the JSON)",
        )
    if kind == "cubemap":  # its other faces: name_1.png .. name_5.png beside it
        stem, suffix = local[: len(local) - len(Path(local).suffix)], Path(local).suffix
        for k in range(1, 6):
            if not (folder / f"{stem}_{k}{suffix}").is_file():
                fail(
                    where,
                    f"no such file {str(folder / f'{stem}_{k}{suffix}')!r} (face {k} of "
                    f"Shadertoy's cube map {src}: download all six into the media/ folder)",
                )
    return Binding(tab, channel, None, local, filt, wrap, vflip, kind == "cubemap")
