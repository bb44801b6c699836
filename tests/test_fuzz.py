"""Fuzz tests for every parser and every CLI option type (issue 14, "no traceback, ever").

Each test feeds generated input to one parser and asserts that it either parses or raises a
``TilekitError`` (which the CLI prints as one line with exit 2) — never another exception,
never a NumPy warning. Structured inputs (TOML data files, tile-set JSON) are the shipped
files with random parts replaced by values of the wrong type or shape.

To fuzz a new parser, add it to ``TEXT_PARSERS`` (text in, anything out) or write a test in
the same shape. Examples are bounded so the whole file runs in well under a minute.
"""

from __future__ import annotations

import copy
import json
import tomllib
import warnings
from collections.abc import Callable
from typing import Any

import click
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tilekit.errors import TilekitError

FAST = settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.too_slow])
SLOW = settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def parses_or_tilekit_error(fn: Callable[..., Any], *args: Any) -> None:
    """``fn(*args)`` returns or raises TilekitError; any other exception or a warning fails,
    except a family's own documented warning (e.g. the multigrid's ``singular=perturb`` says
    that it moved singular offsets, as its spec asked)."""
    from tilekit.plugins.quasiperiodic.tiling import SingularWarning

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        warnings.simplefilter("ignore", SingularWarning)
        try:
            fn(*args)
        except TilekitError as exc:
            assert str(exc).strip(), "an error needs a message"


# --------------------------------------------------------------------------- text parsers


def _parsers() -> dict[str, tuple[Callable[[str], Any], str]]:
    from tilekit.catalogue import parse_filter
    from tilekit.colouring import Colouring
    from tilekit.edgeshapes import EdgeShape, parse_edge_option
    from tilekit.geometry import as_region
    from tilekit.incidence import IncidenceSymbol
    from tilekit.plugins.isohedral.templates import parse_ih_name, parse_zero_based_colouring
    from tilekit.plugins.substitution.expr import evaluate
    from tilekit.plugins.substitution.shapes import parse_edge_shape
    from tilekit.plugins.wang.cli import _fixed
    from tilekit.plugins.wang.tileset import parse_tileset
    from tilekit.regular.notation import VertexType, parse_sequence
    from tilekit.render import parse_palette
    from tilekit.text import parse_floats as _floats
    from tilekit.text import parse_region, parse_settings

    # (parser, the characters its inputs are drawn from, besides arbitrary text)
    return {
        "expr.evaluate": (evaluate, "0123456789.e+-*/() sqrtcosinphi"),
        "IncidenceSymbol.parse": (IncidenceSymbol.parse, "abc+-^{}[];$ "),
        "parse_sequence": (parse_sequence, "0123456789.^()[], ⁰¹²³⁴"),
        "VertexType.parse": (VertexType.parse, "3461.^2"),
        "Colouring.parse": (Colouring.parse, "0123 (),"),
        "parse_zero_based_colouring": (parse_zero_based_colouring, "0123 (),"),
        "parse_filter": (parse_filter, "abk_=!<>~-0123456789.e "),
        "parse_region": (parse_region, "0123456789.,-e inf"),
        "_floats(--param)": (lambda t: _floats(t, "--param", 1e6), "0123456789.,-e inf"),
        "parse_settings": (lambda t: parse_settings(t.split(";")), "ab=;, "),
        "parse_palette": (parse_palette, "#0af,redGX "),
        "as_region": (as_region, "0123456789.,-e"),
        "EdgeShape.parse": (EdgeShape.parse, "bezier:0123456789.,-e"),
        "parse_edge_option": (parse_edge_option, "ab=0123456789.,:-e"),
        "parse_edge_shape": (parse_edge_shape, "ab=0123456789.,:-e"),
        "parse_ih_name": (parse_ih_name, "IHih0123456789 "),
        "wang --fix": (lambda t: _fixed(tuple(t.split(";"))), "0123456789,=a;"),
        "parse_tileset": (parse_tileset, "abc012 :\n#tilesNESWnamecorner-"),
    }


