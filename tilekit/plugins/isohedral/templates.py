"""Isohedral templates (§5.4.5, Appendix A) and tiling vertex parameterizations (§5.4.1) as data.

The shipped text files catalogue/isohedral/templates.ih and parameterizations.tv are read by
:func:`load_templates` and :func:`load_parameterizations`; malformed input raises ParseError
naming the file, the line and the problem.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np

from tilekit.colouring import Colouring
from tilekit.errors import NotFoundError, ParseError
from tilekit.incidence import IncidenceSymbol
from tilekit.resources import catalogue_dir

_TOPOLOGY = re.compile(r"^\d+(\^\d+)?(\.\d+(\^\d+)?)*$")


def topology_valences(topology: str) -> list[int]:
    """The vertex valences around a tile of a topological type, e.g. '3^4.6' -> [3, 3, 3, 3, 6]."""
    if not _TOPOLOGY.match(topology):
        raise ParseError(f"topological type {topology!r} is not like '3^6', '3^4.6' or '4.8^2'")
    out: list[int] = []
    for part in topology.split("."):
        if "^" in part:
            base, exp = part.split("^")
            out += [int(base)] * int(exp)
        else:
            out.append(int(part))
    return out


@dataclass(frozen=True)
class Rule:
    """``target <- base; hops`` (hops are 1-based edge numbers of the incidence symbol)."""

    target: str
    base: str
    hops: tuple[int, ...]

    def __str__(self) -> str:
        return f"{self.target} <- {self.base}; {', '.join(str(h) for h in self.hops)}"


@dataclass(frozen=True)
class Parameterization:
    """A tiling vertex parameterization: a (2k, n+1) coefficient matrix and default parameters."""

    name: str
    topology: str
    coefficients: np.ndarray
    default: tuple[float, ...]

    @property
    def parameters(self) -> int:
        return self.coefficients.shape[1] - 1

    @property
    def vertices(self) -> int:
        return self.coefficients.shape[0] // 2

    def evaluate(self, params: np.ndarray | list[float] | tuple[float, ...]) -> np.ndarray:
        """Tiling vertex positions (k, 2) for a parameter vector (§5.4.1)."""
        v = np.append(np.asarray(params, dtype=float), 1.0)
        return (self.coefficients @ v).reshape(-1, 2)


@dataclass(frozen=True)
class Template:
    """One isohedral type: topology, incidence symbol and (for unmarked types) its template."""

    ih: int
    topology: str
    symbol: IncidenceSymbol | None
    marked: bool = False
    parameterization: str | None = None
    colouring_text: str | None = None
    aspects: tuple[str, ...] = ()
    rules: tuple[Rule, ...] = ()
    edge_offset: int = 0
    notes: tuple[str, ...] = ()
    source: str = ""
    line: int = 0
    extra: dict = field(default_factory=dict, compare=False)

    @property
    def name(self) -> str:
        return f"IH{self.ih}"

    @property
    def colouring(self) -> Colouring | None:
        """The default colouring (Appendix A prints 0-based colours; Colouring is 1-based text)."""
        if self.colouring_text is None:
            return None
        return parse_zero_based_colouring(self.colouring_text)

    def text(self) -> str:
        """The template in the data file's format (``tilekit show`` prints it; it parses back)."""
        head = f"{self.name} {self.topology}"
        if self.symbol is not None:
            head += f" {self.symbol}"
        lines = [head + (" marked" if self.marked else "")]
        lines += [f"  note {n}" for n in self.notes]
        if self.marked:
            if self.source:
                lines.append(f"  source {self.source}")
            return "\n".join(lines)
        if self.edge_offset:
            lines.append(f"  edge-offset {self.edge_offset}")
        lines.append(f"  parameterization {self.parameterization}")
        lines.append(f"  colouring {self.colouring_text}")
        lines.append("  aspects " + ", ".join(self.aspects))
        lines += [f"  rule {r}" for r in self.rules]
        return "\n".join(lines)


