"""The level-by-level substitution loop that every generator shares (§6.1, §7.4).

The similarity engine, the keypoint (spectre) systems and the hat all substitute a seed
supertile level by level: drop the placed supertiles that cannot reach the region, replace
every survivor by its children (one compiled pass over the level, kernels.py), and at the end place
the base tiles. Only the rules per level, the culling test and the base differ; they are
arguments here.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

Expand = Callable[[np.ndarray, np.ndarray, int], tuple[np.ndarray, np.ndarray]]
Cull = Callable[[np.ndarray, np.ndarray, int], np.ndarray]


def substitute_levels(
    label: np.ndarray,
    maps: np.ndarray,
    depth: int,
    expand: Expand,
    cull: Cull | None = None,
    after_level: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Substitute the placed supertiles (``label``, ``maps``) of level ``depth`` down to level 0.

    For n = depth .. 1: keep the supertiles for which ``cull(label, maps, n)`` is true (when
    given), then ``expand(label, maps, n)`` replaces each level-n supertile by its level-(n-1)
    children; ``after_level(label, maps)`` may return a mask to keep (duplicates removed, for
    overlapping systems). Finally ``cull(label, maps, 0)`` drops tiles that miss the region.
    """
    for n in range(depth, 0, -1):
        if cull is not None:
            keep = cull(label, maps, n)
            label, maps = label[keep], maps[keep]
        label, maps = expand(label, maps, n)
        if after_level is not None:
            keep = after_level(label, maps)
            label, maps = label[keep], maps[keep]
    if cull is not None:
        keep = cull(label, maps, 0)
        label, maps = label[keep], maps[keep]
    return label, maps


def expand_base(
    label: np.ndarray, maps: np.ndarray, base: Sequence[np.ndarray], colours: Sequence[np.ndarray]
) -> tuple[np.ndarray, np.ndarray]:
    """The base tiles of level-0 supertiles: label j's tiles are placed by ``maps @ base[j]``
    and coloured ``colours[j]``. Returns (transforms, colours); the dtype of ``maps`` is kept
    (the tiles of one supertile are contiguous, in supertile order)."""
    colour, out = expand_by_label(label, maps, colours, base)
    return out, colour


def expand_by_label(
    label: np.ndarray,
    maps: np.ndarray,
    children: Sequence[np.ndarray],
    matrices: Sequence[np.ndarray],
) -> tuple[np.ndarray, np.ndarray]:
    """One substitution level as arrays: every placed supertile of label j (``maps[k]``)
    becomes its children ``children[j]`` placed by ``maps[k] @ matrices[j]``.

    The dtype of ``maps`` is kept (integer lattice maps stay exact). Returns the children's labels and maps; the children of one supertile are
    contiguous, in supertile order. One compiled pass per level (kernels.py).
    """
    # start-up cost: numba loads in ~0.25 s; only generation needs it, not listing the family
    from tilekit.plugins.substitution import kernels

    return kernels.expand(label, maps, list(children), list(matrices))


def meets_discs(label: np.ndarray, transform: np.ndarray, bounds: tuple[np.ndarray, np.ndarray], box: Sequence[float]) -> np.ndarray:
    """Mask of placed supertiles (rigid ``transform``) whose bounding disc (``bounds``:
    centre and radius per label) meets the box (x0, y0, x1, y1), with a relative and an
    absolute margin of 1e-9 for float noise."""
    # start-up cost: numba, as in expand_by_label
    from tilekit.plugins.substitution import kernels

    centres, radii = bounds
    return kernels.meets(label, transform, centres, radii * (1 + 1e-9) + 1e-9, box, similar=False)
