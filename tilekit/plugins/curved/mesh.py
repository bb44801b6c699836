"""Printable meshes of a tiling of the sphere: one closed triangle mesh whose faces follow the
sphere, written as binary STL (what slicers read) or OBJ with one material per kind of tile
(the tiles as coloured regions).

Each tile is triangulated in its prototile's frame at the pole: ``rings`` rings between the
centre and the outline (its ``samples`` points per edge, placed symmetrically so neighbours
sample a shared edge at the same points), each ring's points pushed onto the sphere; the
tiles' shared boundary points are welded on a grid (a cluster of float-equal points is one
vertex), so the mesh is closed and every edge has exactly two triangles.

Relief (:func:`raise_tiles`): the tiles of chosen colour classes are lifted radially to
radius 1 + h, with vertical walls (in the planes through the centre and each boundary edge)
where a raised tile meets a lower one. Every boundary vertex gets one copy per sector of
equal-height tiles round it and one mid-height vertex on its wall line, so the mesh stays one
closed, consistently oriented surface (every edge in exactly two triangles) even where raised
tiles touch only at a corner, as on a 2-coloured octahedron.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from tilekit.errors import GeometryError, ParameterError, TilekitError
from tilekit.plugins.curved import model
from tilekit.plugins.curved.wythoff import weld

DEFAULT_RINGS = 4
MAX_RINGS = 32
#: Triangles refused past this (a slicer and the disk both have limits; a sphere's tiling
#: never needs more than a few 10^4).
MAX_TRIANGLES = 2_000_000
MESH_FORMATS = (".stl", ".obj")


def sphere_mesh(patch: Any, rings: int = DEFAULT_RINGS) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(vertices (V, 3) on the unit sphere, triangles (T, 3) counter-clockwise seen from
    outside, the tile each triangle belongs to (T,)) for a spherical ModelPatch."""
    if isinstance(rings, bool) or not isinstance(rings, int) or not 1 <= rings <= MAX_RINGS:
        raise ParameterError(f"rings must be an integer 1..{MAX_RINGS}, got {str(rings)[:20]}")
    if not len(patch) or patch.prototiles[0].sign <= 0:
        raise GeometryError("a sphere mesh needs a patch of a tiling of the sphere")
    pts_all, tris_all, owner_all = [], [], []
    base = 0
    sep = np.inf
    for _, idx, proto in patch.parts():
        outline = proto.points                                  # (k, 3) at the pole
        k = len(outline)
        pole = np.array([0.0, 0.0, 1.0])
        t = (np.arange(1, rings + 1) / rings)[:, None, None]
        ring = (1 - t) * pole + t * outline[None]               # (rings, k, 3)
        ring /= np.linalg.norm(ring, axis=-1, keepdims=True)
        local = np.concatenate([pole[None], ring.reshape(-1, 3)])  # centre, then ring by ring
        nxt = (np.arange(k) + 1) % k
        faces = [np.stack([np.zeros(k, dtype=np.int64), 1 + np.arange(k), 1 + nxt], axis=1)]
        for r in range(rings - 1):
            a, b = 1 + r * k + np.arange(k), 1 + r * k + nxt
            c, d = a + k, b + k
            faces += [np.stack([a, c, d], axis=1), np.stack([a, d, b], axis=1)]
        local_tris = np.concatenate(faces)
        edges = local[local_tris] - local[np.roll(local_tris, -1, axis=1)]
        sep = min(sep, float(np.linalg.norm(edges, axis=-1).min()))
        placed = model.apply(patch.transform[idx], local)       # (m, P, 3)
        m, p = placed.shape[:2]
        pts_all.append(placed.reshape(-1, 3))
        placed_tris = np.repeat(local_tris[None], m, axis=0)     # (m, t, 3)
        mirrored = np.linalg.det(patch.transform[idx]) < 0       # a reflection reverses the winding
        placed_tris[mirrored] = placed_tris[mirrored][..., ::-1]
        tris_all.append((placed_tris + base + p * np.arange(m)[:, None, None]).reshape(-1, 3))
        owner_all.append(np.repeat(idx, len(local_tris)))
        base += m * p
    pts = np.concatenate(pts_all)
    tris = np.concatenate(tris_all)
    _check_size(len(tris))
    vid = weld(pts, sep)
    used, new = np.unique(vid, return_inverse=True)
    return pts[used], new.reshape(-1)[tris], np.concatenate(owner_all)


def _check_size(triangles: int) -> None:
    if triangles > MAX_TRIANGLES:
        raise ParameterError(f"this mesh would have {triangles:,} triangles, over the limit of {MAX_TRIANGLES:,}: "
                             "use fewer rings (--rings) or samples (--set samples=N)")


