"""The plugin manager, the built-in family plugins, and the small types plugins return.

Built-in families are ordinary plugins listed in ``DEFAULT_PLUGINS`` and registered
explicitly; third-party ones arrive through the ``tilekit`` entry-point group. Setting
``TILEKIT_PLUGINS`` to a comma-separated list of plugin names (the module's last dotted
component for built-ins, the entry-point name for packages) restricts what loads.
"""

from __future__ import annotations

import importlib
import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import pluggy

from tilekit import hookspecs
from tilekit.errors import NotFoundError, PluginError
from tilekit.recordcache import cached_records

if TYPE_CHECKING:  # pragma: no cover
    from tilekit.tiling import Tiling

DEFAULT_PLUGINS: tuple[str, ...] = (
    "tilekit.plugins.archimedean",
    "tilekit.plugins.isohedral",
    "tilekit.plugins.substitution",
    "tilekit.plugins.wang",
    "tilekit.plugins.polyomino",
    "tilekit.plugins.kuniform",
    "tilekit.plugins.quasiperiodic",
    "tilekit.plugins.curved",
)


@dataclass(frozen=True)
class Family:
    """A tiling family: its name, a one-line summary, and how to rebuild a tiling from a spec.

    ``from_spec(spec)`` receives the JSON object stored in the catalogue (and returned by
    ``Tiling.spec()``) and returns a :class:`tilekit.Tiling`.
    """

    name: str
    summary: str
    from_spec: Callable[[Mapping[str, Any]], Tiling]
    description: str = ""
    #: Optional: build a tiling from a user's data file (``tilekit render --system FILE
    #: --family NAME``), e.g. a substitution system or a Wang tile set.
    from_file: Callable[[str], Tiling] | None = None


@dataclass
class CatalogueRecord:
    """One known tiling (or search result) as the catalogue stores it.

    ``properties`` are the facts the catalogue indexes and queries: JSON scalars (str, int,
    float, bool) or lists of them, stored one row per element so ``--where polygons=6`` tests
    membership; deeper JSON (e.g. a matrix) is stored whole and shown, not compared.
    Catalogue-wide keys: ``periodic``, ``k_hedral``, ``k_isohedral``, ``edge_to_edge``,
    ``symmetry_group`` and ``orbifold`` (orbifold notation, e.g. ``*632``) and
    ``wallpaper_group`` (IUC notation, e.g. ``p6m``). ``aliases`` are other spellings of
    ``name`` that ``tilekit show`` accepts (e.g. ``4.4.4.4`` for ``4^4``).
    """

    family: str
    name: str
    spec: dict[str, Any]
    title: str = ""
    properties: dict[str, Any] = field(default_factory=dict)
    aliases: list[str] = field(default_factory=list)


@dataclass(frozen=True)
class SearchParam:
    """One parameter of a search, shown as a ``--name`` option of ``tilekit search KIND``.

    ``min`` / ``max`` bound a number (inclusive) and ``choices`` lists the values a text
    parameter takes; both are checked before a run is created, so a stored run's parameters
    are always valid.
    """

    name: str
    type: type = str  # str, int, float or bool
    default: Any = None
    help: str = ""
    required: bool = False
    min: float | None = None
    max: float | None = None
    choices: Sequence[str] | None = None


@dataclass
class ChunkResult:
    """What one chunk of a search yields, all written in ONE transaction with its done mark.

    ``results`` are small JSON objects kept with the run (``run_results``); ``rows`` maps a
    plugin result table's name (:class:`ResultTable`) to rows of plain column values,
    bulk-upserted by the table's key; ``records`` are catalogue tilings (new, or updated
    properties); ``counts`` are tallies summed over all chunks into the run's summary.
    """

    results: list[dict[str, Any]] = field(default_factory=list)
    records: list[CatalogueRecord] = field(default_factory=list)
    rows: dict[str, list[dict[str, Any]]] = field(default_factory=dict)
    counts: dict[str, int | float] = field(default_factory=dict)