PARSERS = _parsers()


@pytest.mark.parametrize("name", sorted(PARSERS))
def test_text_parser_never_crashes(name: str) -> None:
    fn, alphabet = PARSERS[name]

    @FAST
    @given(st.one_of(st.text(alphabet=alphabet, max_size=60), st.text(max_size=30)))
    def run(text: str) -> None:
        parses_or_tilekit_error(fn, text)

    run()


@pytest.mark.parametrize("name", ["expr.evaluate", "IncidenceSymbol.parse", "parse_sequence", "parse_filter",
                                  "parse_region", "parse_tileset", "Colouring.parse"])
@pytest.mark.parametrize("unit", ["1+", "-", "(", "9", "a+", "3.", "k=1", "a a a a\n"])
def test_long_inputs_are_bounded(name: str, unit: str) -> None:
    # expressions such as 1+1+...+1 or runs of '-', 5,000-edge symbols, 4,300+ digit numbers:
    # a one-line error (or a value) quickly, never RecursionError/MemoryError/ValueError
    import time

    fn = PARSERS[name][0]
    for n in (500, 5_000, 50_000):
        start = time.perf_counter()
        parses_or_tilekit_error(fn, unit * n)
        assert time.perf_counter() - start < 2.0, (name, unit, n)


def test_evaluator_cases_from_the_issue() -> None:
    # sqrt((-1)**0.5): a complex value inside sqrt is a ParseError, not a TypeError
    from tilekit.errors import ParseError
    from tilekit.plugins.substitution.expr import evaluate

    for text in ("sqrt((-1)**0.5)", "cos((-8)**(1/3))", "sin((-2)**0.5)", "+".join(["1"] * 2000), "-" * 3000 + "1",
                 "9**9**9", "1" * 5000):
        with pytest.raises(ParseError):
            evaluate(text)
    assert evaluate("+".join(["1"] * 30)) == 30.0
    assert evaluate("sqrt(5)/2 + phi**-1") == pytest.approx(5**0.5 / 2 + 0.6180339887)


# --------------------------------------------------------------------------- data files


WRONG = st.one_of(
    st.none(), st.booleans(), st.integers(-5, 5), st.integers(10**20, 10**30), st.floats(allow_nan=True),
    st.text(max_size=6), st.just("sqrt((-1)**0.5)"), st.just([]), st.just({}), st.lists(st.integers(-3, 9), max_size=4),
    st.just([[0, 0], [1, 0]]), st.just([[0, 0, 0]]), st.just({"tile": "nope"}), st.just([{"tile": 0}]),
)


def _slots(obj: Any, prefix: tuple = ()) -> list[tuple]:
    out = [prefix] if prefix else []
    if isinstance(obj, dict):
        for k, v in obj.items():
            out += _slots(v, prefix + (k,))
    elif isinstance(obj, list):
        for i, v in enumerate(obj[:3]):
            out += _slots(v, prefix + (i,))
    return out


def _mutated(base: dict, data: st.DataObject, values: st.SearchStrategy = None) -> dict:
    """``base`` with 1-3 parts replaced by ``values`` (default WRONG), or a key dropped."""
    values = WRONG if values is None else values
    doc = copy.deepcopy(base)
    slots = _slots(doc)
    for _ in range(data.draw(st.integers(1, 3))):
        path = data.draw(st.sampled_from(slots))
        parent = doc
        try:
            for k in path[:-1]:
                parent = parent[k]
            if isinstance(parent, dict) and data.draw(st.booleans()) and data.draw(st.booleans()):
                parent.pop(path[-1], None)
            else:
                parent[path[-1]] = data.draw(values)
        except (KeyError, IndexError, TypeError):
            pass
    return doc


def _system_files() -> list[tuple[str, dict]]:
    from tilekit.plugins.substitution import system_dir

    return [(p.name, tomllib.loads(p.read_text(encoding="utf-8"))) for p in sorted(system_dir().glob("*.toml"))]


