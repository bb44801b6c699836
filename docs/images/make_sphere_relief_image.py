"""Regenerate docs/images/sphere-relief.png: printable spheres with tiles in relief, drawn from
the mesh tilekit writes (sphere_mesh + raise_tiles, as `tilekit sphere-mesh --relief-mm`):
the Escher octahedron curved-ih-3-4-3 with one colour class raised, and the truncated
icosahedron 5.6.6 with its pentagons raised. A flat-shaded orthographic view: faces turned
away are culled, the rest painted far to near.

Run: python docs/images/make_sphere_relief_image.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw

from tilekit.catalogue import open_catalogue
from tilekit.plugins.curved.mesh import raise_tiles, sphere_mesh
from tilekit.plugins.curved.render import DEFAULT_PALETTE

HERE = Path(__file__).resolve().parent
PANEL = 400
SUPER = 3


def view(axis: np.ndarray, up: np.ndarray) -> np.ndarray:
    """Rows: screen x, screen y, towards the viewer."""
    z = axis / np.linalg.norm(axis)
    x = np.cross(up, z)
    x /= np.linalg.norm(x)
    return np.stack([x, np.cross(z, x), z])


def draw(vertices: np.ndarray, triangles: np.ndarray, colour: np.ndarray, rot: np.ndarray) -> Image.Image:
    size = PANEL * SUPER
    v = vertices @ rot.T
    tri = v[triangles]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    front = normal[:, 2] > 0
    light = np.array([-0.4, 0.5, 0.77])
    shade = 0.3 + 0.7 * np.clip(normal @ (light / np.linalg.norm(light)), 0, 1)
    order = np.flatnonzero(front)[np.argsort(tri[front, :, 2].mean(axis=1))]
    scale = size / 2 / (1.05 * np.linalg.norm(vertices, axis=1).max())
    xy = np.stack([size / 2 + tri[..., 0] * scale, size / 2 - tri[..., 1] * scale], axis=-1)
    rgb = np.array([[int(c[i:i + 2], 16) for i in (1, 3, 5)] for c in DEFAULT_PALETTE], dtype=float)
    fill = (rgb[colour % len(rgb)] * shade[:, None]).astype(int)
    img = Image.new("RGB", (size, size), "white")
    pen = ImageDraw.Draw(img)
    for t in order.tolist():
        pen.polygon([tuple(p) for p in xy[t].tolist()], fill=tuple(fill[t].tolist()), outline=tuple(fill[t].tolist()))
    return img.resize((PANEL, PANEL), Image.LANCZOS)


def main() -> None:
    cat = open_catalogue("sqlite://")
    panels = []
    for name, relief, axis in [("curved-ih-3-4-3", 0.08, (1.0, 0.7, 0.45)), ("truncated-icosahedron", 0.06, (0.3, 0.2, 1.0))]:
        patch = cat.tiling(name).patch()
        v, tri, owner = raise_tiles(*sphere_mesh(patch, rings=6), patch.colour == 0, relief)
        panels.append(draw(v, tri, patch.colour[owner], view(np.array(axis), np.array([0.0, 0.0, 1.0]))))
    out = Image.new("RGB", (PANEL * len(panels), PANEL), "white")
    for i, p in enumerate(panels):
        out.paste(p, (i * PANEL, 0))
    out.save(HERE / "sphere-relief.png", optimize=True)


if __name__ == "__main__":
    main()
