"""The editor's URL (/editor/IHn?params=..&edge=..): one query syntax for the editor and the
JSON API. ``editor_query`` formats an isohedral spec; the API's parser (``query_options`` +
``normalise_options`` + ``configure``) reads it back into the same tiling."""

from __future__ import annotations

import html
import json
import re
from urllib.parse import parse_qsl, urlsplit

import numpy as np
import pytest

from tilekit.edgeshapes import EdgeShape
from tilekit.errors import ParameterError, ParseError
from tilekit.plugins.isohedral.engine import IsohedralTiling, unmarked_from_spec
from tilekit.plugins.isohedral.spec import editor_path, editor_query
from tilekit.web.service import normalise_options, query_options

#: Shaped, non-default tilings: J edges (IH16, IH41), S and J (IH21), U and S (IH13), a
#: smooth (Bézier) U shape and a colouring (IH12), parameters with 17 significant digits.
SPECS = [
    {"ih": 16, "params": [0.25], "edges": {"b": "0,0:0.3,0.2:0.7,-0.1:1,0"}},
    {"ih": 21, "params": [0.11, 0.6600000000000001],
     "edges": {"a": "0,0:0.3,0.15:0.6,0.1:1,0", "b": "0,0:0.5,0.1:1,0", "d": "0,0:0.4,-0.08:1,0"}},
    {"ih": 41, "params": [0.23076923076923078, 0.52], "edges": {"a": "0,0:0.5,0.12:1,0", "b": "0,0:0.3,-0.1:1,0"}},
    {"ih": 13, "params": [0.127, 0.28, 0.55], "edges": {"a": "0,0:0.4,0.05:1,0", "c": "0,0:0.5,0.06:1,0"}},
    {"ih": 12, "params": [0.13, 0.23], "edges": {"a": "bezier:0,0:0.3,0.2:0.7,0.2:1,0"},
     "colouring": "(1 2)(2 1)(2 1)"},
]


def api_parse(ih: int, query: str) -> dict:
    """The API's parse of a query string: the pairs, query_options, normalise_options and
    the tiling's configure (what Renderer.build does), as the tiling's spec."""
    options = normalise_options(query_options(parse_qsl(query, keep_blank_values=True)))
    return IsohedralTiling(ih).configure(**options).spec()


def page_info(text: str) -> dict:
    return json.loads(html.unescape(re.search(r'data-info="([^"]*)"', text).group(1)))


def test_specs_are_valid_and_not_defaults():
    for spec in SPECS:
        tiling = unmarked_from_spec(spec)
        assert tiling.spec() != IsohedralTiling(spec["ih"]).spec()
        kinds = {tiling.symbol.label_kind(label) for label in tiling.edge_shapes}
        assert kinds, spec
    assert {k for s in SPECS for k in unmarked_from_spec(s).template.symbol.edge_kinds()} >= {"J", "U", "S"}


@pytest.mark.parametrize("spec", SPECS, ids=lambda s: f"IH{s['ih']}")
def test_spec_to_query_to_the_apis_parse_is_the_same_tiling(spec, client):
    expected = unmarked_from_spec(spec).spec()
    query = editor_query(spec)
    assert api_parse(spec["ih"], query) == expected
    # the same through the HTTP API and the editor page (the parser behind both)
    got = client.get(f"/api/tiling/IH{spec['ih']}/spec?{query}")
    assert got.status_code == 200, got.text
    assert got.json() == {"family": "isohedral", "name": f"IH{spec['ih']}", "spec": expected}
    page = client.get(editor_path(spec))
    assert page.status_code == 200
    info = page_info(page.text)
    assert info["spec"] == expected and info["params"] == expected["params"]
    assert {e["label"]: EdgeShape(np.array(e["points"]), e["smooth"]).to_text() for e in info["edges"]
            if e["label"] in expected["edges"]} == expected["edges"]
    assert 'data-notice' not in page.text and '<p class="error" id="error" role="alert"></p>' in page.text


