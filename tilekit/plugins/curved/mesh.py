"""Printable meshes of a tiling of the sphere: one closed triangle mesh whose faces follow the
sphere, written as binary STL (what slicers read) or OBJ with one material per kind of tile
(the tiles as coloured regions).

Each tile is triangulated in its prototile's frame at the pole: ``rings`` rings between the
centre and the outline (its ``samples`` points per edge, placed symmetrically so neighbours
sample a shared edge at the same points), each ring's points pushed onto the sphere; the
tiles' shared boundary points are welded on a grid (a cluster of float-equal points is one
vertex), so the mesh is closed and every edge has exactly two triangles.
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
        tris_all.append((local_tris[None] + base + p * np.arange(m)[:, None, None]).reshape(-1, 3))
        owner_all.append(np.repeat(idx, len(local_tris)))
        base += m * p
    pts = np.concatenate(pts_all)
    tris = np.concatenate(tris_all)
    if len(tris) > MAX_TRIANGLES:
        raise ParameterError(f"this mesh would have {len(tris):,} triangles, over the limit of {MAX_TRIANGLES:,}: "
                             "use fewer rings (--rings) or samples (--set samples=N)")
    vid = weld(pts, sep)
    used, new = np.unique(vid, return_inverse=True)
    return pts[used], new.reshape(-1)[tris], np.concatenate(owner_all)


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
               palette: list[str] | None = None) -> tuple[int, int]:
    """Write a spherical tiling as a printable sphere of diameter ``size_mm`` (.stl or .obj by
    the suffix); returns (tiles, triangles)."""
    # start-up cost: the SVG writer's module, only for its palette
    from tilekit.plugins.curved.render import DEFAULT_PALETTE

    suffix = Path(path).suffix.lower()
    if suffix not in MESH_FORMATS:
        raise ParameterError(f"a sphere mesh is written as {' or '.join(MESH_FORMATS)}, not {str(path)[:60]!r}")
    if getattr(tiling, "hyperbolic", True):
        raise ParameterError(f"{getattr(tiling, 'name', 'this tiling')} is not a tiling of the sphere: a printable "
                             "mesh is made for spherical tilings (e.g. icosahedron, 3.4.4.4)")
    patch = tiling.patch()
    vertices, triangles, owner = sphere_mesh(patch, rings)
    if suffix == ".stl":
        write_stl(path, vertices, triangles, size_mm / 2)
    else:
        write_obj(path, vertices, triangles, patch.colour[owner], size_mm / 2, list(palette or DEFAULT_PALETTE))
    return len(patch), len(triangles)
