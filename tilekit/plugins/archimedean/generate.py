"""Write catalogue/archimedean/tilings.json: the constructed Archimedean and Laves units.

Run ``python -m tilekit.plugins.archimedean.generate [PATH]``. Every Euclidean vertex type
(§4.1) is tried with the builder; the types that extend are constructed (translational unit
and lattice read off the grown patch, see construct.py) and their duals computed. The file
is only a cache of that computation, so ``archimedean_tiling`` need not grow patches when a
catalogue is seeded; tests/plugins/test_archimedean.py regenerates it and compares.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

import numpy as np

from tilekit.plugins.archimedean import construct
from tilekit.regular.notation import (
    VertexType,
    euclidean_species,
    parse_sequence,
    types_of_species,
)
from tilekit.resources import catalogue_dir
from tilekit.symmetry import wallpaper_group

#: Radius (edge lengths) to which a vertex type must extend before it is constructed.
SCREEN_RADIUS = 4.0


def _rows(transforms: np.ndarray) -> list[list[float]]:
    return [[float(v) for v in t[:2].ravel()] for t in transforms]


def generate() -> dict[str, Any]:
    """The data: {"archimedean": {type: unit}, "laves": {type+hand: unit}}."""
    arch: dict[str, Any] = {}
    laves: dict[str, Any] = {}
    for species in euclidean_species():
        for vt in types_of_species(species):
            screen = construct.grow(vt, construct.seed_radius(vt) + SCREEN_RADIUS)
            if not screen.ok:
                continue
            protos, transforms, v1, v2, info = construct._construct(vt.polygons)
            arch[str(vt)] = {
                "unit": [[int(vt.sizes[p]), row] for p, row in zip(protos, _rows(transforms))],
                "v1": [float(v) for v in v1],
                "v2": [float(v) for v in v2],
                "construction": {"radius": info["radius"], "nodes": info["nodes"],
                                 "backtracks": info["backtracks"]},
            }
    construct._CACHE = {"archimedean": arch}  # Laves duals are computed from these units
    construct._laves.cache_clear()
    for key in list(arch):
        vt = VertexType.of(_polys(key))
        hands = ["l", "r"] if construct.is_chiral(vt) else [""]
        for hand in hands:
            outline, transforms, v1, v2 = construct._laves(vt.polygons, hand, True)
            laves[key + hand] = {
                "outline": [[float(x), float(y)] for x, y in outline],
                "unit": _rows(transforms),
                "v1": [float(v) for v in v1],
                "v2": [float(v) for v in v2],
            }
    construct._CACHE = {"archimedean": arch, "laves": laves}
    groups: dict[str, dict[str, Any]] = {}
    for key in arch:
        vt = VertexType.of(_polys(key))
        for hand in (["l", "r"] if construct.is_chiral(vt) else [""]):
            for tiling in (construct.archimedean_tiling(vt, hand), construct.laves_tiling(vt, hand)):
                groups[tiling.name] = {"wallpaper_group": wallpaper_group(tiling).iuc,
                                       **construct.transitivity(tiling)}
    construct._CACHE = None
    construct._laves.cache_clear()
    return {
        "generated_by": "python -m tilekit.plugins.archimedean.generate",
        "archimedean": arch,
        "laves": laves,
        "symmetry": groups,
    }


def _polys(text: str) -> tuple[int, ...]:

    return parse_sequence(text)


def default_path() -> Path:

    return catalogue_dir() / "archimedean" / "tilings.json"


def dumps(data: dict[str, Any]) -> str:
    """JSON with one line per tiling, so diffs show which unit changed."""
    lines = ["{", f' "generated_by": {json.dumps(data["generated_by"])},']
    for section in ("archimedean", "laves", "symmetry"):
        items = list(data[section].items())
        lines.append(f' "{section}": {{')
        for i, (key, value) in enumerate(items):
            comma = "," if i < len(items) - 1 else ""
            lines.append(f"  {json.dumps(key)}: {json.dumps(value)}{comma}")
        lines.append("  }" if section == "symmetry" else "  },")
    lines.append("}")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    path = Path(argv[0]) if argv else default_path()
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(dumps(generate()))
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
