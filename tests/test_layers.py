"""Layers without circles, read from the code's own imports (issue 29).

Two graphs over every tilekit module: the module-level imports, and every import that can run
(module level and inside functions; ``if TYPE_CHECKING:`` blocks never run and are left out).
Neither may hold a circle. An import inside a function must say why (a measured start-up cost,
an optional dependency) or belong to a module of the reasoned allow-list below. No family
imports another family; the core and the web layer import no family (the plugins' contributions
reach them through hooks and the plugin manager's DEFAULT_PLUGINS, the one list that names them).
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import tilekit

ROOT = Path(tilekit.__file__).parent


def module_name(path: Path) -> str:
    parts = path.relative_to(ROOT.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _target(node: ast.ImportFrom, package: str) -> str:
    if node.level:
        base = package.split(".")
        base = base[: len(base) - node.level + 1]
        return ".".join(base + ([node.module] if node.module else []))
    return node.module or ""


def imports_of(path: Path, modules: set[str], *, nested: bool = False) -> set[str]:
    """The tilekit modules ``path`` imports: at module level (class bodies included, they run
    on import), and with ``nested`` also inside functions. ``if TYPE_CHECKING:`` blocks are
    left out: they never run."""
    name = module_name(path)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    tree = ast.parse(path.read_text(), str(path))
    out: set[str] = set()

    def visit(node: ast.AST) -> None:
        if isinstance(node, ast.If) and isinstance(node.test, ast.Name) and node.test.id == "TYPE_CHECKING":
            for child in node.orelse:
                visit(child)
            return
        if not nested and isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda):
            return
        if isinstance(node, ast.Import):
            for alias in node.names:
                out.add(alias.name)
        elif isinstance(node, ast.ImportFrom):
            target = _target(node, package)
            # ``from package import submodule`` needs the submodule, not the package's
            # __init__ to have finished; ``from module import name`` needs the module
            subs = {f"{target}.{alias.name}" for alias in node.names} & modules
            out.update(subs)
            if len(subs) < len(node.names):
                out.add(target)
        for child in ast.iter_child_nodes(node):
            visit(child)

    visit(tree)
    return {m for m in out if m in modules and m != name}


def module_level_imports(path: Path, modules: set[str]) -> set[str]:
    """The tilekit modules ``path`` imports at module level."""
    return imports_of(path, modules)


def import_graph(*, nested: bool = False) -> dict[str, set[str]]:
    """Module -> the tilekit modules it imports (with ``nested``, inside functions too).

    Only the imports a module writes count: importing a.b.c also runs a/__init__ first, but a
    package that re-exports its submodules is no circle unless a submodule imports the package
    itself (``from tilekit.plugins.isohedral import _from_file`` inside isohedral/cli)."""
    paths = sorted(ROOT.rglob("*.py"))
    modules = {module_name(p) for p in paths}
    return {module_name(p): imports_of(p, modules, nested=nested) for p in paths}


def find_cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []
    counter = [0]

    def strong(v: str) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            strong(v)
    return out


def test_the_graph_sees_known_edges():
    graph = import_graph()
    assert "tilekit.geometry" in graph["tilekit.tiling"]
    assert "tilekit.sat" in graph["tilekit.plugins.wang.sat"]


def test_the_graph_sees_imports_inside_functions():
    graph = import_graph(nested=True)
    # tilekit serve imports the web app when it runs, not when `tilekit --help` lists it
    assert "tilekit.web" in graph["tilekit.cli.serve"]
    assert "tilekit.web" not in import_graph()["tilekit.cli.serve"]


def test_no_import_cycle_among_tilekit_modules():
    assert find_cycles(import_graph()) == []


def test_no_import_cycle_counting_imports_inside_functions():
    """A lazy import is no licence for a circle: the web layer stands beside the command line
    (region parsing lives in tilekit.text), Patch reaches the export layer by name
    (tilekit.tiling.EXPORT_BACKEND), the isohedral analysis stands above its engine."""
    assert find_cycles(import_graph(nested=True)) == []


def test_the_named_layers_point_down():
    graph = import_graph(nested=True)
    assert not {m for m in graph["tilekit.web.service"] if m.startswith("tilekit.cli")}
    assert "tilekit.export" not in graph["tilekit.tiling"]
    assert "tilekit.plugins.isohedral.analysis" not in graph["tilekit.plugins.isohedral.engine"]
    # the export layer is a real module with the functions Patch calls by name
    import tilekit.export
    from tilekit.tiling import EXPORT_BACKEND
    assert EXPORT_BACKEND == tilekit.export.__name__
    called = set(re.findall(r"_export\(\)\.(\w+)\(", (ROOT / "tiling.py").read_text()))
    assert {"adjacency", "plot_patch", "patch_mimebundle", "tiling_mimebundle"} <= called
    for name in called:
        assert callable(getattr(tilekit.export, name)), name


def function_level_tilekit_imports() -> list[tuple[str, int, str, str]]:
    """(module, line, imported tilekit module, source line) for every import inside a
    function, class or ``if TYPE_CHECKING`` block."""
    paths = sorted(ROOT.rglob("*.py"))
    out = []
    for path in paths:
        lines = path.read_text().splitlines()
        tree = ast.parse("\n".join(lines))
        top = {id(n) for n in tree.body}
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and id(node) not in top and not node.level:
                if (node.module or "").startswith("tilekit"):
                    out.append((module_name(path), node.lineno, node.module, lines[node.lineno - 1]))
    return out


#: Modules whose imports inside functions all stay, each for a reason; the nested graph above
#: shows that none of them closes a circle. Every other lazy import says why on its line or
#: the three above it (a measured start-up cost, an optional dependency, TYPE_CHECKING).
LAZY_ALLOWED = {
    # the command line imports the library inside each command so that `tilekit --help` loads
    # no plugin, NumPy, shapely or SQLAlchemy (start-up cost: tests/test_startup.py measures it)
    f"tilekit.cli.{group}": "start-up cost of `tilekit --help`"
    for group in ("base", "listing", "render", "runs", "catalogue", "sample", "serve", "extra")
}


def test_imports_inside_functions_say_why():
    unexplained = []
    for module, lineno, _target, line in function_level_tilekit_imports():
        if module in LAZY_ALLOWED:
            continue
        path = ROOT.parent / (module.replace(".", "/") + ".py")
        if not path.exists():
            path = ROOT.parent / module.replace(".", "/") / "__init__.py"
        source = path.read_text().splitlines()
        context = " ".join(source[max(0, lineno - 4) : lineno])
        if "TYPE_CHECKING" in context or "start-up cost" in context or "optional" in context:
            continue
        unexplained.append(f"{module}:{lineno}: {line.strip()}")
    assert unexplained == []


def family_of(module: str) -> str | None:
    """The family package a module belongs to (``tilekit.plugins.isohedral.engine`` ->
    ``isohedral``), None for the core, the plugin manager and the web layer."""
    parts = module.split(".")
    if len(parts) >= 3 and parts[:2] == ["tilekit", "plugins"]:
        return parts[2]
    return None


def family_violations(graph: dict[str, set[str]]) -> list[str]:
    out = []
    for module, deps in sorted(graph.items()):
        mine = family_of(module)
        for dep in sorted(deps):
            theirs = family_of(dep)
            if theirs is not None and theirs != mine:
                where = f"family {mine}" if mine else ("the web layer" if module.startswith("tilekit.web") else "the core")
                out.append(f"{module} -> {dep} ({where} imports family {theirs})")
    return out


def test_family_rule_checker_sees_a_violation():
    graph = {"tilekit.plugins.a.x": {"tilekit.plugins.b.y"}, "tilekit.web.app": {"tilekit.plugins.a"},
             "tilekit.tiling": {"tilekit.plugins.b.y"}, "tilekit.plugins.b.y": {"tilekit.plugins.b", "tilekit.plugins"}}
    assert family_violations(graph) == [
        "tilekit.plugins.a.x -> tilekit.plugins.b.y (family a imports family b)",
        "tilekit.tiling -> tilekit.plugins.b.y (the core imports family b)",
        "tilekit.web.app -> tilekit.plugins.a (the web layer imports family a)",
    ]


def test_no_family_imports_another_and_neither_core_nor_web_imports_a_family():
    """Counting imports inside functions: a family's contributions reach the core and the web
    layer through hooks (tilekit/hookspecs.py), never by name."""
    assert family_violations(import_graph(nested=True)) == []


def test_no_core_module_names_a_family_module_in_a_string():
    """importlib.import_module("tilekit.plugins.x") would dodge the import graph; only the plugin
    manager's DEFAULT_PLUGINS names the built-in families."""
    found = []
    for path in sorted(ROOT.rglob("*.py")):
        module = module_name(path)
        if family_of(module) is not None or module == "tilekit.plugins":
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Constant) and isinstance(node.value, str):
                if re.fullmatch(r"tilekit\.plugins\.\w+(\.\w+)*", node.value):
                    found.append(f"{module}: {node.value!r}")
    assert found == []