SYSTEMS = _system_files()


@pytest.mark.parametrize("name", [n for n, _ in SYSTEMS])
def test_substitution_loader_never_crashes(name: str) -> None:
    # tilekit render --system FILE: any TOML data is a system or one ParseError naming the file
    from tilekit.plugins.substitution.system import load_data

    base = dict(SYSTEMS)[name]

    @SLOW
    @given(st.data())
    def run(data: st.DataObject) -> None:
        parses_or_tilekit_error(load_data, _mutated(base, data), name)

    run()


def test_hat_loader_never_crashes() -> None:
    from tilekit.plugins.substitution.hat import hat_data_path, hat_system_from_data

    base = tomllib.loads(hat_data_path().read_text(encoding="utf-8"))

    @SLOW
    @given(st.data())
    def run(data: st.DataObject) -> None:
        parses_or_tilekit_error(hat_system_from_data, _mutated(base, data), "hat.toml")

    run()


def test_keypoint_constants_not_a_table() -> None:
    # a keypoint system whose `constants` is not a table: ParseError naming file and table
    from tilekit.errors import ParseError
    from tilekit.plugins.substitution.system import load_data

    data = copy.deepcopy(dict(SYSTEMS)["spectre.toml"])
    data["constants"] = [1, 2]
    with pytest.raises(ParseError, match=r"spectre.toml: \[constants\] must be a table"):
        load_data(data, "spectre.toml")


def test_wang_json_never_crashes() -> None:
    from tilekit.plugins.wang import WangTiling
    from tilekit.plugins.wang.tileset import WangTileSet, get_tileset

    base = get_tileset("jeandel-rao").to_json()

    @FAST
    @given(st.data())
    def run(data: st.DataObject) -> None:
        doc = _mutated(base, data)
        parses_or_tilekit_error(WangTileSet.from_json, doc)
        parses_or_tilekit_error(WangTiling.from_spec, {"tileset": doc})

    run()


@pytest.mark.parametrize("suffix,reader", [(".toml", "system"), (".wang", "tileset"), (".toml", "texture")])
def test_files_of_any_bytes(tmp_path, suffix: str, reader: str) -> None:
    # non-UTF-8 .toml and .wang files are one ParseError, not UnicodeDecodeError
    from tilekit.plugins.substitution.system import load_system
    from tilekit.plugins.wang.render import load_texture
    from tilekit.plugins.wang.tileset import load_tileset

    fn = {"system": load_system, "tileset": load_tileset, "texture": load_texture}[reader]

    @SLOW
    @given(st.binary(max_size=80))
    def run(blob: bytes) -> None:
        path = tmp_path / f"fuzz{suffix}"
        path.write_bytes(blob)
        parses_or_tilekit_error(fn, path)

    run()
    path = tmp_path / f"latin1{suffix}"
    path.write_bytes("name = 'caf\xe9'\n".encode("latin-1"))
    with pytest.raises(TilekitError, match="not UTF-8"):
        fn(path)


# --------------------------------------------------------------------------- specs and options


def test_periodic_spec_never_crashes() -> None:
    from tilekit.tiling import PeriodicTiling, Prototile

    base = {
        "kind": "periodic",
        "prototiles": [{"outline": [[0, 0], [1, 0], [1, 1], [0, 1]]}],
        "unit": [{"prototile": 0, "transform": [[1, 0, 0], [0, 1, 0]], "aspect": 0}],
        "v1": [1, 0], "v2": [0, 1], "colouring": "(1)(1)(1)", "name": "sq", "family": "x",
    }

    @FAST
    @given(st.data())
    def run(data: st.DataObject) -> None:
        doc = _mutated(base, data)
        parses_or_tilekit_error(PeriodicTiling.from_spec, doc)
        parses_or_tilekit_error(Prototile.from_json, doc["prototiles"][0] if isinstance(doc.get("prototiles"), list)
                                and doc["prototiles"] and isinstance(doc["prototiles"][0], dict) else {})

    run()