@dataclass(frozen=True)
class ResultTable:
    """A table of search results that a plugin owns (one row per result, typed columns).

    ``table`` is defined on the plugin's own ``sqlalchemy.MetaData`` and created by the
    plugin's Alembic branch (``tilekit_migration_locations``). ``key`` names the natural key:
    a row whose key exists is updated (only the columns the row gives), never doubled. A
    ``run_id`` column, if the table has one, is filled with the run that wrote the row.
    With ``family`` set, ``tilekit list --family F`` and ``Catalogue.query(family=F)`` read
    this table, filtering on its columns; ``name_column`` is where ``tilekit show NAME``
    looks names up, and ``spec(row)`` turns a row into the spec the family's ``from_spec``
    rebuilds (for show and render); ``tiling_family`` names that family when it is not
    ``family`` itself (e.g. rows listed as ``vertex-species`` rebuilt as ``archimedean``).
    ``aliases`` are further family names that read the same table (``--family polyform`` for
    the polyomino family's rows on every grid). ``scopes`` restricts a family name to some
    rows: ``(name, column, value)`` entries, e.g. ``("polyomino", "grid", "square")`` (the
    table as that family is read with ``where`` set to those conditions).
    """

    table: Any  # sqlalchemy.Table
    key: tuple[str, ...]
    family: str | None = None
    name_column: str | None = None
    spec: Callable[[Mapping[str, Any]], dict[str, Any]] | None = None
    title: Callable[[Mapping[str, Any]], str] | None = None
    tiling_family: str | None = None
    aliases: tuple[str, ...] = ()
    scopes: tuple[tuple[str, str, Any], ...] = ()
    #: the (column, value) conditions of the family name this table was looked up by
    where: tuple[tuple[str, Any], ...] = ()

    @property
    def name(self) -> str:
        return str(self.table.name)

    def scoped(self, family: str) -> ResultTable:
        """This table as ``family`` reads it (its ``scopes`` for that name as ``where``)."""
        import dataclasses

        return dataclasses.replace(self, where=tuple((c, v) for f, c, v in self.scopes if f == family))


@dataclass(frozen=True)
class Search:
    """An enumeration or search job a family contributes.

    ``chunks(params)`` splits a run into JSON-serialisable chunk descriptions (the unit of
    resume, of leases and of parallel work): a list or any iterable, stored in batches as
    it is produced; ``run_chunk(params, chunk)`` computes one chunk and must be a
    module-level function or otherwise picklable, so process pools and dask workers can run
    it. ``summarize(params, results)`` (optional) turns the run's JSON ``results`` (a list:
    keep them small, and write large outputs as result-table ``rows``) into a short dict
    shown by ``tilekit runs``; the summed ``counts`` of the chunks are added to it.
    """

    name: str
    summary: str
    family: str
    params: Sequence[SearchParam]
    chunks: Callable[[Mapping[str, Any]], Iterable[dict[str, Any]]]
    run_chunk: Callable[[Mapping[str, Any], Mapping[str, Any]], ChunkResult]
    summarize: Callable[[Mapping[str, Any], list[dict[str, Any]]], dict[str, Any]] | None = None


@dataclass(frozen=True)
class Sampler:
    """A tile-based importance sampler (§7.4) a family contributes: ``tilekit sample --method NAME``.

    ``candidates(density, tau_lo, tau_hi, seed)`` returns ``(points, lo, hi)``: every sample
    point its tiles can give inside the unit square whose *threshold interval* [lo, hi) meets
    [tau_lo, tau_hi]. A point is in the set made with threshold tau (the density integral one
    sample stands for) exactly when lo <= tau < hi, so :func:`tilekit.sampling.sample` picks
    tau for the requested count from one call, without regenerating. ``reference`` names the
    paper the method follows. A sampler may return a fourth item, a dict of per-candidate
    arrays, and a ``finish(points, extra, tau)`` that moves the chosen points (a correction
    step); ``extra["key"]`` (a structural context), ``extra["frame"]`` ((m, 2, 2) tile maps)
    and ``extra["integral"]`` let :func:`tilekit.sampling.train_corrections` fit its table.
    """

    name: str
    summary: str
    family: str
    candidates: Callable[..., tuple[Any, ...]]
    reference: str = ""
    finish: Callable[..., Any] | None = None


