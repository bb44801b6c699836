"""The library calls behind every ``tilekit`` command and the web API (docs/api.md).

In the manner of sqlite-utils: the command line parses options, makes one call here and prints
what it returns; the web server's API and pages make the same calls. Tilings: ``resolve_tiling``
(a catalogue name or a data file), ``configure`` (options -> ``Tiling.configure``),
``render_svg`` (bounded: estimate, refuse over the limit, patch, draw), ``render_file`` (a
picture or an export written to a file, streamed when it cannot fit in memory),
``write_prototile`` (one tile). Records: ``query``, ``record``, ``family_summary``, ``keys``.
Runs: ``start_run``, ``run_report``, ``run_data``.

Heavy libraries (NumPy, shapely, SQLAlchemy) are imported inside the calls that need them, so
that importing this module costs a command nothing (start-up cost: tests/test_startup.py).
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from tilekit import limits
from tilekit.cli_types import geometry_option
from tilekit.errors import ParameterError, TilekitError
from tilekit.plugins import families, family_for_file, get_family
from tilekit.text import parse_region

#: A catalogue, or a function that opens one (called only when a call needs the catalogue:
#: a tiling from a data file needs none).
CatalogueLike = Any

def _opened(catalogue: CatalogueLike) -> Any:
    return catalogue() if callable(catalogue) and not hasattr(catalogue, "tiling") else catalogue


# --------------------------------------------------------------------------- tilings


def resolve_tiling(catalogue: CatalogueLike, name: str | None = None, *, system: str | None = None,
                   family: str | None = None, pm: Any = None) -> Any:
    """The tiling called ``name`` in the catalogue, or the one a data file ``system`` describes
    (read by ``family``, default the family that claims the file by its suffix through
    ``tilekit_claim_file``). Exactly one of ``name`` and ``system``; one-line errors otherwise."""
    if system is None:
        if name is None:
            raise ParameterError("render needs a tiling NAME (see tilekit list) or --system FILE")
        if family is not None:
            raise ParameterError("--family only goes with --system FILE")
        return _opened(catalogue).tiling(name)
    if name is not None:
        raise ParameterError(f"give either a tiling NAME ({name!r}) or --system FILE, not both")
    claimed = family or family_for_file(system, pm)
    if claimed is None:
        import os

        readers = sorted(n for n, f in families(pm).items() if f.from_file is not None)
        raise ParameterError(
            f"no installed family claims the file {os.path.basename(system)!r}; name one with --family "
            f"(families that read files: {', '.join(readers) or 'none'})"
        )
    fam = get_family(claimed, pm)
    if fam.from_file is None:
        raise ParameterError(f"family {fam.name!r} cannot read data files; --system needs a family that can")
    return fam.from_file(system)


def configure(tiling: Any, options: Mapping[str, Any] | None = None, *, geometry: str | None = None) -> Any:
    """``tiling`` configured by ``options`` (``params``, ``edges``, ``depth``, ``tiling`` and a
    family's own keys; a nested ``settings`` mapping is merged in, as the web API sends it) and
    the surface ``geometry`` (sphere, plane, hyperbolic: checked against the tiling's kind).
    The tiling itself when nothing is asked; the family checks its options."""
    conf = {k: v for k, v in (options or {}).items() if k != "settings"}
    conf.update((options or {}).get("settings") or {})
    conf.update(geometry_option(tiling, geometry))
    return tiling.configure(**conf) if conf else tiling


def tiling_region(tiling: Any, region: Any = None) -> tuple[Any, Any]:
    """(the region to estimate with, the region to draw): ``region`` as ``x0,y0,x1,y1`` text, a
    box or a shapely geometry; None estimates the tiling's own and draws its default region."""
    from tilekit.geometry import as_region  # start-up cost: shapely

    if region is None:
        return None, tiling.default_region()
    box = as_region(parse_region(region) if isinstance(region, str) else region)
    return box, box


def translation_vectors(tiling: Any, bounds: Sequence[float]) -> tuple[Any, Any, Any]:
    """(origin, v1, v2) of a periodic tiling's translation vectors, anchored at the lattice point
    nearest the middle of ``bounds`` (what ``--vectors`` draws); ParameterError otherwise."""
    import numpy as np  # start-up cost: NumPy

    v1, v2 = getattr(tiling, "v1", None), getattr(tiling, "v2", None)
    if v1 is None or v2 is None:
        raise ParameterError(f"--vectors needs a periodic tiling; {tiling.name or 'this tiling'} has no translation vectors")
    basis = np.column_stack([v1, v2])
    centre = np.array([(bounds[0] + bounds[2]) / 2, (bounds[1] + bounds[3]) / 2])
    origin = basis @ np.round(np.linalg.solve(basis, centre))
    return origin, np.asarray(v1, dtype=float), np.asarray(v2, dtype=float)


class Progress:
    """What a long render tells its caller; this one says nothing. The command line's version
    prints lines and a progress bar on a terminal (tilekit/cli/render.py)."""

    def making(self, estimate: float) -> None:
        """About to make a patch of about ``estimate`` tiles."""

    def drawing(self, tiles: int) -> None:
        """About to draw a picture of ``tiles`` tiles."""

    @contextlib.contextmanager
    def streaming(self, estimate: float) -> Iterator[Callable[[int], None]]:
        """Around a streamed export: yields a function told the tiles of each chunk written."""
        yield lambda tiles: None


def _refuse_tiles(count: float, limit: int, name: str) -> None:
    limits.refuse_over("tiles", count, limit, "--max-tiles")


@dataclass
class Picture:
    """An SVG drawn by :func:`render_svg`: its text, the tiles drawn, the estimate checked
    first, and the region drawn."""

    svg: str
    tiles: int
    estimate: int
    region: Any = field(repr=False, default=None)


def render_svg(tiling: Any, region: Any = None, *, max_tiles: int = limits.MAX_TILES,
               too_large: Callable[[float, int, str], None] | None = None, estimate: float | None = None,
               progress: Progress | None = None, vectors: bool = False, strict_labels: bool = False,
               **svg_options: Any) -> Picture:
    """SVG text of ``tiling`` over ``region`` (default: its own), bounded: the estimate
    (``Tiling.estimate_tiles``) is checked against ``max_tiles`` before anything is made, and
    the patch's true count again after; ``too_large(count, limit, name)`` raises the refusal
    (default: a LimitError naming ``--max-tiles``; the web server's is HTTP 413). Drawn by the
    family's ``Tiling.render_svg`` with ``svg_options`` (palette, labels, size, width, height,
    stroke ...); ``vectors`` adds the translation vectors; ``strict_labels`` refuses labels on
    tiles that carry none."""
    import math

    refuse = too_large or _refuse_tiles
    box, area = tiling_region(tiling, region)
    name = getattr(tiling, "name", "") or ""
    if estimate is None:
        estimate = float(tiling.estimate_tiles(box))
    estimate = int(estimate) if math.isfinite(estimate) and estimate < 2**62 else 2**62
    if estimate > max_tiles:
        refuse(estimate, max_tiles, name)
    progress = progress or Progress()
    progress.making(estimate)
    patch = tiling.patch(area)
    if len(patch) > max_tiles:  # the estimate was low: refuse all the same
        refuse(len(patch), max_tiles, name)
    if strict_labels and svg_options.get("labels") and not any(p.edge_labels is not None for p in patch.prototiles):
        raise ParameterError(
            f"--labels: the tiles of {name or 'this tiling'} carry no edge labels "
            "to draw (isohedral types and Wang sets do)"
        )
    progress.drawing(len(patch))
    drawn = dict(svg_options, region=area)
    if vectors:
        drawn["vectors"] = translation_vectors(tiling, area.bounds)
    svg = tiling.render_svg(patch, **drawn)
    return Picture(svg, len(patch), estimate, area)


@dataclass
class Written:
    """A file :func:`render_file` wrote: its path, the tiles in it, and the chunk size when it
    was streamed (None when the patch was made whole)."""

    path: str
    tiles: int
    chunk: int | None = None


_PICTURE_ONLY = ("--width", "--height", "--stroke-width", "--labels", "--vectors")


def render_file(tiling: Any, out: str, region: Any = None, *, max_tiles: int = limits.MAX_TILES,
                palette: Any = None, stroke: str = "#222", stroke_width: float | None = None,
                width: int | None = None, height: int | None = None, dpi: float = 96.0, labels: bool = False,
                vectors: bool = False, layers: str | None = None, mm_per_unit: float | None = None,
                progress: Progress | None = None) -> Written:
    """Write ``tiling`` over ``region`` to ``out``, the suffix choosing: .svg / .png (a picture),
    .geojson / .json / .csv (tiles and neighbours), .cut.svg / .dxf (edges for cutters). Bounded
    like :func:`render_svg` (``max_tiles``, memory, free disk space), and streamed chunk by chunk
    (``Tiling.iter_patches``) when the family streams and the patch cannot fit in memory.
    ``palette`` and ``stroke`` are colour text or lists; a bad one fails before any work."""
    from tilekit.export import (  # start-up cost: NumPy, shapely
        STREAM_FORMATS,
        check_disk_space,
        check_export_size,
        export_fits_in_memory,
        outline_vertices,
        write_patch,
    )
    from tilekit.render import parse_palette, write_svg  # start-up cost: NumPy

    fmt = check_render_options(out, layers=layers, mm_per_unit=mm_per_unit, width=width, height=height,
                               stroke_width=stroke_width, labels=labels, vectors=vectors)
    palette = parse_palette(palette)
    parse_palette(stroke)
    progress = progress or Progress()
    box, area = tiling_region(tiling, region)
    estimate = tiling.estimate_tiles(box)
    check_export_size(estimate, fmt, max_tiles, memory=False)
    vertices = outline_vertices(tiling.prototiles)
    if not export_fits_in_memory(estimate, fmt, vertices, tiling.bytes_per_tile):
        if not (tiling.streams and fmt in STREAM_FORMATS and not labels):
            # the one-line refusal: this cannot stream
            check_export_size(estimate, fmt, max_tiles, vertices=vertices, making=tiling.bytes_per_tile)
        check_disk_space(out, estimate, fmt, tiling.prototiles)
        return _render_stream(tiling, area, out, fmt, estimate, progress, vertices, palette=palette, stroke=stroke,
                              stroke_width=stroke_width, width=width, height=height, vectors=vectors)
    check_disk_space(out, estimate, fmt, tiling.prototiles)
    if fmt in (".svg", ".png"):
        drawn: dict[str, Any] = {"palette": palette, "labels": labels, "stroke": stroke, "width": width,
                                 "height": height}
        if stroke_width is not None:
            drawn["stroke_width_px"] = stroke_width
        picture = render_svg(tiling, area, max_tiles=max_tiles, estimate=estimate, vectors=vectors,
                             strict_labels=True, progress=progress, **drawn)
        return Written(str(write_svg(picture.svg, out, dpi)), picture.tiles)
    progress.making(estimate)
    patch = tiling.patch(area)
    classes = _tile_classes(tiling, patch) if fmt in (".geojson", ".json") else None
    names = tiling.tile_labels(patch, area) if fmt in (".json", ".csv") else None
    # --stroke's default is the picture's outline colour; cut lines are red unless it is given
    write_patch(patch, out, classes=classes, layers=layers or "one", mm_per_unit=mm_per_unit or 10.0,
                palette=palette, stroke=stroke if stroke != "#222" else None, labels=names)
    return Written(out, len(patch))


def render(catalogue: CatalogueLike, out: str, name: str | None = None, *, system: str | None = None,
           family: str | None = None, pm: Any = None, options: Mapping[str, Any] | None = None,
           geometry: str | None = None, **file_options: Any) -> Written:
    """``tilekit render``: the output checked first (:func:`check_render_options`), then the
    tiling resolved (:func:`resolve_tiling`: ``name`` from ``catalogue``, or the data file
    ``system``), configured (:func:`configure`) and written (:func:`render_file`, whose keyword
    options ``file_options`` are)."""
    check_render_options(out, **{k: file_options.get(k) for k in _OPTION_KEYS})
    tiling = configure(resolve_tiling(catalogue, name, system=system, family=family, pm=pm), options,
                       geometry=geometry)
    return render_file(tiling, out, **file_options)


_OPTION_KEYS = ("layers", "mm_per_unit", "width", "height", "stroke_width", "labels", "vectors")


def check_render_options(out: str, **given: Any) -> str:
    """The output format of ``out`` (an unknown suffix is refused naming the valid ones), after
    checking that each option ``given`` (layers, mm_per_unit: cut files; width, height,
    stroke_width, labels, vectors: pictures) applies to it."""
    from tilekit.export import output_format  # start-up cost: NumPy

    fmt = output_format(out)
    picture = fmt in (".svg", ".png")
    cut = fmt in (".cut.svg", ".dxf")
    for key, value in given.items():
        flag = "--" + key.replace("_", "-")
        if value is None or value is False:
            continue
        if (flag in _PICTURE_ONLY and not picture) or (flag not in _PICTURE_ONLY and not cut):
            kinds = ".svg and .png" if flag in _PICTURE_ONLY else ".cut.svg and .dxf"
            raise ParameterError(f"{flag} applies to {kinds} output, not {fmt}")
    if given.get("width") is not None and given.get("height") is not None:
        raise ParameterError("give --width or --height, not both (the other follows the region's shape)")
    return fmt


def _render_stream(tiling: Any, area: Any, out: str, fmt: str, estimate: float, progress: Progress,
                   vertices: int, *, vectors: bool, **svg: Any) -> Written:
    """A patch larger than memory written chunk by chunk (``Tiling.iter_patches``, chunks as
    large as half the memory the export may take allows): GeoJSON features or SVG paths."""
    from tilekit.export import stream_chunk_tiles, write_patches  # start-up cost: NumPy

    chunk = stream_chunk_tiles(fmt, vertices)
    options: dict[str, Any] = {}
    if fmt == ".svg":
        options = {k: svg[k] for k in ("palette", "stroke", "width", "height")}
        options["region"] = area
        if svg.get("stroke_width") is not None:
            options["stroke_width_px"] = svg["stroke_width"]
        if vectors:
            options["vectors"] = translation_vectors(tiling, area.bounds)
    with progress.streaming(estimate) as advance:
        def told(patches: Iterator[Any]) -> Iterator[Any]:
            for p in patches:
                advance(len(p))
                yield p

        count = write_patches(told(tiling.iter_patches(area, chunk_tiles=chunk)), out, **options)
    return Written(out, count, chunk)


def _tile_classes(tiling: Any, patch: Any) -> Any:
    """Each tile's transitivity class for a periodic tiling whose aspects tell it, else None."""
    from tilekit.symmetry.orbits import patch_tile_classes  # start-up cost: NumPy, shapely
    from tilekit.tiling import PeriodicTiling  # start-up cost: NumPy, shapely

    if not isinstance(tiling, PeriodicTiling):
        return None
    try:
        return patch_tile_classes(tiling, patch)
    except TilekitError:  # a unit the symmetry search cannot analyse: the classes are unknown
        return None


def prototile_patch(tiling: Any, index: int) -> Any:
    """A patch of one tile: prototile ``index`` of ``tiling`` at the origin, unmoved (its
    outline with any shaped edges, its marking), or a ParameterError naming the valid range."""
    import numpy as np  # start-up cost: NumPy

    from tilekit.tiling import Patch  # start-up cost: NumPy, shapely

    protos = tiling.prototiles
    if not 0 <= index < len(protos):
        names = ", ".join(f"{i}: {p.name or '-'}" for i, p in enumerate(protos[:12]))
        raise ParameterError(f"--index {index}: {tiling.name or 'the tiling'} has {len(protos)} prototile"
                             f"{'s' if len(protos) != 1 else ''} (--index 0..{len(protos) - 1}; {names})")
    return Patch([protos[index]], np.zeros(1, dtype=np.int64), np.eye(3)[None])


@dataclass
class WrittenPrototile:
    """A prototile :func:`write_prototile` wrote: the file, which of how many prototiles, its
    name, its number of sides (tiling vertices on its outline) and its area."""

    path: str
    index: int
    of: int
    name: str
    sides: int
    area: float


def write_prototile(catalogue: CatalogueLike, name: str, out: str, index: int = 0,
                    options: Mapping[str, Any] | None = None, *, mm_per_unit: float = 10.0) -> WrittenPrototile:
    """``tilekit prototile``: prototile ``index`` of the catalogue tiling ``name`` (configured by
    ``options``, as :func:`configure`) written to ``out`` at the origin in the tiling's units: a
    picture (.svg, .png), its polygon (.geojson, .json) or its outline for a cutter (.dxf,
    .cut.svg, ``mm_per_unit``). The suffix is checked before any work."""
    from tilekit.export import output_format, write_patch  # start-up cost: NumPy, shapely
    from tilekit.polygon import area, corner_count  # start-up cost: NumPy
    from tilekit.render import write_image  # start-up cost: NumPy

    fmt = output_format(out)
    if fmt == ".csv":
        raise ParameterError("a prototile has no tile table: write .svg, .png, .geojson, .json, .dxf or .cut.svg")
    tiling = configure(_opened(catalogue).tiling(name), options)
    patch = prototile_patch(tiling, index)
    proto = patch.prototiles[0]
    if fmt in (".svg", ".png"):
        write_image(patch, out)
    else:
        write_patch(patch, out, mm_per_unit=mm_per_unit)
    return WrittenPrototile(out, index, len(tiling.prototiles), proto.name or "",
                            int(corner_count(proto.outline, proto.corners)), float(area(proto.outline)))


# --------------------------------------------------------------------------- records


@dataclass
class Matches:
    """The tilings a :func:`query` matches: iterate for the entries (streamed, in order, paged by
    ``limit`` / ``offset``), :meth:`count` for how many match in all (ignoring the page)."""

    catalogue: Any
    family: str | None = None
    where: list[str] = field(default_factory=list)
    text: str | None = None
    order_by: str = "name"
    limit: int | None = None
    offset: int = 0

    def __iter__(self) -> Iterator[Any]:
        return iter(self.catalogue.iter_query(family=self.family, where=self.where, text=self.text,
                                              order_by=self.order_by, limit=self.limit, offset=self.offset))

    def count(self) -> int:
        """How many tilings match the filters, whatever the page."""
        return int(self.catalogue.count_matching(family=self.family, where=self.where, text=self.text))

    def csv_keys(self) -> list[str] | None:
        """The columns of a CSV of these entries: a result table's own, None for catalogue tilings."""
        if self.catalogue.family_table(self.family) is None:
            return None
        return list(self.catalogue._export_keys(self.family))


def query(catalogue: Any, family: str | None = None, where: Sequence[str] = (), text: str | None = None,
          order_by: str = "name", limit: int | None = None, offset: int = 0) -> Matches:
    """The catalogue's tilings (or a result table's rows, for a family that has one) matching
    every filter of ``where`` (``KEY=V``, ``KEY>=N``, ``KEY~TEXT`` ...: docs/catalogue.md) and
    ``text``; an unknown family is a NotFoundError naming the close ones, a bad filter a
    ParseError, both raised here, before any row is read."""
    catalogue.check_family(family)
    return Matches(catalogue, family, list(where), text, order_by, limit, offset)


@dataclass
class Record:
    """What :func:`record` knows of one tiling: its catalogue ``entry``, the ``tiling`` rebuilt
    from its spec (None without geometry, ``error`` then says why), and ``installed``: whether a
    plugin that draws its family is loaded."""

    entry: Any
    tiling: Any = None
    error: str | None = None
    installed: bool = True

    def description(self) -> str:
        """The family's description of the tiling (``Tiling.describe``), '' without geometry."""
        return (self.tiling.describe() or "") if self.tiling is not None else ""

    def computed_group(self) -> Any:
        """The wallpaper group computed from the geometry when the record does not state one and
        the tiling is periodic (a WallpaperGroup), else None."""
        from tilekit.tiling import PeriodicTiling  # start-up cost: NumPy, shapely

        props = self.entry.properties
        if "wallpaper_group" in props or "symmetry_group" in props or not isinstance(self.tiling, PeriodicTiling):
            return None
        from tilekit.symmetry import wallpaper_group  # start-up cost: NumPy, shapely

        return wallpaper_group(self.tiling)


def record(catalogue: Any, name: str, *, pm: Any = None, build: Callable[[Any], Any] | None = None,
           get: Callable[[str], Any] | None = None) -> Record:
    """The record called ``name`` (a name or an alias; NotFoundError suggesting close names),
    found by ``get(name)`` (default ``catalogue.get``; the web server looks up result rows by
    their own name first), with its tiling built by ``build(entry)`` (default
    ``catalogue.tiling``; the web server passes its cache). A record without geometry is no
    error: :attr:`Record.error` says why."""
    entry = (get or catalogue.get)(name)
    if entry.family not in families(pm or catalogue.pm) and catalogue.family_table(entry.family) is None:
        return Record(entry, error=f"family {entry.family!r} is not installed: no geometry", installed=False)
    try:
        return Record(entry, (build or catalogue.tiling)(entry))
    except TilekitError as exc:  # a record without geometry, e.g. a vertex type that cannot tile
        return Record(entry, error=str(exc))


@dataclass
class FamilySummary:
    """A family as ``tilekit show FAMILY`` shows it: the Family, how many tilings it has, one of
    them, and the options ``tilekit render`` takes for it (``Tiling.options_help``)."""

    family: Any
    tilings: int
    example: str | None = None
    options_help: str = ""


def family_summary(catalogue: Any, name: str, *, pm: Any = None) -> FamilySummary | None:
    """The family ``name`` when it is one and no tiling is called so, else None."""
    fams = families(pm or catalogue.pm)
    if name not in fams or catalogue.query(where=[f"name={name}"]):
        return None
    sample = catalogue.query(family=name, limit=1)
    text = ""
    if sample:
        try:
            text = catalogue.tiling(sample[0].name).options_help()
        except TilekitError:
            text = ""
    return FamilySummary(fams[name], catalogue.count(name), sample[0].name if sample else None, text)


def keys(catalogue: Any, family: str | None = None) -> list[Any]:
    """Every key ``--where`` filters on (KeyInfo: type, families, how many tilings, an example,
    older names): the text columns and the shared vocabulary first, then the families' own;
    for a family with a result table, its columns."""
    # start-up cost: the catalogue package is imported by the commands that read it
    from tilekit.catalogue.entry import TEXT_COLUMNS
    from tilekit.catalogue.vocabulary import KeyInfo

    catalogue.check_family(family)
    rt = catalogue.family_table(family)
    if rt is not None:
        return _result_table_keys(catalogue, rt, family or "")
    infos = catalogue.key_table(family)
    everyone = tuple(sorted({f for info in infos for f in info.families}))
    first = catalogue.query(family=family, limit=1)
    if not first:
        return infos
    total = catalogue.count(family)
    shown = {"name": first[0].name, "family": first[0].family, "title": (first[0].title.split() or ["a"])[0].lower()}
    return [KeyInfo(key=c, type="text", families=everyone, tilings=total,
                    example=f"{c}{'~' if c == 'title' else '='}{shown[c]}") for c in TEXT_COLUMNS] + infos


def _result_table_keys(catalogue: Any, rt: Any, family: str) -> list[Any]:
    """KeyInfos for the columns of a result table (what ``--where`` filters on for its family)."""
    from tilekit.catalogue.results import column_kind  # start-up cost: SQLAlchemy
    from tilekit.catalogue.vocabulary import KeyInfo  # start-up cost: the catalogue package

    rows = catalogue.count_result_rows(rt)
    examples = {"bool": "{}=true", "int": "{}>=1", "float": "{}>=0.5", "json": "{}~TEXT", "text": "{}=TEXT"}
    return [KeyInfo(key=column.name, type=column_kind(column.type), families=(family,), tilings=rows,
                    example=examples.get(column_kind(column.type), "{}=VALUE").format(column.name))
            for column in rt.table.c]


# --------------------------------------------------------------------------- runs


def start_run(catalogue: Any, kind: str, params: Mapping[str, Any] | None = None, *, executor: str = "local",
              workers: int | None = None, resume: int | None = None, scheduler: str | None = None,
              progress: Callable[[int, int], None] | None = None, on_run: Callable[[int], None] | None = None,
              pm: Any = None) -> Any:
    """Run the search ``kind`` (a registered Search) with ``params`` to the end, or continue run
    ``resume`` with its stored parameters, and return its RunInfo. ``progress(done, total)`` is
    told the chunks; ``on_run(run_id)`` the run's id as soon as it exists (so an interrupted
    run can be named). Ctrl-C or SIGTERM leave the run resumable (:func:`tilekit.search.run_search`)."""
    from tilekit.search import run_search  # start-up cost: NumPy, SQLAlchemy

    run_id = run_search(catalogue, kind, params, executor=executor, workers=workers, resume_run=resume,
                        progress=progress, pm=pm, on_run=on_run, scheduler=scheduler)
    return catalogue.run(run_id)


@dataclass
class RunReport:
    """One run in detail (``tilekit runs RUN_ID``, the web's run page): its RunInfo, the
    indices of chunks not done, the number of results, and the rates derived from them."""

    info: Any
    pending: list[int]
    results: int

    @property
    def chunk_rate(self) -> float | None:
        """Chunks a second of wall time, None before any chunk is done."""
        i = self.info
        return i.chunks_done / i.seconds if i.chunks_done and i.seconds > 0 else None

    @property
    def row_rate(self) -> float | None:
        """Result rows a second of wall time, None before any chunk is done."""
        i = self.info
        return i.rows / i.seconds if i.chunks_done and i.seconds > 0 else None

    @property
    def worker_seconds_left(self) -> tuple[float, float] | None:
        """(worker seconds per chunk, worker seconds left) of a running or interrupted run."""
        i = self.info
        if not (i.chunks_done and i.status in ("running", "interrupted") and i.worker_seconds > 0):
            return None
        per_chunk = i.worker_seconds / i.chunks_done
        return per_chunk, per_chunk * (i.chunks_total - i.chunks_done)


def run_report(catalogue: Any, run_id: int) -> RunReport:
    """Run ``run_id`` in detail; NotFoundError for an unknown run."""
    info = catalogue.run(run_id)
    pending = [int(c["index"]) for c in catalogue.run_chunks(info.id) if c["status"] != "done"]
    return RunReport(info, pending, sum(1 for _ in catalogue.iter_results(info.id)))


def run_data(catalogue: Any, run_id: int | None = None, *, results: bool = True) -> list[dict[str, Any]]:
    """Runs as plain JSON (``tilekit runs --format json``, ``/api/runs``): every run, or run
    ``run_id`` with its per-status counts and (``results``) its JSON results."""
    from tilekit.catalogue import run_json  # start-up cost: SQLAlchemy

    if run_id is None:
        return [run_json(i) for i in catalogue.runs()]
    item = run_json(catalogue.run(run_id))
    if results:
        item["results"] = catalogue.results(run_id)
    item["counts"] = catalogue.run_counts(run_id)
    return [item]