CONFIGURE_CASES = [
    ("penrose-p3", "substitution"), ("chair", "substitution"), ("spectre", "substitution"),
    ("hat", "substitution"), ("IH41", "isohedral"), ("stochastic-2colour", "wang"),
]


@pytest.mark.parametrize("name,family", CONFIGURE_CASES)
def test_family_options_never_crash(name: str, family: str) -> None:
    # tilekit render NAME --set KEY=VALUE / --depth / --param / --edge: configure() takes text
    from tilekit.plugins import families

    fam = families()[family]
    tiling = fam.from_spec({"system": name} if family == "substitution" else
                           {"ih": 41} if family == "isohedral" else {"set": name})
    keys = ["depth", "seed", "params", "edges", "colouring", "colours", "method", "time_limit", "r1", "theta1",
            "nope"]

    @FAST
    @given(st.sampled_from(keys), st.one_of(st.text(alphabet="0123456789.-e(), =abc:", max_size=20),
                                            st.lists(st.text(alphabet="0123456789.-e,:=b", max_size=10), max_size=3)))
    def run(key: str, value: Any) -> None:
        parses_or_tilekit_error(lambda: tiling.configure(**{key: value}))

    run()


def test_cli_option_types_never_crash() -> None:
    from tilekit.cli_types import COUNT, POSITIVE, RUN_ID, BoundedInt, FiniteFloat

    types = [COUNT, POSITIVE, RUN_ID, BoundedInt(16, 10_000), FiniteFloat(1e9), FiniteFloat(1e7, min=0.0)]

    @FAST
    @given(st.sampled_from(types), st.one_of(st.text(alphabet="0123456789+-_.e infa", max_size=30),
                                             st.text(max_size=10), st.integers()))
    def run(kind: click.ParamType, value: Any) -> None:
        try:
            kind.convert(value, None, None)
        except click.BadParameter as exc:
            assert "\n" not in exc.format_message()

    run()
    for kind in types:
        for text in ("9" * 5000, "--0", "+-1"):  # hypothesis once found '--0' (two signs) crashing int()
            with pytest.raises(click.BadParameter):
                kind.convert(text, None, None)


@pytest.fixture(scope="module")
def catalogue_url(tmp_path_factory) -> str:
    from click.testing import CliRunner

    from tilekit.cli import cli

    url = f"sqlite:///{tmp_path_factory.mktemp('fuzzcat') / 'cat.sqlite'}"
    assert CliRunner().invoke(cli, ["--catalogue", url, "list", "--limit", "1"]).exit_code == 0
    return url


OPTION_TEXT = st.text(alphabet="0123456789.,-e:=ab#fx inf", max_size=24)


def test_render_options_through_the_cli(catalogue_url, tmp_path) -> None:
    # tilekit render NAME --region/--param/--colours/--set/--edge/--depth/--width with generated
    # values: exit 0 with a file, or exit 2 with one line "error: ..." (never a traceback)
    from click.testing import CliRunner

    from tilekit.cli import cli

    options = ["--region", "--param", "--colours", "--set", "--edge", "--depth", "--width", "--max-tiles", "--stroke"]

    @settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow,
                                                                    HealthCheck.function_scoped_fixture])
    @given(st.sampled_from(["4^4", "IH16", "penrose-p3", "chair", "stochastic-2colour"]),
           st.lists(st.tuples(st.sampled_from(options), OPTION_TEXT), min_size=1, max_size=3))
    def run(name: str, opts: list[tuple[str, str]]) -> None:
        argv = ["--catalogue", catalogue_url, "render", name, "-o", str(tmp_path / "f.svg"), "--max-tiles", "20000"]
        for flag, value in opts:
            argv += [flag, value]
        result = CliRunner().invoke(cli, argv)
        assert "Traceback" not in result.output
        assert result.exception is None or isinstance(result.exception, SystemExit), repr(result.exception)
        if result.exit_code != 0:
            lines = result.stderr.splitlines()
            assert result.exit_code == 2 and len(lines) == 1 and lines[0].startswith("error: "), result.stderr

    run()


