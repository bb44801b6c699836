"""tilekit.schema: the declarative checker behind the project's TOML/JSON formats."""

from __future__ import annotations

import pytest

from tilekit.errors import ParseError
from tilekit.schema import Field, check

POINT = Field("list", items=Field("number"), length=(2, 2))
ENTRY = Field("table", fields={
    "name": Field("str", default="t"),
    "kind": Field("str", default="exact", choices=("exact", "indented")),
    "count": Field("int", range=(1, 10)),
    "outline": Field("list", required=True, items=POINT, length=(3, None), missing="[[tile]] #{n} needs an 'outline'"),
})
FILE = Field("table", fields={"tile": Field("list", required=True, items=ENTRY, length=(1, None))})

SQUARE = [[0, 0], [1, 0], [1, 1], [0, 1]]


def test_defaults_are_filled_and_the_input_is_left_alone() -> None:
    data = {"tile": [{"outline": SQUARE}]}
    out = check(FILE, data, "f.toml")
    assert out["tile"][0]["name"] == "t" and out["tile"][0]["kind"] == "exact"
    assert "name" not in data["tile"][0]  # a new dict, not the caller's


@pytest.mark.parametrize(
    "entry, message",
    [
        ({}, "f.toml: [[tile]] #1 needs an 'outline'"),
        ({"outline": SQUARE[:2]}, "f.toml: tile[1].outline must be a list of at least 3 items"),
        ({"outline": [[0, 0], [1, "x"], [0, 1]]}, "f.toml: tile[1].outline[2][2] must be a number, got 'x'"),
        ({"outline": [[0, 0], [1, True], [0, 1]]}, "f.toml: tile[1].outline[2][2] must be a number, got True"),
        ({"outline": SQUARE, "kind": "loose"}, "f.toml: tile[1].kind 'loose' is not one of exact, indented"),
        ({"outline": SQUARE, "count": 11}, "f.toml: tile[1].count 11 is outside 1..10"),
        ({"outline": SQUARE, "count": 2.5}, "f.toml: tile[1].count must be an integer, got 2.5"),
    ],
)
def test_one_line_errors_name_the_file_and_the_field(entry: dict, message: str) -> None:
    with pytest.raises(ParseError) as err:
        check(FILE, {"tile": [entry]}, "f.toml")
    assert str(err.value).startswith(message) and "\n" not in str(err.value)


def test_top_level_and_missing_tables() -> None:
    with pytest.raises(ParseError, match=r"^f.toml: top level must be a table, got \[1\]"):
        check(FILE, [1], "f.toml")
    with pytest.raises(ParseError, match=r"^f.toml: tile is missing"):
        check(FILE, {}, "f.toml")


def test_unknown_kind_is_a_schema_bug() -> None:
    with pytest.raises(ValueError, match="schema kind"):
        Field("float")
