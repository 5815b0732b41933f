"""glslcheck/base/config.py is the one home of the `GLSLCHECK_*` environment variables: every name
the source mentions is in its table, docs/configuration.md carries that table, each reader
refuses a bad value with an InputError naming its variable, and nothing else in glslcheck/ reads
one."""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest

import glslcheck
from glslcheck.base import config
from glslcheck.base.diagnostics import InputError

PACKAGE = Path(glslcheck.__file__).parent
ROOT = PACKAGE.parent
NAMES = {name for name, *_ in config.VARIABLES}


def _sources() -> dict[Path, str]:
    return {p: p.read_text(encoding="utf-8") for p in PACKAGE.rglob("*.py")}


def test_every_variable_in_the_source_is_in_the_table():
    used = {m for text in _sources().values() for m in re.findall(r"GLSLCHECK_[A-Z0-9_]+", text)}
    assert used, "the search found no variable"
    assert used <= NAMES, sorted(used - NAMES)


def test_only_config_reads_them():
    """Other modules call config's readers; writing a variable (for a child process, or the
    options the CLI hands on) is not reading it."""
    read = re.compile(r"environ(?:\.get\(|\[)\s*[\"']GLSLCHECK_|getenv\(\s*[\"']GLSLCHECK_")
    readers = [
        str(p.relative_to(ROOT))
        for p, text in _sources().items()
        if p.name != "config.py" and read.search(text)
    ]
    assert readers == []


def test_docs_have_the_table():
    assert config.table() in (ROOT / "docs" / "configuration.md").read_text(encoding="utf-8")


def test_table_rows_are_complete():
    for row in config.VARIABLES:
        assert len(row) == 5 and all(row), row
    for row in config.FOREIGN:
        assert len(row) == 3 and all(row) and not row[0].startswith("GLSLCHECK_"), row


READERS = {
    "GLSLCHECK_FRAME_SECONDS": (config.frame_seconds, "soon"),
    "GLSLCHECK_MEMORY_MB": (config.memory_mb, "-1"),
    "GLSLCHECK_PARALLEL": (config.parallel, "fibres"),
    "GLSLCHECK_JIT": (config.jit, "fast"),
    "GLSLCHECK_COMPILED_LANES": (config.compiled_lanes, "4"),
    "GLSLCHECK_TIERS": (config.tiers, "never"),
    "GLSLCHECK_WEBGL_TIMEOUT": (config.webgl_timeout, "inf"),
    "GLSLCHECK_CHROMIUM": (config.chromium, os.devnull),
    "GLSLCHECK_JOBS": (config.jobs, "0"),
}


def test_every_variable_has_a_reader():
    assert set(READERS) == NAMES


@pytest.mark.parametrize("name", sorted(READERS))
def test_reader_refuses_a_bad_value(monkeypatch, name):
    read, bad = READERS[name]
    monkeypatch.setenv(name, bad)
    with pytest.raises(InputError, match=f"^error: \\$?{name} must be "):
        read()


@pytest.mark.parametrize("name", sorted(READERS))
def test_reader_reads_at_call_time(monkeypatch, name):
    """Unset, each reader gives its default; the environment is read on every call."""
    read, bad = READERS[name]
    monkeypatch.delenv(name, raising=False)
    default = read()
    monkeypatch.setenv(name, bad)
    with pytest.raises(InputError):
        read()
    monkeypatch.delenv(name)
    assert read() == default


@pytest.mark.parametrize(
    "name,text,value",
    [
        ("GLSLCHECK_FRAME_SECONDS", " 2.5 ", 2.5),
        ("GLSLCHECK_FRAME_SECONDS", "", config.FRAME_SECONDS),
        ("GLSLCHECK_MEMORY_MB", "64", 64.0),
        ("GLSLCHECK_MEMORY_MB", "", None),
        ("GLSLCHECK_PARALLEL", "threads", "threads"),
        ("GLSLCHECK_JIT", "", "auto"),
        ("GLSLCHECK_COMPILED_LANES", "auto", None),
        ("GLSLCHECK_COMPILED_LANES", "16", 16),
        ("GLSLCHECK_WEBGL_TIMEOUT", "3", 3.0),
        ("GLSLCHECK_CHROMIUM", "", None),
        ("GLSLCHECK_JOBS", "auto", None),
        ("GLSLCHECK_JOBS", "1", 1),
        ("GLSLCHECK_JOBS", "8", 2),
    ],
)
def test_reader_accepts(monkeypatch, name, text, value):
    monkeypatch.setenv(name, text)
    assert READERS[name][0]() == value