@pytest.mark.parametrize("name,family,n", [("IH41", "isohedral", 2), ("penrose-p2", "substitution", 1)])
@pytest.mark.parametrize("value", ["1e308", "-1e300", "1e200", "nan", "inf"])
def test_huge_params_are_errors_without_warnings(name, family, n, value):
    # tilekit render IH41 --param 1e308 (library side): a ParameterError, no NumPy overflow warning
    from tilekit.plugins import families

    fam = families()[family]
    tiling = fam.from_spec({"ih": 41} if family == "isohedral" else {"system": name})
    parses_or_tilekit_error(lambda: tiling.configure(params=[value] * n).patch((-3, -3, 3, 3)))


# --------------------------------------------------------------------------- issue 27: type-confused documents
#
# Every family's from_spec, every loader of a user's file and the JSON / TOML parsers, fed
# documents whose parts are replaced by values of the wrong type, nested past any sane depth,
# or numbers that are huge (a 400-digit integer), non-finite or at the edge of a float. The
# outcome is a value or a TilekitError with a one-line message: never another exception, never
# a NumPy warning. A fast profile runs by default; the slow run (-m slow) tries thousands.

FUZZ_FAST = settings(max_examples=50, deadline=None, suppress_health_check=list(HealthCheck))
FUZZ_SLOW = settings(max_examples=2000, deadline=None, suppress_health_check=list(HealthCheck))


def _nested(depth: int, leaf: Any = 0) -> Any:
    value = leaf
    for _ in range(depth):
        value = [value]
    return value


SCALARS = st.one_of(
    st.none(), st.booleans(), st.integers(-3, 12), st.integers(-(10**400), 10**400),
    st.sampled_from([2**63, -(2**63) - 1, 10**400, 10**4000]), st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([1e308, -1e308, 5e-324, float("inf"), float("-inf"), float("nan")]),
    st.text(max_size=8), st.sampled_from(["", "IH28", "sqrt(2)", "1e999", "0,0:1,0", "(1)(1)(1)", "x" * 300]),
)
CONFUSED = st.one_of(
    SCALARS,
    st.lists(SCALARS, max_size=4),
    st.dictionaries(st.text(max_size=6), SCALARS, max_size=3),
    st.builds(_nested, st.integers(30, 200), SCALARS),
    st.builds(lambda d: {"a": _nested(d)}, st.integers(30, 120)),
)


def _confused(base: Any, data: st.DataObject) -> Any:
    """``base`` with 1-3 parts replaced by CONFUSED values (or a key dropped); now and then
    a document of the wrong kind altogether."""
    if not _slots(base) or data.draw(st.integers(0, 19)) == 0:
        return data.draw(CONFUSED)
    return _mutated(base, data, CONFUSED)


def _built_and_drawn(from_spec: Callable[[Any], Any], doc: Any) -> None:
    """from_spec(doc), and a patch of its default region when that is small."""
    tiling = from_spec(doc)
    region = tiling.default_region()
    if tiling.estimate_tiles(region) <= 2000:
        tiling.patch(region)