def _wanted() -> set[str] | None:
    raw = os.environ.get("TILEKIT_PLUGINS")
    if raw is None or not raw.strip():
        return None
    return {part.strip() for part in raw.split(",") if part.strip()}


def make_plugin_manager(extra_plugins: Iterable[object] = ()) -> pluggy.PluginManager:
    """Build a fresh plugin manager: built-ins, entry points, then ``extra_plugins``."""
    pm = pluggy.PluginManager("tilekit")
    pm.add_hookspecs(hookspecs)
    wanted = _wanted()
    for modname in DEFAULT_PLUGINS:
        short = modname.rsplit(".", 1)[-1]
        if wanted is not None and short not in wanted and modname not in wanted:
            continue
        module = importlib.import_module(modname)
        pm.register(module, name=modname)
    if wanted is None:
        pm.load_setuptools_entrypoints("tilekit")
    else:
        from importlib.metadata import entry_points

        for ep in entry_points(group="tilekit"):
            if ep.name in wanted and pm.get_plugin(ep.name) is None:
                pm.register(ep.load(), name=ep.name)
    for plugin in extra_plugins:
        if not pm.is_registered(plugin):  # e.g. an installed plugin, already loaded by its entry point
            pm.register(plugin)
    return pm


_pm: pluggy.PluginManager | None = None


def get_plugin_manager() -> pluggy.PluginManager:
    """The process-wide plugin manager (built on first use)."""
    global _pm
    if _pm is None:
        _pm = make_plugin_manager()
    return _pm


def reset_plugin_manager() -> None:
    """Forget the process-wide manager (tests, or after installing a plugin at run time)."""
    global _pm
    _pm = None


def _flatten(results: Iterable[Iterable[Any] | None]) -> list[Any]:
    out: list[Any] = []
    for items in results:
        if items:
            out.extend(items)
    return out


def _by_name(results: list[Any], cls: type, hook: str, what: str) -> dict[str, Any]:
    """A hook's flattened results by ``name``: each must be a ``cls``, no name twice."""
    out: dict[str, Any] = {}
    for item in _flatten(results):
        if not isinstance(item, cls):
            raise PluginError(f"{hook} returned {type(item).__name__}, not {cls.__name__}")
        if item.name in out:
            raise PluginError(f"two plugins define the {what} {item.name!r}")
        out[item.name] = item
    return out


def families(pm: pluggy.PluginManager | None = None) -> dict[str, Family]:
    """All registered families by name."""
    pm = pm or get_plugin_manager()
    return _by_name(pm.hook.tilekit_families(), Family, "tilekit_families", "family")


def get_family(name: str, pm: pluggy.PluginManager | None = None) -> Family:
    """The family called ``name``, or NotFoundError naming the valid ones."""
    fams = families(pm)
    try:
        return fams[name]
    except KeyError:
        raise NotFoundError("family", name, fams) from None


def _shipped_per_plugin(pm: pluggy.PluginManager) -> list[Any]:
    """``tilekit_catalogue_records`` of each plugin, in pluggy's call order, through the
    on-disk cache of tilekit.recordcache (a plugin module's records are computed once per
    version of its sources and data, not once per new catalogue)."""
    caller = pm.hook.tilekit_catalogue_records
    impls = caller.get_hookimpls()
    if any(getattr(impl, "hookwrapper", False) or getattr(impl, "wrapper", False) for impl in impls):
        return caller()
    return [cached_records(impl.plugin_name, impl.plugin, lambda f=impl.function: list(f() or ()), CatalogueRecord)
            for impl in reversed(impls)]  # pluggy calls the last registered first


