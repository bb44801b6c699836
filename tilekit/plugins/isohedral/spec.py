"""Any isohedral tiling, marked or not, from its catalogue spec ``{"ih": 16, ...}``; and the
web editor's URL of an unmarked one (:func:`editor_path`)."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any
from urllib.parse import quote

from tilekit.errors import ParameterError, ParseError
from tilekit.files import read_json
from tilekit.plugins.isohedral.engine import _spec_ih, unmarked_from_spec
from tilekit.plugins.isohedral.marked import marked_tiling
from tilekit.plugins.isohedral.split import number_text, parse_split, split_from_spec, split_text
from tilekit.plugins.isohedral.templates import get_template
from tilekit.schema import finite_number
from tilekit.tiling import PeriodicTiling

#: Characters left unescaped in a query value: the edge syntax's ``LABEL=x,y:x,y``, a
#: colouring's parentheses and a split's ``S,T;PATH`` stay readable (RFC 3986 allows them in a
#: query; Starlette splits a query on ``&`` only).
_QUERY_SAFE = ",:=();"


def tiling_from_spec(spec: Mapping[str, Any]) -> PeriodicTiling:
    """Rebuild an isohedral tiling from ``{"ih": 16, "params": [...], "edges": {...}}``; with a
    ``"split"`` table, the dihedral tiling of that tile split in two (:mod:`.split`)."""
    t = get_template(_spec_ih(spec))
    if t.marked:
        return marked_tiling(t.ih)
    base = unmarked_from_spec(spec)
    if spec.get("split") is not None:
        return split_from_spec(spec, base)
    return base


def _number(value: Any) -> str:
    """The shortest text that float() reads back as exactly ``value`` (:func:`.split.number_text`)."""
    return number_text(finite_number(value, "isohedral spec parameter"))


def editor_query(spec: Mapping[str, Any]) -> str:
    """The query string of an isohedral spec in the syntax of the JSON API and the editor.

    ``params=v0,v1,...`` (exact: each number's shortest round-trip text), one ``edge=LABEL=TEXT``
    per edge shape (the spec's own ``EdgeShape`` text), ``colouring=`` when the spec has one,
    ``set=split=S,T;PATH`` when it has a split (:func:`~.split.split_text`):
    what ``/api/render/IHn``, ``/api/tiling/IHn/spec`` and ``/editor/IHn`` read back through
    :func:`tilekit.web.service.query_options` and ``normalise_options`` into the same tiling
    (tests/web/test_editor_url.py checks spec -> query -> the API's parse -> the same spec).
    """
    if not isinstance(spec, Mapping):
        raise ParseError(f"an isohedral spec is a JSON object like {{'ih': 16}}, not {spec!r}")
    _spec_ih(spec)
    items: list[tuple[str, str]] = []
    params = spec.get("params") or []
    if not isinstance(params, list | tuple):
        raise ParseError(f"isohedral spec params {params!r} are not a list of numbers")
    if params:
        items.append(("params", ",".join(_number(p) for p in params)))
    edges = spec.get("edges") or {}
    if not isinstance(edges, Mapping):
        raise ParseError(f"isohedral spec edges {edges!r} are not an object of LABEL: 'x,y:x,y:...'")
    for label, text in edges.items():
        if not isinstance(label, str) or not isinstance(text, str):
            raise ParseError(f"isohedral spec edge {label!r}: {text!r} is not LABEL: 'x,y:x,y:...'")
        items.append(("edge", f"{label}={text.strip()}"))
    if spec.get("colouring"):
        items.append(("colouring", str(spec["colouring"])))
    if spec.get("split") is not None:
        split = parse_split(spec["split"])
        if split is None or not isinstance(split.get("ends"), list | tuple) or len(split["ends"]) != 2:
            raise ParseError(f"isohedral spec split {spec['split']!r} is not {{'ends': [s, t], 'path': 'x,y:...'}}")
        items.append(("set", "split=" + split_text(split)))
    return "&".join(f"{k}={quote(v, safe=_QUERY_SAFE)}" for k, v in items)


def editor_path(spec: Mapping[str, Any]) -> str:
    """``/editor/IHn?params=...&edge=...``: the web editor (``tilekit serve``) opened on the
    tiling of an unmarked type's spec (:func:`editor_query`)."""
    t = get_template(_spec_ih(spec))
    if t.marked:
        raise ParameterError(f"{t.name} is a marked type; the editor takes the 81 unmarked types")
    query = editor_query(spec)
    return f"/editor/{t.name}" + (f"?{query}" if query else "")


def tiling_from_file(path: str) -> PeriodicTiling:
    """A tiling from a spec file: ``{"family": "isohedral", "spec": {...}}`` (the web editor's
    export and escherize's output) or a bare spec ``{"ih": 16, ...}``."""
    name = Path(path).name
    data = read_json(path, "isohedral spec file")
    if isinstance(data, dict) and "spec" in data:
        if data.get("family", "isohedral") != "isohedral":
            raise ParseError(f"{name}: a {data.get('family')!r} spec, not an isohedral one")
        data = data["spec"]
    if not isinstance(data, dict):
        raise ParseError(f'{name}: an isohedral spec is a JSON object like {{"ih": 16, "params": [0.3]}}')
    return tiling_from_spec(data)