def _spec_bases() -> dict[str, list[dict]]:
    from tilekit.plugins.isohedral import isohedral_tiling
    from tilekit.plugins.substitution import builtin_systems
    from tilekit.plugins.wang.tileset import get_tileset

    return {
        "archimedean": [{"kind": "archimedean", "vertex_type": "3.4.6.4"}, {"kind": "vertex_type", "vertex_type": "4.8.8"}],
        "laves": [{"kind": "laves", "vertex_type": "3.3.4.3.4"}],
        "isohedral": [isohedral_tiling("IH16", params=[0.3], edges=["b=0,0:0.3,0.1:1,0"]).spec(),
                      {"ih": 41, "params": [0.1, 0.2], "colouring": "(1 2)(2 1)(1 2)"}, {"ih": 19}],
        "substitution": [{"system": "penrose-p3", "depth": 2, "seed": "obtuse"}, {"system": "spectre", "depth": 1},
                         {"system": "penrose-p3", "params": [0.2], "edges": ["a=0.5,0.1"]},
                         {"system_data": copy.deepcopy(builtin_systems()["chair"].data), "source": "x.toml", "depth": 2}],
        "wang": [{"set": "jeandel-rao-11", "seed": 3, "method": "auto"},
                 {"tileset": get_tileset("stochastic-2colour").to_json(), "seed": 1}],
        "polyomino": [{"code": ".x./xx./.xx", "name": "pentomino-F", "tiling": 0},
                      {"code": "xxx/x.x/xxx", "view": "coronas",
                       "witness": {"kind": "coronas", "tiles": [[0, 0, 0, 0], [0, 3, 0, 1]]}},
                      {"code": "xx/x.", "witness": {"kind": "torus", "tiles": [[0, 0, 0, 0]], "lattice": [1, 0, 1]}}],
        "k-uniform": [{"kind": "k-uniform", "dsymbol": "3,12,12/3,3,3/0,1,2/0,2,1/1,0,2", "name": "[3.12^2] p6m"}],
        "spherical": [{"p": 5, "q": 3}, {"p": 3, "q": 4, "samples": 3, "name": "octahedron"}],
        "hyperbolic": [{"p": 7, "q": 3, "depth": 3}, {"p": 5, "q": 4, "radius": 2.5, "samples": 2}],
        "curved": [{"configuration": "3.4.4.4"}, {"symbol": "2 3 | 7", "radius": 1.5, "samples": 2},
                   {"configuration": "3.3.4.3.5", "plane": "halfplane", "radius": 1.0, "geometry": "hyperbolic"},
                   {"configuration": "3.3.3.6.6", "pairing": "0- 1+ 2+ 3- 4+", "radius": 1.5},
                   {"laves": True, "configuration": "3.3.3.6.6", "pairing": "0- 1+ 2+ 3- 4+", "group": "rotations",
                    "radius": 1.0, "edges": {"c": "0.3,0.1:0.6,-0.08"}},
                   {"laves": True, "configuration": "3.4.3.4"},
                   {"laves": True, "configuration": "4.6.14", "radius": 1.5, "samples": 2},
                   {"laves": True, "symbol": "2 3 | 7", "group": "rotations", "radius": 1.0, "plane": "klein"}],
        "curved-isohedral": [{"p": 6, "q": 4, "pairing": "a a b b c d", "radius": 2.0, "edges": {"a": "0.3,0.1:0.6,-0.1"}},
                             {"p": 3, "q": 3, "pairing": "a b c", "samples": 2},
                             {"p": 4, "q": 5, "symbol": "[abab; ba]", "radius": 1.5, "edges": {"a": "0.2,0.1:0.35,-0.05"}}],
        "quasiperiodic": [{"n": 5}, {"n": 8, "gamma": [0.1, 0.2, 0.3, 0.4], "singular": "perturb"}],
    }


SPEC_BASES = _spec_bases()


def test_every_family_has_a_fuzzed_spec():
    from tilekit.plugins import families

    assert set(families()) <= set(SPEC_BASES), set(families()) - set(SPEC_BASES)
    for name, bases in SPEC_BASES.items():
        for base in bases:
            _built_and_drawn(families()[name].from_spec, base)  # the bases themselves build


def _fuzz_from_spec(family: str, profile: Any) -> None:
    from tilekit.plugins import families

    from_spec = families()[family].from_spec

    @profile
    @given(st.sampled_from(SPEC_BASES[family]), st.data())
    def run(base: dict, data: st.DataObject) -> None:
        parses_or_tilekit_error(_built_and_drawn, from_spec, _confused(base, data))

    run()


