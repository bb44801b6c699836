"""Assertions the CLI tests share (tests/ is on sys.path through its conftest.py)."""

from __future__ import annotations


def assert_one_line_error(result, fragment: str = "") -> None:
    """A click result that failed the project's way: exit 2, one stderr line ``error: ...``
    containing ``fragment``, no traceback."""
    assert result.exit_code == 2, (result.exit_code, result.output)
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), result.stderr
    assert "Traceback" not in result.output
    assert fragment in lines[0], lines[0]