def parse_zero_based_colouring(text: str) -> Colouring:
    """Parse '(0 1) (1 2 0) (0 1 2)' with 0-based colours as printed in Appendix A."""
    groups = re.findall(r"\(([^()]*)\)", text)
    try:
        shifted = ["(" + " ".join(str(int(x) + 1) for x in g.split()) + ")" for g in groups]
    except ValueError:
        raise ParseError(f"colouring {text!r} holds a non-integer") from None
    return Colouring.parse("".join(shifted))


def _fail(path: Path | str, lineno: int, problem: str) -> ParseError:
    return ParseError(f"{Path(path).name}, line {lineno}: {problem}")


def _read_blocks(text: str, path: Path | str, what: str, header: Callable[[str, int], dict[str, Any]],
                 entry: Callable[[dict[str, Any], str, int], None],
                 finish: Callable[[dict[str, Any] | None], None]) -> None:
    """Read a block file (.ih, .tv): a line that is not indented opens a block (``header``
    makes its record), indented lines are its entries, ``finish`` checks a block when the
    next begins or the text ends. ``#`` starts a comment; blank lines are skipped."""
    cur: dict[str, Any] | None = None
    for lineno, raw in enumerate(text.splitlines(), 1):
        line = raw.split("#", 1)[0].rstrip()
        if not line.strip():
            continue
        if not raw.startswith((" ", "\t")):
            finish(cur)
            cur = header(line, lineno)
        elif cur is None:
            raise _fail(path, lineno, f"indented line before the first '{what}' header")
        else:
            entry(cur, line, lineno)
    finish(cur)


# --------------------------------------------------------------------------- parameterizations


def parse_parameterizations(text: str, path: Path | str = "parameterizations.tv") -> dict[str, Parameterization]:
    """Parse the parameterization file format (see the file's header): a 'TVn' header line
    opens a block, indented 'default' and 'Pj' lines fill it, and each finished block is
    compiled to its coefficient matrix once."""
    out: dict[str, Parameterization] = {}

    def entry(cur: dict[str, Any], line: str, lineno: int) -> None:
        parts = line.split()
        if parts[0] == "default":
            _tv_default(cur, parts[1:], path, lineno)
        elif re.fullmatch(r"P\d+", parts[0]):
            _tv_vertex(cur, parts, path, lineno)
        else:
            raise _fail(path, lineno, f"unknown entry {parts[0]!r} (expected 'default' or 'Pj')")

    _read_blocks(text, path, "TVn", lambda line, lineno: _parameterization_header(line, out, path, lineno),
                 entry, lambda cur: _finish_parameterization(cur, out, path))
    return out


def _parameterization_header(line: str, out: Mapping[str, Parameterization], path: Path | str,
                             lineno: int) -> dict[str, Any]:
    parts = line.split()
    if len(parts) != 4 or not re.fullmatch(r"TV\d+", parts[0]) or parts[2] != "parameters":
        raise _fail(path, lineno, f"expected 'TVn <topology> parameters <n>', got {line.strip()!r}")
    try:
        n = int(parts[3])
    except ValueError:
        raise _fail(path, lineno, f"parameter count {parts[3]!r} is not an integer") from None
    topology_valences_checked(parts[1], path, lineno)
    if parts[0] in out:
        raise _fail(path, lineno, f"{parts[0]} is defined twice")
    return {"name": parts[0], "topology": parts[1], "n": n, "default": None, "rows": [], "line": lineno}


def _tv_default(cur: dict[str, Any], values: list[str], path: Path | str, lineno: int) -> None:
    vals = [] if values == ["-"] else values
    try:
        cur["default"] = [float(v) for v in vals]
    except ValueError:
        raise _fail(path, lineno, f"default {' '.join(vals)!r} holds a non-number") from None
    if len(cur["default"]) != cur["n"]:
        raise _fail(path, lineno, f"{cur['name']} has {cur['n']} parameters but {len(vals)} defaults")


