"""The vertex-species search (§4.1, exercises 4.8–4.11) and the classification of sequences.

Every vertex type p1...pk (3 <= k <= 6) whose angles sum to 2π is tried with the shared
builder under the rule "every vertex has this type", out to a radius round a seed polygon
(the type's largest). A type whose search space is exhausted is *impossible*, with the
builder's reason (the radius at which every branch died); a type that reaches the radius is
then constructed as a periodic tiling (construct.py), which proves it *extends to a tiling*.

Sequences with angle sum below 2π are *spherical* (exercise 4.11) and above it
*hyperbolic*. For a spherical type, a vertex-transitive polyhedron would have
V = 4 / (2 - k + 2 Σ 1/p_i) vertices (Euler's formula with V·δ = 4π, δ the angle defect)
and V·m_p / p faces of each size p (m_p: how often p occurs); the type is named when it is
the vertex type of a Platonic or Archimedean solid, a prism (4^2.n) or an antiprism (3^3.n).
Non-Euclidean sequences are enumerated in a bounded range: 3 <= k <= 6, and 3 <= p_i <=
max_sides (default 12) for spherical ones, 3 <= p_i <= hyperbolic_max_sides (default 6) for
hyperbolic ones (there are 98,308 hyperbolic types with sides up to 12: too many to be useful)
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from fractions import Fraction
from typing import Any

from tilekit.errors import ParameterError
from tilekit.plugins import CatalogueRecord, ChunkResult, Search, SearchParam
from tilekit.plugins.archimedean import construct
from tilekit.plugins.archimedean import records as rec
from tilekit.plugins.archimedean.tables import row_of
from tilekit.regular.notation import (
    VertexType,
    bounded_species,
    euclidean_species,
    geometry_of,
    types_of_species,
)

#: Vertex types of the Platonic and Archimedean solids (Cromwell, *Polyhedra*, 1997, ch. 2
#: and 5; Grünbaum & Shephard, *Tilings and Patterns*, §2.1) with their published vertex
#: counts, which tests compare with the count Euler's formula gives.
SOLIDS: dict[str, tuple[str, str, int]] = {
    "3^3": ("tetrahedron", "platonic", 4),
    "3^4": ("octahedron", "platonic", 6),
    "3^5": ("icosahedron", "platonic", 12),
    "4^3": ("cube", "platonic", 8),
    "5^3": ("dodecahedron", "platonic", 20),
    "3.6^2": ("truncated tetrahedron", "archimedean", 12),
    "3.8^2": ("truncated cube", "archimedean", 24),
    "3.10^2": ("truncated dodecahedron", "archimedean", 60),
    "4.6^2": ("truncated octahedron", "archimedean", 24),
    "5.6^2": ("truncated icosahedron", "archimedean", 60),
    "3.4.3.4": ("cuboctahedron", "archimedean", 12),
    "3.5.3.5": ("icosidodecahedron", "archimedean", 30),
    "3.4^3": ("rhombicuboctahedron", "archimedean", 24),
    "3.4.5.4": ("rhombicosidodecahedron", "archimedean", 60),
    "4.6.8": ("truncated cuboctahedron", "archimedean", 48),
    "4.6.10": ("truncated icosidodecahedron", "archimedean", 120),
    "3^4.4": ("snub cube", "archimedean", 24),
    "3^4.5": ("snub dodecahedron", "archimedean", 60),
}

DEFAULTS = {"radius": 4.0, "max_nodes": 200_000, "max_sides": 12, "hyperbolic_max_sides": 6}


def spherical_vertices(vt: VertexType) -> Fraction:
    """V = 4 / (2 - k + 2 Σ 1/p): the vertex count of a vertex-transitive polyhedron of type vt."""
    defect = 2 - len(vt.polygons) + 2 * sum((Fraction(1, p) for p in vt.polygons), Fraction(0))
    if defect <= 0:
        raise ParameterError(f"vertex type {vt} is not spherical (angle sum >= 2π)")
    return 4 / defect


def spherical_solid(vt: VertexType) -> tuple[str, str] | None:
    """(name, class) of the solid with this vertex type: Platonic, Archimedean, prism, antiprism."""
    name = str(vt)
    if name in SOLIDS:
        return SOLIDS[name][0], SOLIDS[name][1]
    polys = vt.polygons
    if len(polys) == 3 and polys.count(4) >= 2:
        n = next((q for q in polys if q != 4), 4)
        return f"{n}-gonal prism", "prism"
    if len(polys) == 4 and polys.count(3) >= 3:
        n = next((q for q in polys if q != 3), 3)
        return f"{n}-gonal antiprism", "antiprism"
    return None


def classify_sequence(vt: VertexType) -> dict[str, Any]:
    """Properties of a non-Euclidean vertex type (geometry, angle sum, spherical data)."""
    props: dict[str, Any] = {
        "geometry": vt.geometry,
        "angle_sum": _angle_text(vt),
        "angle_excess": float(vt.excess),
    }
    if vt.geometry == "spherical":
        v = spherical_vertices(vt)
        faces = {p: v * vt.polygons.count(p) / p for p in vt.sizes}
        props["euler_vertices"] = float(v)
        props["euler_feasible"] = v.denominator == 1 and all(f.denominator == 1 for f in faces.values())
        solid = spherical_solid(vt)
        props["status"] = "polyhedron" if solid else "no uniform polyhedron"
        if solid:
            props["solid"], props["solid_class"] = solid
    else:
        props["status"] = "hyperbolic"
    return props


def _angle_text(vt: VertexType) -> str:
    e = vt.excess
    return "2π" if e == 0 else ("<2π" if e < 0 else ">2π")


def _base_properties(vt: VertexType) -> dict[str, Any]:
    return {
        "kind": "vertex type",
        "vertex_type": str(vt),
        "species": vt.species_name,
        "polygons": list(vt.sizes),
        "valence": len(vt.polygons),
    }


def classify_euclidean(vt: VertexType, radius: float, max_nodes: int) -> dict[str, Any]:
    """Try to extend type vt with the builder; construct it when it survives."""
    started = time.perf_counter()
    r = construct.seed_radius(vt) + radius
    res = construct.grow(vt, r, max_nodes=max_nodes)
    out: dict[str, Any] = {
        "geometry": "euclidean",
        "angle_sum": "2π",
        "angle_excess": 0.0,
        "search_radius": round(r, 6),
        "nodes": res.stats.nodes,
        "backtracks": res.stats.backtracks,
        "reached_radius": round(res.stats.max_radius, 6),
    }
    if res.stats.rejections:
        # the local contradictions that killed branches, most frequent first
        out["contradictions"] = "; ".join(
            f"{why}: {n}" for why, n in sorted(res.stats.rejections.items(), key=lambda kv: (-kv[1], kv[0]))
        )
    if res.status == "exhausted":
        out["status"] = "impossible"
        out["reason"] = res.stats.reason
    elif res.status == "limit":
        out["status"] = "undecided"
        out["reason"] = res.stats.reason
    else:
        tiling = construct.archimedean_tiling(vt, rebuild=False)
        out["status"] = "tiles"
        out["reason"] = (
            f"extends to the radius {r:.3g} and is periodic: a translational unit of "
            f"{len(tiling.unit_prototile)} tiles repeats by v1={_vec(tiling.v1)}, v2={_vec(tiling.v2)}"
        )
        out["tiles_per_unit"] = int(len(tiling.unit_prototile))
    out["seconds"] = round(time.perf_counter() - started, 4)
    return out


def _vec(v) -> str:
    return "(" + ", ".join(f"{float(x):.4g}" for x in v) + ")"


# --------------------------------------------------------------------------- the Search


def _params(params: Mapping[str, Any]) -> dict[str, Any]:
    """Defaults filled in and every value checked against the declared ranges (the same
    check :func:`tilekit.search.validate_params` makes before a run is created)."""
    p = dict(DEFAULTS)
    p.update({k: v for k, v in params.items() if v is not None})
    for decl in SEARCH.params:
        value = float(p[decl.name])
        if not decl.min <= value <= decl.max:
            raise ParameterError(f"{decl.name}={p[decl.name]} must be between {decl.min:g} and {decl.max:g}")
    return p


def chunks(params: Mapping[str, Any]) -> list[dict[str, Any]]:
    """One chunk per Euclidean species (its types), then one per valence k for the bounded
    spherical / hyperbolic sequences."""
    p = _params(params)
    out: list[dict[str, Any]] = [
        {"geometry": "euclidean", "species": list(s)} for s in euclidean_species()
    ]
    for k in range(3, 7):
        out.append({"geometry": "non-euclidean", "k": k, "max_sides": int(p["max_sides"]),
                    "hyperbolic_max_sides": int(p["hyperbolic_max_sides"])})
    return out


def run_chunk(params: Mapping[str, Any], chunk: Mapping[str, Any]) -> ChunkResult:
    """Classify the vertex types of one chunk: a ``vertex_species`` row per type, a
    catalogue tiling for each type that tiles, the survivors as JSON results, and counts."""

    p = _params(params)
    found: list[dict[str, Any]] = []
    records: list[CatalogueRecord] = []
    counts: dict[str, int] = {}
    if chunk["geometry"] == "euclidean":
        species = tuple(int(x) for x in chunk["species"])
        types = types_of_species(species)
        classified = []
        for vt in types:
            props = _base_properties(vt)
            props["types_in_species"] = len(types)
            props.update(classify_euclidean(vt, float(p["radius"]), int(p["max_nodes"])))
            classified.append((vt, props))
        # a species tiles when one of its types does (exercise 4.10)
        species_tiles = any(props["status"] == "tiles" for _, props in classified)
        counts["euclidean_species"] = 1
        counts["tiling_species"] = int(species_tiles)
        for vt, props in classified:
            props["species_tiles"] = species_tiles
            found.append(props)
            if props["status"] == "tiles":
                records.extend(rec.vertex_type_records(vt, props))
    else:
        k = int(chunk["k"])
        for species in bounded_species(int(chunk["max_sides"]), k, k):
            geometry = geometry_of(species)
            if geometry == "euclidean":
                continue
            if geometry == "hyperbolic" and species[-1] > int(chunk["hyperbolic_max_sides"]):
                continue
            types = types_of_species(species)
            for vt in types:
                props = _base_properties(vt)
                props["types_in_species"] = len(types)
                props.update(classify_sequence(vt))
                found.append(props)
    for props in found:
        geometry, status = props["geometry"], props.get("status")
        if geometry == "euclidean":
            counts["euclidean_types"] = counts.get("euclidean_types", 0) + 1
            key = {"tiles": "tiling_types", "impossible": "impossible_types"}.get(status, "undecided_types")
            counts[key] = counts.get(key, 0) + 1
        elif geometry == "spherical":
            counts["spherical_types"] = counts.get("spherical_types", 0) + 1
            counts["polyhedra"] = counts.get("polyhedra", 0) + int(status == "polyhedron")
        else:
            counts["hyperbolic_types"] = counts.get("hyperbolic_types", 0) + 1
    survivors = [{"vertex_type": r["vertex_type"], "species": r["species"]}
                 for r in found if r.get("status") == "tiles"]
    return ChunkResult(results=survivors, records=records,
                       rows={"vertex_species": [row_of(r) for r in found]}, counts=counts)


#: the counts every summary has, zero when no chunk reported them
_COUNT_KEYS = ("euclidean_types", "euclidean_species", "tiling_species", "tiling_types",
               "impossible_types", "undecided_types", "spherical_types", "polyhedra", "hyperbolic_types")


def summarize(params: Mapping[str, Any], results: list[dict[str, Any]]) -> dict[str, Any]:
    """The survivors (the JSON results); the tallies come from the chunks' summed counts."""
    return {**dict.fromkeys(_COUNT_KEYS, 0), "survivors": sorted(r["vertex_type"] for r in results)}


SEARCH = Search(
    name="vertex-species",
    summary="Enumerate vertex types p1...pk and classify each: tiles the plane, impossible, spherical or hyperbolic",
    family="archimedean",
    params=(
        SearchParam("radius", float, DEFAULTS["radius"],
                    "edge lengths beyond the seed polygon that a type must extend to", min=0.5, max=12.0),
        SearchParam("max_nodes", int, DEFAULTS["max_nodes"], "builder node limit per vertex type",
                    min=1, max=10_000_000),
        SearchParam("max_sides", int, DEFAULTS["max_sides"],
                    "largest polygon in the bounded spherical enumeration", min=3, max=24),
        SearchParam("hyperbolic_max_sides", int, DEFAULTS["hyperbolic_max_sides"],
                    "largest polygon in the bounded hyperbolic enumeration", min=3, max=10),
    ),
    chunks=chunks,
    run_chunk=run_chunk,
    summarize=summarize,
)