@pytest.mark.parametrize("family", sorted(SPEC_BASES))
def test_from_spec_never_crashes(family: str) -> None:
    _fuzz_from_spec(family, FUZZ_FAST)


@pytest.mark.slow
@pytest.mark.parametrize("family", sorted(SPEC_BASES))
def test_from_spec_never_crashes_thousands(family: str) -> None:
    _fuzz_from_spec(family, FUZZ_SLOW)


def _toml_value(value: Any) -> str | None:
    """``value`` as an inline TOML value (None: not representable, the key is left out)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value) if value.bit_length() < 4000 else None
    if isinstance(value, float):
        return "nan" if value != value else ("inf" if value > 0 else "-inf") if value in (float("inf"), float("-inf")) else repr(value)
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, list):
        items = [_toml_value(v) for v in value]
        return "[" + ", ".join(v for v in items if v is not None) + "]"
    if isinstance(value, dict):
        items = [(json.dumps(str(k)), _toml_value(v)) for k, v in value.items()]
        return "{" + ", ".join(f"{k} = {v}" for k, v in items if v is not None) + "}"
    return None


def _toml(doc: Any) -> str:
    if not isinstance(doc, dict):
        doc = {"value": doc}
    lines = [f"{json.dumps(str(k))} = {v}" for k, v in ((k, _toml_value(v)) for k, v in doc.items()) if v is not None]
    return "\n".join(lines) + "\n"


def _loaders() -> dict[str, tuple[Callable[[Any], Any], str, Callable[[], list[Any]], Callable[[Any], str]]]:
    """name -> (loader of a path, file name, base documents, writer of a document as text)."""
    from tilekit.plugins import families
    from tilekit.plugins.isohedral.escher import read_goal
    from tilekit.plugins.substitution import system_dir
    from tilekit.plugins.substitution.system import load_system
    from tilekit.plugins.wang.render import load_texture
    from tilekit.plugins.wang.tileset import load_tileset
    from tilekit.resources import catalogue_dir

    def tomls(folder: Any) -> Callable[[], list[Any]]:
        return lambda: [tomllib.loads(p.read_text(encoding="utf-8")) for p in sorted(folder.glob("*.toml"))[:4]]

    def wang_text(doc: Any) -> str:  # a .wang file: header lines and tile lines from the document's parts
        from tilekit.plugins.wang.tileset import WangTileSet

        try:
            return WangTileSet.from_json(doc).to_text()
        except TilekitError:
            return "\n".join(f"{k}: {v}" if not isinstance(v, list) else "tiles: N E S W\n" + "\n".join(
                " ".join(map(str, r)) if isinstance(r, list) else str(r) for r in v) for k, v in
                (doc.items() if isinstance(doc, dict) else [("name", doc)])) + "\n"

    def svg_text(doc: Any) -> str:  # a <polygon points>, or a <path d> for a {"d": ...} document
        def flat(value: Any) -> str:
            if isinstance(value, list | tuple):
                return " ".join(flat(v) for v in value)
            return str(value)

        if isinstance(doc, dict):
            body = f'<path d="M {flat(list(doc.values()))} Z"/>'
        else:
            body = f'<polygon points="{flat(doc)}"/>'
        return f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10">{body}</svg>'

    from tilekit.plugins.wang.tileset import get_tileset

    return {
        "substitution --system": (load_system, "fuzz.toml", tomls(system_dir()), _toml),
        "wang --texture": (load_texture, "fuzz.toml", tomls(catalogue_dir() / "wang" / "textures"), _toml),
        "isohedral spec file": (families()["isohedral"].from_file, "fuzz.isohedral.json",
                                lambda: [SPEC_BASES["isohedral"][0], {"family": "isohedral", "spec": {"ih": 41}}], json.dumps),
        "escherize goal": (read_goal, "fuzz.json",
                           lambda: [[[0, 0], [2, 0], [2, 1], [1, 2], [0, 1]], {"points": [[0, 0], [1, 0], [0, 1]]}],
                           json.dumps),
        "escherize SVG goal": (read_goal, "fuzz.svg",
                               lambda: [[[0, 0], [2, 0], [2, 1], [1, 2], [0, 1]], {"d": [[0, 0], [1, 0], [0, 1]]}],
                               svg_text),
        ".wang tile set": (load_tileset, "fuzz.wang",
                           lambda: [get_tileset("jeandel-rao").to_json(), get_tileset("corner-2colour").to_json()],
                           wang_text),
    }


LOADERS = _loaders()


def _fuzz_loader(name: str, tmp_path: Any, profile: Any) -> None:
    load, filename, bases, write = LOADERS[name]
    docs = bases()

    @profile
    @given(st.sampled_from(docs), st.data())
    def run(base: Any, data: st.DataObject) -> None:
        path = tmp_path / filename
        try:
            text = write(_confused(base, data))
        except (ValueError, TypeError):  # e.g. json.dumps of an integer Python will not print
            return
        path.write_text(text, encoding="utf-8", errors="surrogatepass")
        parses_or_tilekit_error(load, path)

    run()


@pytest.mark.parametrize("name", sorted(LOADERS))
def test_file_loader_never_crashes(name: str, tmp_path) -> None:
    _fuzz_loader(name, tmp_path, FUZZ_FAST)


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(LOADERS))
def test_file_loader_never_crashes_thousands(name: str, tmp_path) -> None:
    _fuzz_loader(name, tmp_path, FUZZ_SLOW)


JSON_TEXT = st.recursive(
    st.one_of(st.sampled_from(["0", "-1", "1e400", "-1e400", "NaN", "Infinity", "-Infinity", "1" * 5000, "true", "null",
                               '"x"', "1.5", "2e-400"])),
    lambda inner: st.one_of(st.lists(inner, max_size=4).map(lambda xs: "[" + ",".join(xs) + "]"),
                            st.lists(inner, max_size=3).map(lambda xs: "{" + ",".join(f'"k{i}":{x}' for i, x in enumerate(xs)) + "}"),
                            st.integers(30, 3000).map(lambda d: "[" * d + "]" * d),
                            st.integers(30, 3000).map(lambda d: '{"a":' * d + "1" + "}" * d)),
    max_leaves=12,
)


def _fuzz_parsers(profile: Any) -> None:
    from tilekit.schema import parse_json, parse_toml

    @profile
    @given(JSON_TEXT, st.text(max_size=40))
    def run(text: str, noise: str) -> None:
        parses_or_tilekit_error(parse_json, text, "fuzz.json")
        parses_or_tilekit_error(parse_json, text + noise, "fuzz.json")
        parses_or_tilekit_error(parse_toml, "a = " + text.replace(":", "="), "fuzz.toml")
        parses_or_tilekit_error(parse_toml, noise, "fuzz.toml")

    run()


def test_json_and_toml_parsers_never_crash() -> None:
    _fuzz_parsers(FUZZ_FAST)


@pytest.mark.slow
def test_json_and_toml_parsers_never_crash_thousands() -> None:
    _fuzz_parsers(FUZZ_SLOW)


def test_png_densities_of_any_header(tmp_path) -> None:
    # a PNG signature, an IHDR of any size and any bytes after it: a density or one ParseError
    # (LimitError past the pixel limit), never PIL's DecompressionBombError
    import struct
    import zlib

    from tilekit.density import from_image

    @FUZZ_FAST
    @given(st.integers(0, 2**32 - 1), st.integers(0, 2**32 - 1), st.binary(max_size=200))
    def run(w: int, h: int, tail: bytes) -> None:
        body = struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0)
        ihdr = struct.pack(">I", 13) + b"IHDR" + body + struct.pack(">I", zlib.crc32(b"IHDR" + body))
        path = tmp_path / "fuzz.png"
        path.write_bytes(b"\x89PNG\r\n\x1a\n" + ihdr + tail)
        parses_or_tilekit_error(from_image, path)

    run()