def _tv_vertex(cur: dict[str, Any], parts: list[str], path: Path | str, lineno: int) -> None:
    want = len(cur["rows"]) // 2 + 1
    if int(parts[0][1:]) != want:
        raise _fail(path, lineno, f"expected vertex P{want}, got {parts[0]}")
    try:
        xi, yi = parts.index("x"), parts.index("y")
        xs = [float(v) for v in parts[xi + 1 : yi]]
        ys = [float(v) for v in parts[yi + 1 :]]
    except ValueError:
        raise _fail(path, lineno, "vertex line must be 'Pj x c1 .. c(n+1) y c1 .. c(n+1)' (numbers)") from None
    if len(xs) != cur["n"] + 1 or len(ys) != cur["n"] + 1:
        raise _fail(
            path, lineno, f"{parts[0]} needs {cur['n'] + 1} coefficients for x and for y, "
            f"got {len(xs)} and {len(ys)}"
        )
    cur["rows"].append(xs)
    cur["rows"].append(ys)


def _finish_parameterization(cur: dict[str, Any] | None, out: dict[str, Parameterization], path: Path | str) -> None:
    if cur is None:
        return
    if cur["default"] is None:
        raise _fail(path, cur["line"], f"{cur['name']} has no 'default' line")
    if len(cur["rows"]) < 6:
        raise _fail(path, cur["line"], f"{cur['name']} has {len(cur['rows']) // 2} vertices; a tile needs 3 or more")
    m = np.array(cur["rows"], dtype=float)
    out[cur["name"]] = Parameterization(cur["name"], cur["topology"], m, tuple(cur["default"]))


def topology_valences_checked(topology: str, path: Path | str, lineno: int) -> list[int]:
    try:
        return topology_valences(topology)
    except ParseError as exc:
        raise _fail(path, lineno, str(exc)) from None


# --------------------------------------------------------------------------- templates

_RULE = re.compile(r"^(\w+)\s*<-\s*(\w+)\s*;\s*(\d+(\s*,\s*\d+)*)$")


def parse_templates(text: str, path: Path | str = "templates.ih") -> dict[int, Template]:
    """Parse the template file format (see the file's header): header lines open a block,
    indented lines are entries read by the handlers of ``_ENTRIES``, and each finished
    block is checked and compiled to a :class:`Template`."""
    out: dict[int, Template] = {}

    def entry(cur: dict[str, Any], line: str, lineno: int) -> None:
        key, _, value = line.strip().partition(" ")
        handler = _ENTRIES.get(key)
        if handler is None:
            raise _fail(
                path, lineno,
                f"unknown entry {key!r} (expected parameterization, colouring, aspects, rule, "
                "edge-offset, note or source)",
            )
        handler(cur, value.strip(), path, lineno)

    _read_blocks(text, path, "IHn", lambda line, lineno: _template_header(line, out, path, lineno),
                 entry, lambda cur: _finish_template(cur, out, path))
    return out


def _template_header(line: str, out: Mapping[int, Template], path: Path | str, lineno: int) -> dict[str, Any]:
    """A block's first line, 'IHn <topology> [<symbol>]' or 'IHn <topology> [<symbol>] marked'."""
    m = re.match(r"^IH(\d+)\s+(\S+)(?:\s+(\[.*\]))?\s*(marked)?\s*$", line)
    if not m or (m.group(3) is None and not m.group(4)):
        raise _fail(
            path, lineno, f"expected 'IHn <topology> [<symbol>]' or 'IHn <topology> marked', got {line.strip()!r}"
        )
    ih = int(m.group(1))
    if not 1 <= ih <= 93:
        raise _fail(path, lineno, f"IH{ih} is not one of IH1..IH93")
    if ih in out:
        raise _fail(path, lineno, f"IH{ih} is defined twice")
    valences = topology_valences_checked(m.group(2), path, lineno)
    symbol = None
    if m.group(3) is not None:
        try:
            symbol = IncidenceSymbol.parse(m.group(3))
        except ParseError as exc:
            raise _fail(path, lineno, str(exc)) from None
    if symbol is not None and len(symbol) != len(valences):
        raise _fail(
            path, lineno, f"IH{ih}: symbol {symbol} has {len(symbol)} edges but topology "
            f"{m.group(2)} has {len(valences)}"
        )
    return {
        "ih": ih, "topology": m.group(2), "symbol": symbol, "marked": bool(m.group(4)),
        "parameterization": None, "colouring": None, "colouring_line": lineno, "aspects": None,
        "rules": [], "offset": 0, "notes": [], "source": "", "line": lineno,
    }