def catalogue_records(pm: pluggy.PluginManager | None = None) -> list[CatalogueRecord]:
    """Every record the plugins ship, in registration order, with the properties that
    ``tilekit_extra_properties`` hooks add (a record's own keys are never overwritten)."""
    pm = pm or get_plugin_manager()
    records = _flatten(_shipped_per_plugin(pm))
    if not pm.hook.tilekit_extra_properties.get_hookimpls():
        return records
    for record in records:
        for extra in pm.hook.tilekit_extra_properties(record=record):
            if not extra:
                continue
            if not isinstance(extra, Mapping):
                raise PluginError(f"tilekit_extra_properties returned {type(extra).__name__}, not a dict")
            for key, value in extra.items():
                record.properties.setdefault(key, value)
    return records


def public_name(name: str, pm: pluggy.PluginManager | None = None) -> Any:
    """The object a plugin adds to the ``tilekit`` package as ``name`` (``tilekit_public_names``),
    PluginError when two plugins offer it or none does."""
    pm = pm or get_plugin_manager()
    offers = [names[name] for names in pm.hook.tilekit_public_names() if names and name in names]
    if len(offers) > 1:
        raise PluginError(f"two plugins define the public name tilekit.{name}")
    if not offers:
        raise PluginError(f"no loaded plugin offers tilekit.{name} (is the plugin that provides it installed, "
                          "and not left out by TILEKIT_PLUGINS?)")
    return offers[0]


def family_for_file(path: str, pm: pluggy.PluginManager | None = None) -> str | None:
    """The family that claims the data file ``path`` (``tilekit_claim_file``), or None."""
    pm = pm or get_plugin_manager()
    return pm.hook.tilekit_claim_file(path=str(path))


def normalise(key: str, value: str, pm: pluggy.PluginManager | None = None) -> tuple[str, str]:
    """``(key, value)`` as stored: what a plugin's ``tilekit_normalise`` makes of a typed
    value (an equivalent symbol, vertex type, code ...), or the pair unchanged."""
    pm = pm or get_plugin_manager()
    found = pm.hook.tilekit_normalise(key=key, value=value)
    if found is None:
        return key, value
    if not (isinstance(found, tuple) and len(found) == 2 and all(isinstance(v, str) for v in found)):
        raise PluginError(f"tilekit_normalise({key!r}, {value[:40]!r}) returned {found!r}, not (key, value)")
    return found


@dataclass(frozen=True)
class WebRoute:
    """A page or endpoint a plugin adds to the web app (``tilekit_web_routes``): a Starlette
    path (``/editor/{name:str}``), ``view(request, web)``, the HTTP methods it answers and, for
    an ``/api/`` endpoint, a line for the API's own page (``/api``)."""

    path: str
    view: Callable[..., Any]
    methods: tuple[str, ...] = ("GET",)
    doc: str = ""


def web_pages(module: str, menu: Sequence[tuple[str, str]] = ()) -> tuple[Callable[..., Any], ...]:
    """The four web hooks of a plugin whose pages live in ``module`` (a module with ``ROUTES``,
    ``tiling_links(name, tiling)``, ``STATIC`` and ``STATIC_DIR``), in the order
    (tilekit_web_routes, tilekit_web_menu_links, tilekit_web_tiling_links, tilekit_web_static).
    The page module (Starlette, the family's engine) is imported only when a web app is made,
    not when the plugin loads; ``menu`` are the plugin's (path, label) navigation links::

        (tilekit_web_routes, tilekit_web_menu_links, tilekit_web_tiling_links,
         tilekit_web_static) = web_pages("my_family.web", [("/mine", "my page")])
    """

    def pages() -> Any:
        return importlib.import_module(module)

    @hookspecs.hookimpl
    def tilekit_web_routes(web: Any) -> list[Any]:
        return list(pages().ROUTES)

    @hookspecs.hookimpl
    def tilekit_web_menu_links(web: Any) -> list[tuple[str, str]]:
        return list(menu)

    @hookspecs.hookimpl
    def tilekit_web_tiling_links(web: Any, name: str, tiling: Any) -> list[tuple[str, str]]:
        return pages().tiling_links(name, tiling)

    @hookspecs.hookimpl
    def tilekit_web_static() -> list[tuple[str, Any]]:
        return [(pages().STATIC, pages().STATIC_DIR)]

    return tilekit_web_routes, tilekit_web_menu_links, tilekit_web_tiling_links, tilekit_web_static