def test_the_query_form():
    spec = SPECS[4]
    assert editor_path(spec) == ("/editor/IH12?params=0.13,0.23&edge=a=bezier:0,0:0.3,0.2:0.7,0.2:1,0"
                                 "&colouring=(1%202)(2%201)(2%201)")
    assert editor_query({"ih": 16, "params": [0.1 + 0.2]}) == "params=0.30000000000000004"
    assert editor_path({"ih": 84}) == "/editor/IH84"  # no parameters, straight edges
    assert editor_query({"ih": 16, "edges": {"b": "0.2,0.1 "}}) == "edge=b=0.2,0.1"
    with pytest.raises(ParameterError, match="IH19 is a marked type"):
        editor_path({"ih": 19})
    with pytest.raises(ParseError, match="'ih' is missing"):
        editor_query({"params": [1]})
    with pytest.raises(ParseError, match="must be a finite number"):
        editor_query({"ih": 16, "params": [float("nan")]})


def test_partner_labels_parse_to_the_class_shape(client):
    # IH16's labels b and c are partners sharing one shape class (b); a shape given for c is
    # carried over to b by the engine, through the URL as through configure
    t = IsohedralTiling(16)
    assert t.symbol.adjacent_map()["c"][0] == "b"
    query = "params=0.25&edge=c=0,0:0.3,0.2:1,0"
    expected = t.configure(params=[0.25], edges=["c=0,0:0.3,0.2:1,0"]).spec()
    assert list(expected["edges"]) == ["b"]
    assert api_parse(16, query) == expected
    assert page_info(client.get(f"/editor/IH16?{query}").text)["spec"] == expected


def test_an_escherize_results_editor_path_reopens_its_tiling(client):
    pytest.importorskip("scipy")
    from tilekit.plugins.isohedral import escher

    goal = np.asarray(unmarked_from_spec(SPECS[1]).prototile.outline)
    results, failed = escher.escherize(goal, [21, 13], settings=escher.Settings(starts=1, samples=64))
    assert not failed and results[0].ih == 21 and results[0].distance < 1e-5
    for r in results:
        path = r.editor()
        assert path == editor_path(r.spec()) and path.startswith(f"/editor/IH{r.ih}?params=")
        assert r.to_json()["editor"] == path
        query = urlsplit(path).query
        assert api_parse(r.ih, query) == r.tiling().spec()
        info = page_info(client.get(path).text)
        assert info["spec"] == r.tiling().spec()
        assert info["params"] == r.params  # exact, not rounded


@pytest.mark.parametrize(
    ("query", "fragment"),
    [
        ("params=0.1,abc", "params 'abc' is not a number"),
        ("params=0.2", "IH21 takes 2 parameter(s)"),
        ("edge=z=0,0:0.5,0.1:1,0", "IH21 has no edge label 'z'"),
        ("edge=b", "is not 'LABEL=x,y:x,y:...'"),
        ("edge=b=0,0:0.5,3:1,0", "IH21: edge 2 (label 'b') and edge 4 (label 'd') cross"),  # the engine's
        ("zoom=2", "unknown render option(s) 'zoom'"),
    ],
)
def test_a_refused_url_shows_the_apis_line_over_the_defaults(client, query, fragment):
    api = client.get(f"/api/tiling/IH21/spec?{query}")
    assert api.status_code == 400
    line = api.json()["error"]
    assert fragment in line and "\n" not in line
    page = client.get(f"/editor/IH21?{query}")
    assert page.status_code == 200
    assert f'data-notice="{html.escape(line, quote=True)}"' in page.text
    assert f'<p class="error" id="error" role="alert">{html.escape(line, quote=True)}</p>' in page.text
    info = page_info(page.text)
    assert info["spec"] == IsohedralTiling(21).spec()
    assert all(e["points"] == [[0.0, 0.0], [1.0, 0.0]] for e in info["edges"])
