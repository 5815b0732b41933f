"""The class of submissions the grade tests read (tests/grade/lab_class.py)."""

from lab_class import lab_class  # noqa: F401 - a fixture, found by its name