def _entry_parameterization(cur: dict[str, Any], value: str, path: Path | str, lineno: int) -> None:
    if not re.fullmatch(r"TV\d+", value):
        raise _fail(path, lineno, f"parameterization {value!r} is not 'TVn'")
    cur["parameterization"] = value


def _entry_colouring(cur: dict[str, Any], value: str, path: Path | str, lineno: int) -> None:
    cur["colouring"] = value
    cur["colouring_line"] = lineno


def _entry_aspects(cur: dict[str, Any], value: str, path: Path | str, lineno: int) -> None:
    names = [a.strip() for a in value.split(",") if a.strip()]
    if not names or len(set(names)) != len(names):
        raise _fail(path, lineno, f"aspects {value!r} must be distinct names separated by commas")
    cur["aspects"] = names


def _entry_rule(cur: dict[str, Any], value: str, path: Path | str, lineno: int) -> None:
    rm = _RULE.match(value)
    if not rm:
        raise _fail(path, lineno, f"rule {value!r} is not 'A <- B; i, j, ...'")
    hops = tuple(int(h) for h in rm.group(3).split(","))
    cur["rules"].append((Rule(rm.group(1), rm.group(2), hops), lineno))


def _entry_edge_offset(cur: dict[str, Any], value: str, path: Path | str, lineno: int) -> None:
    try:
        cur["offset"] = int(value)
    except ValueError:
        raise _fail(path, lineno, f"edge-offset {value!r} is not an integer") from None


def _entry_note(cur: dict[str, Any], value: str, path: Path | str, lineno: int) -> None:
    cur["notes"].append(value)


def _entry_source(cur: dict[str, Any], value: str, path: Path | str, lineno: int) -> None:
    cur["source"] = value


#: The entries of a template block, by keyword.
_ENTRIES = {
    "parameterization": _entry_parameterization,
    "colouring": _entry_colouring,
    "aspects": _entry_aspects,
    "rule": _entry_rule,
    "edge-offset": _entry_edge_offset,
    "note": _entry_note,
    "source": _entry_source,
}


def _finish_template(cur: dict[str, Any] | None, out: dict[int, Template], path: Path | str) -> None:
    """Check a finished block and add its Template to ``out``."""
    if cur is None:
        return
    ln = cur["line"]
    if cur["marked"]:
        if not cur["source"]:
            raise _fail(path, ln, f"marked type IH{cur['ih']} needs a 'source' line citing its symbol")
    else:
        for key in ("parameterization", "colouring", "aspects"):
            if cur[key] is None:
                raise _fail(path, ln, f"IH{cur['ih']} has no '{key}' line")
        if cur["symbol"] is None:
            raise _fail(path, ln, f"unmarked type IH{cur['ih']} needs an incidence symbol")
        _check_rules(cur, path)
        _check_colouring(cur, path)
    out[cur["ih"]] = Template(
        ih=cur["ih"],
        topology=cur["topology"],
        symbol=cur["symbol"],
        marked=cur["marked"],
        parameterization=cur["parameterization"],
        colouring_text=cur["colouring"],
        aspects=tuple(cur["aspects"] or ()),
        rules=tuple(r for r, _ in cur["rules"]),
        edge_offset=cur["offset"],
        notes=tuple(cur["notes"]),
        source=cur["source"],
        line=ln,
    )