@dataclass(frozen=True)
class PluginInfo:
    """One loaded plugin: its registered name, where it came from, the hooks it implements."""

    name: str
    source: str
    hooks: tuple[str, ...]
    distribution: str | None = None

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.name, "source": self.source, "hooks": list(self.hooks), "distribution": self.distribution}


def plugin_info(pm: pluggy.PluginManager | None = None) -> list[PluginInfo]:
    """What ``tilekit plugins`` shows (like ``pytest --trace-config``): every registered plugin
    in registration order, the file (or object) it came from, its hooks, and the
    distribution (name==version) for plugins loaded from the ``tilekit`` entry points."""
    pm = pm or get_plugin_manager()
    dists = {id(plugin): f"{dist.project_name}=={dist.version}" for plugin, dist in pm.list_plugin_distinfo()}
    out = []
    for name, plugin in pm.list_name_plugin():
        if plugin is None:  # blocked
            continue
        source = getattr(plugin, "__file__", None) or f"{type(plugin).__module__}.{type(plugin).__qualname__}"
        hooks = tuple(sorted(caller.name for caller in (pm.get_hookcallers(plugin) or [])))
        out.append(PluginInfo(str(name), str(source), hooks, dists.get(id(plugin))))
    return out


def samplers(pm: pluggy.PluginManager | None = None) -> dict[str, Sampler]:
    """Every sampler the plugins contribute, by name (a clash is a PluginError)."""
    pm = pm or get_plugin_manager()
    return _by_name(pm.hook.tilekit_samplers(), Sampler, "tilekit_samplers", "sampler")


def searches(pm: pluggy.PluginManager | None = None) -> dict[str, Search]:
    """All registered searches by name."""
    pm = pm or get_plugin_manager()
    return _by_name(pm.hook.tilekit_searches(), Search, "tilekit_searches", "search")


def get_search(name: str, pm: pluggy.PluginManager | None = None) -> Search:
    found = searches(pm)
    try:
        return found[name]
    except KeyError:
        raise NotFoundError("search", name, found) from None


def result_tables(pm: pluggy.PluginManager | None = None) -> dict[str, ResultTable]:
    """Every plugin result table by table name."""
    pm = pm or get_plugin_manager()
    out: dict[str, ResultTable] = {}
    for rt in _flatten(pm.hook.tilekit_result_tables()):
        if not isinstance(rt, ResultTable):
            raise PluginError(f"tilekit_result_tables returned {type(rt).__name__}, not ResultTable")
        if rt.name in out:
            raise PluginError(f"two plugins define the result table {rt.name!r}")
        missing = [k for k in (*rt.key, *( [rt.name_column] if rt.name_column else [])) if k not in rt.table.c]
        if not rt.key or missing:
            raise PluginError(f"result table {rt.name!r}: key or name column {missing or '()'} is not a column")
        out[rt.name] = rt
    return out


def migration_locations(pm: pluggy.PluginManager | None = None) -> list[str]:
    pm = pm or get_plugin_manager()
    return [str(p) for p in _flatten(pm.hook.tilekit_migration_locations())]


def tiling_from_spec(family: str, spec: Mapping[str, Any]) -> Tiling:
    """Rebuild a tiling of ``family`` from its catalogue spec."""
    return get_family(family).from_spec(spec)
