"""Lint configuration: finding it, reading it, checking it, and merging command-line overrides.

For each linted file the nearest configuration applies, searched upward from the file's folder
(then from the current directory when nothing is found there):

* `glslcheck.toml`, whose top-level keys are the settings, or
* `pyproject.toml` with a `[tool.glslcheck]` table (a `pyproject.toml` without one is skipped).

When one folder holds both, `glslcheck.toml` wins. Settings:

    select        = ["rule-name", ...]   only these rules (default: every rule)
    ignore        = ["rule-name", ...]   never these rules
    comment-span  = 5                    statements a comment covers (missing-comment)
    tab-patterns  = ["lab4/*.txt", ...]  extra file-name globs taken as shader files by hooks
                                         and by `glslcheck lint --skip-non-shaders`

Command-line `--select` / `--ignore` replace the file's values. Any mistake (bad TOML, an unknown
key or rule name, a wrong type) raises `InputError` naming the configuration file (exit 2).
"""

from __future__ import annotations

import os

from ..base.diagnostics import InputError
from ..base.records import field, record, replace

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Mapping
    from typing import Any

DEFAULT_COMMENT_SPAN = 5
# key -> (python type of the value, description used in error messages)
COMMAND_LINE = "glslcheck lint"  # the `where` of command-line settings in messages
KEYS: dict[str, tuple[type, str]] = {
    "select": (list, "a list of rule names"),
    "ignore": (list, "a list of rule names"),
    "comment-span": (int, "a positive integer"),
    "tab-patterns": (list, "a list of file-name glob patterns"),
}


@record(frozen=True)
class LintConfig:
    """The settings in force for one file; `path` is the file they came from (None: defaults)."""

    select: frozenset[str] | None = None  # None: every rule
    ignore: frozenset[str] = frozenset()
    comment_span: int = DEFAULT_COMMENT_SPAN
    tab_patterns: tuple[str, ...] = ()
    path: str | None = None

    def enabled(self, rule: str) -> bool:
        return (self.select is None or rule in self.select) and rule not in self.ignore


@record
class ConfigFinder:
    """Finds and caches the configuration of each folder; `overrides` (settings keys) win."""

    overrides: Mapping[str, Any] = field(default_factory=dict)
    known_rules: frozenset[str] = frozenset()
    _by_dir: dict[str, LintConfig | None] = field(default_factory=dict)  # None: none up from there
    _cwd_config: LintConfig | None = None

    def for_file(self, path: str | os.PathLike) -> LintConfig:
        folder = os.path.dirname(os.path.realpath(path))  # `Path(path).resolve().parent`
        found = self._search(folder)
        if found is None:
            if self._cwd_config is None:
                self._cwd_config = self._search(os.path.realpath(os.getcwd())) or LintConfig()
            found = self._cwd_config
        return apply_overrides(found, self.overrides, self.known_rules, COMMAND_LINE)

    def _search(self, folder: str) -> LintConfig | None:
        visited: list[str] = []
        result: LintConfig | None = None
        for d in _up_from(folder):
            if d in self._by_dir:
                result = self._by_dir[d]
                break
            visited.append(d)
            result = load_config_in(d, self.known_rules)
            if result is not None:
                break
        # Each folder visited has the answer found above it, also "none" (then the next file of
        # a folder without configuration does not read every parent's pyproject.toml again).
        for d in visited:
            self._by_dir[d] = result
        return result


def _up_from(folder: str) -> list[str]:
    """A resolved folder and the folders above it, up to the root (`(folder, *folder.parents)`
    of a `Path`: glslcheck's lint path does not import pathlib, for its start-up time)."""
    found = [folder]
    while True:
        up = os.path.dirname(folder)
        if up == folder:
            return found
        found.append(up)
        folder = up


def load_config_in(folder: str, known_rules: frozenset[str]) -> LintConfig | None:
    """The configuration a folder itself holds, or None."""
    own = os.path.join(folder, "glslcheck.toml")
    if os.path.isfile(own):
        return parse_config(_read_toml(own), own, own, known_rules)
    py = os.path.join(folder, "pyproject.toml")
    if os.path.isfile(py):
        data = _read_toml(py)
        table = (
            data.get("tool", {}).get("glslcheck") if isinstance(data.get("tool"), dict) else None
        )
        if table is not None:
            if not isinstance(table, dict):
                raise InputError(f"{py}: error: [tool.glslcheck] must be a table")
            return parse_config(table, str(py), f"{py} [tool.glslcheck]", known_rules)
    return None


def _read_toml(path: str) -> dict[str, Any]:
    import tomllib  # only where a folder has a configuration file: not on every start-up

    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except tomllib.TOMLDecodeError as e:
        raise InputError(f"{path}: error: not valid TOML: {e}") from None
    except OSError as e:
        raise InputError(
            f"{path}: error: cannot read the configuration ({e.strerror or e})"
        ) from None


def parse_config(
    table: Mapping[str, Any], path: str, where: str, known_rules: frozenset[str]
) -> LintConfig:
    """Check a settings table (keys as in the file at `path`) and build its LintConfig."""
    return apply_overrides(LintConfig(path=path), table, known_rules, where)


def apply_overrides(
    base: LintConfig, table: Mapping[str, Any], known_rules: frozenset[str], where: str
) -> LintConfig:
    """`base` with the settings in `table` replacing its own; InputError naming `where` on a
    mistake."""
    changes: dict[str, Any] = {}
    command_line = where == COMMAND_LINE
    for key, value in table.items():
        shown = f"--{key}" if command_line else f"`{key}`"
        if key not in KEYS:
            raise InputError(
                f"{where}: error: unknown setting `{key}`; the settings are {', '.join(KEYS)}"
            )
        if value is None:
            continue
        kind, what = KEYS[key]
        well_typed = isinstance(value, kind) and not isinstance(value, bool)
        if not well_typed:
            raise InputError(f"{where}: error: {shown} must be {what}, not {value!r}")
        if kind is list and not all(isinstance(v, str) for v in value):
            raise InputError(f"{where}: error: {shown} must be {what}, not {value!r}")
        if key in ("select", "ignore"):
            unknown = [v for v in value if v not in known_rules]
            if unknown and known_rules:
                raise InputError(
                    f"{where}: error: {shown} names unknown rule(s) {', '.join(unknown)}; "
                    "`glslcheck rule --all` lists the rules"
                )
            changes[key] = frozenset(value)
        elif key == "comment-span":
            if value < 1:
                raise InputError(f"{where}: error: {shown} must be {what}, not {value!r}")
            changes["comment_span"] = value
        elif key == "tab-patterns":
            changes["tab_patterns"] = tuple(value)
    return replace(base, **changes)