def _check_rules(cur: dict[str, Any], path: Path | str) -> None:
    """Every rule builds on a defined aspect and hops across real edges; every aspect and
    each of v1, v2 gets exactly one rule."""
    names = cur["aspects"]
    n = len(cur["symbol"])
    defined = {names[0]}
    for rule, rl in cur["rules"]:
        if rule.base not in defined:
            raise _fail(path, rl, f"rule '{rule}' uses aspect {rule.base!r} before it is defined")
        if rule.target in ("v1", "v2"):
            continue
        if rule.target not in names:
            raise _fail(path, rl, f"rule '{rule}' defines {rule.target!r}, not one of the aspects {names}")
        defined.add(rule.target)
        bad = [h for h in rule.hops if not 1 <= h <= n]
        if bad:
            raise _fail(path, rl, f"rule '{rule}' hops across edge {bad[0]}; edges are 1..{n}")
    missing = [a for a in names if a not in defined]
    if missing:
        raise _fail(path, cur["line"], f"IH{cur['ih']}: no rule defines aspect(s) {missing}")
    targets = [r.target for r, _ in cur["rules"]]
    if targets.count("v1") != 1 or targets.count("v2") != 1:
        raise _fail(path, cur["line"], f"IH{cur['ih']} needs exactly one rule for each of v1 and v2")


def _check_colouring(cur: dict[str, Any], path: Path | str) -> None:
    try:
        col = parse_zero_based_colouring(cur["colouring"])
    except ParseError as exc:
        raise _fail(path, cur["colouring_line"], str(exc)) from None
    if len(col.aspects) != len(cur["aspects"]):
        raise _fail(
            path, cur["colouring_line"],
            f"colouring gives {len(col.aspects)} aspect colours for {len(cur['aspects'])} aspects",
        )


def data_dir() -> Path:
    return catalogue_dir() / "isohedral"


@lru_cache(maxsize=1)
def load_parameterizations() -> dict[str, Parameterization]:
    path = data_dir() / "parameterizations.tv"
    return parse_parameterizations(path.read_text(encoding="utf-8"), path)


@lru_cache(maxsize=1)
def load_templates() -> dict[int, Template]:
    path = data_dir() / "templates.ih"
    templates = parse_templates(path.read_text(encoding="utf-8"), path)
    tvs = load_parameterizations()
    for t in templates.values():
        if t.marked:
            continue
        tv = tvs.get(t.parameterization or "")
        if tv is None:
            raise _fail(path, t.line, f"IH{t.ih} uses {t.parameterization}, which parameterizations.tv lacks")
        if tv.vertices != len(t.symbol):
            raise _fail(path, t.line, f"IH{t.ih}: {t.parameterization} has {tv.vertices} vertices, symbol has {len(t.symbol)} edges")
        if tv.topology != t.topology:
            raise _fail(path, t.line, f"IH{t.ih}: topology {t.topology} but {t.parameterization} is for {tv.topology}")
    return templates


def parse_ih_name(name: str | int) -> int:
    """'IH16', 'ih16', 'IH016' or 16 -> 16; NotFoundError otherwise."""
    if isinstance(name, bool) or not isinstance(name, int | str):
        raise NotFoundError("isohedral type", repr(name)[:40], [f"IH{i}" for i in range(1, 94)])
    if isinstance(name, int):
        if not 1 <= name <= 93:
            raise NotFoundError("isohedral type", str(name) if abs(name) < 10**40 else "a huge number",
                                [f"IH{i}" for i in range(1, 94)])
        n = name
    else:
        m = re.fullmatch(r"(?i)\s*(?:ih)?0*(\d{1,4})\s*", str(name))
        if not m:
            raise NotFoundError("isohedral type", str(name), [f"IH{i}" for i in range(1, 94)])
        n = int(m.group(1))
    if not 1 <= n <= 93:
        raise NotFoundError("isohedral type", str(name), [f"IH{i}" for i in range(1, 94)])
    return n


def get_template(name: str | int) -> Template:
    n = parse_ih_name(name)
    templates = load_templates()
    if n not in templates:
        raise NotFoundError("isohedral type", f"IH{n}", [t.name for t in templates.values()])
    return templates[n]