def raise_tiles(vertices: np.ndarray, triangles: np.ndarray, owner: np.ndarray, raised: np.ndarray,
                height: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The closed mesh of :func:`sphere_mesh` with the tiles where ``raised`` (bool per tile) lifted
    to radius 1 + ``height``, and vertical walls where a raised tile meets a lower one; returns
    (vertices, triangles, owner) as sphere_mesh does (a wall belongs to its raised tile)."""
    nv = len(vertices)
    up = raised[owner]                                            # (T,) per triangle
    # half-edges a -> b of each triangle and the twin b -> a across it (the mesh is closed)
    a = triangles.reshape(-1)
    b = np.roll(triangles, -1, axis=1).reshape(-1)
    tri_of = np.repeat(np.arange(len(triangles)), 3)
    key = a * nv + b
    order = np.argsort(key)
    twin = order[np.searchsorted(key[order], b * nv + a)]
    # corners: one node per (tile, vertex); nodes of equal-height tiles across an edge are joined
    corner_key = np.concatenate([owner[tri_of] * nv + a, owner[tri_of] * nv + b])
    nodes, node_of = np.unique(corner_key, return_inverse=True)
    node_a, node_b = node_of[:len(a)], node_of[len(a):]
    same = (up[tri_of] == up[tri_of[twin]]) & (owner[tri_of] != owner[tri_of[twin]])
    # the twin's node at a is its node_b (it runs b -> a), its node at b its node_a
    pairs = np.concatenate([np.stack([node_a[same], node_b[twin[same]]], axis=1),
                            np.stack([node_b[same], node_a[twin[same]]], axis=1)])
    label = np.arange(len(nodes))
    while True:                                                   # label propagation: sectors are small
        low = np.minimum(label[pairs[:, 0]], label[pairs[:, 1]])
        new = label.copy()
        np.minimum.at(new, pairs[:, 0], low)
        np.minimum.at(new, pairs[:, 1], low)
        new = new[new]
        if np.array_equal(new, label):
            break
        label = new
    sector, vert_of_node = np.unique(label, return_inverse=True)
    node_vid = nodes % nv
    node_up = raised[nodes // nv]
    out = vertices[node_vid[sector]] * np.where(node_up[sector], 1.0 + height, 1.0)[:, None]
    new_tris = vert_of_node[node_a].reshape(-1, 3)                # the same corners, now per sector
    # walls: a raised half-edge a -> b whose twin is low; the wall's vertical sides pass through one
    # mid-height vertex per boundary vertex, shared by all the walls meeting there
    wall = np.flatnonzero(up[tri_of] & ~up[tri_of[twin]])
    wa, wb = a[wall], b[wall]
    mids, mid_of = np.unique(np.concatenate([wa, wb]), return_inverse=True)
    m_a, m_b = len(out) + mid_of[:len(wall)], len(out) + mid_of[len(wall):]
    out = np.concatenate([out, vertices[mids] * (1.0 + height / 2)])
    top_a, top_b = vert_of_node[node_a[wall]], vert_of_node[node_b[wall]]
    bot_a, bot_b = vert_of_node[node_b[twin[wall]]], vert_of_node[node_a[twin[wall]]]
    walls = np.concatenate([np.stack(q, axis=1) for q in ((top_b, top_a, m_a), (top_b, m_a, m_b),
                                                          (m_b, m_a, bot_a), (m_b, bot_a, bot_b))])
    _check_size(len(new_tris) + len(walls))
    return (out, np.concatenate([new_tris, walls]),
            np.concatenate([owner, np.tile(owner[tri_of[wall]], 4)]))


def relief_mask(colour: np.ndarray, classes: tuple[int, ...] | list[int]) -> np.ndarray:
    """Per tile: is its colour class one of ``classes``? (Bad classes are one-line errors.)"""
    present = sorted(set(colour.tolist()))
    bad = [c for c in classes if c not in present]
    if bad or not classes:
        raise ParameterError(f"colour class {bad[0] if bad else '(none)'} is not one of this tiling's colour classes "
                             f"{', '.join(map(str, present))}: raise one or more of them")
    raised = np.isin(colour, list(classes))
    if raised.all():
        raise ParameterError(f"raising colour classes {', '.join(map(str, classes))} lifts every tile (a larger ball, "
                             f"no relief): raise some of the classes {', '.join(map(str, present))}, not all")
    return raised


def write_stl(path: str | Path, vertices: np.ndarray, triangles: np.ndarray, radius_mm: float) -> None:
    """Binary STL, millimetres: the mesh scaled to ``radius_mm``, a facet normal per triangle."""
    tri = vertices[triangles] * radius_mm                     # (T, 3, 3)
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normal /= np.maximum(np.linalg.norm(normal, axis=1, keepdims=True), 1e-300)
    rec = np.zeros(len(tri), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    rec["n"], rec["v"] = normal, tri
    header = b"tilekit sphere mesh (binary STL, mm)".ljust(80, b" ")
    try:
        with open(path, "wb") as fh:
            fh.write(header)
            fh.write(np.uint32(len(tri)).tobytes())
            fh.write(rec.tobytes())
    except OSError as exc:
        raise TilekitError(f"cannot write {str(path)!r}: {exc.strerror or exc}") from None


def write_obj(path: str | Path, vertices: np.ndarray, triangles: np.ndarray, kind: np.ndarray, radius_mm: float,
              palette: list[str]) -> Path:
    """OBJ, millimetres, with a material per kind of tile in a .mtl beside it (returned)."""
    path = Path(path)
    mtl = path.with_suffix(".mtl")
    kinds = sorted(set(kind.tolist()))
    try:
        with open(mtl, "w", encoding="utf-8") as fh:
            for k in kinds:
                colour = palette[k % len(palette)].lstrip("#")
                r, g, b = (int(colour[i:i + 2], 16) / 255 for i in (0, 2, 4))
                fh.write(f"newmtl tile{k}\nKd {r:.4f} {g:.4f} {b:.4f}\n\n")
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(f"# tilekit sphere mesh, mm\nmtllib {mtl.name}\n")
            fh.writelines(f"v {x:.6f} {y:.6f} {z:.6f}\n" for x, y, z in (vertices * radius_mm).tolist())
            for k in kinds:
                fh.write(f"usemtl tile{k}\n")
                fh.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in triangles[kind == k].tolist())
    except OSError as exc:
        raise TilekitError(f"cannot write {str(path)!r}: {exc.strerror or exc}") from None
    return mtl


def write_mesh(tiling: Any, path: str | Path, size_mm: float = 60.0, rings: int = DEFAULT_RINGS,
               palette: list[str] | None = None, relief_mm: float | None = None,
               raise_colours: tuple[int, ...] = (0,)) -> tuple[int, int]:
    """Write a spherical tiling as a printable sphere of diameter ``size_mm`` (.stl or .obj by
    the suffix); returns (tiles, triangles). With ``relief_mm`` the tiles of the colour classes
    ``raise_colours`` (default the first) stand that far above the ball, 0 < relief_mm <= a
    quarter of size_mm (half the radius)."""
    # start-up cost: the SVG writer's module, only for its palette
    from tilekit.plugins.curved.render import DEFAULT_PALETTE

    suffix = Path(path).suffix.lower()
    if suffix not in MESH_FORMATS:
        raise ParameterError(f"a sphere mesh is written as {' or '.join(MESH_FORMATS)}, not {str(path)[:60]!r}")
    if getattr(tiling, "hyperbolic", True):
        raise ParameterError(f"{getattr(tiling, 'name', 'this tiling')} is not a tiling of the sphere: a printable "
                             "mesh is made for spherical tilings (e.g. icosahedron, 3.4.4.4)")
    if relief_mm is not None:
        relief_mm = check_relief(relief_mm, size_mm)
    patch = tiling.patch()
    vertices, triangles, owner = sphere_mesh(patch, rings)
    if relief_mm is not None:
        raised = relief_mask(patch.colour, tuple(raise_colours))
        vertices, triangles, owner = raise_tiles(vertices, triangles, owner, raised, relief_mm / (size_mm / 2))
    if suffix == ".stl":
        write_stl(path, vertices, triangles, size_mm / 2)
    else:
        write_obj(path, vertices, triangles, patch.colour[owner], size_mm / 2, list(palette or DEFAULT_PALETTE))
    return len(patch), len(triangles)


def check_relief(relief_mm: Any, size_mm: float) -> float:
    """The relief height as a float, or a one-line error naming the valid range."""
    limit = size_mm / 4
    try:
        h = float(relief_mm)
    except (TypeError, ValueError):
        h = float("nan")
    if isinstance(relief_mm, bool) or not 0 < h <= limit:      # NaN fails both comparisons
        raise ParameterError(f"relief must be a height in mm with 0 < relief <= {limit:g} (half the radius of a "
                             f"{size_mm:g} mm sphere), got {str(relief_mm)[:20]}")
    return h
