"""The shipped substitution systems (catalogue/substitution/*.toml and the hat's own format), loaded
once per process; a module of its own so that the tiling and sampling modules read them without
importing the package's __init__ (no import circle)."""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

from tilekit.resources import catalogue_dir

if TYPE_CHECKING:  # pragma: no cover
    from tilekit.plugins.substitution.system import SubstitutionSystem

__all__ = ["builtin_systems", "system_dir"]


def system_dir() -> Path:
    """The folder of shipped system files."""
    return catalogue_dir() / "substitution"


@lru_cache(maxsize=1)
def builtin_systems() -> dict[str, Any]:
    """Every shipped system by name (loaded and validated once per process)."""
    # measured start-up cost: the systems load NumPy and shapely (~0.4 s), on first use
    from tilekit.plugins.substitution.hat import hat_systems  # the hat's own data format
    from tilekit.plugins.substitution.system import load_system  # start-up cost: as above

    out: dict[str, SubstitutionSystem] = {}
    for path in sorted(system_dir().glob("*.toml")):
        system = load_system(path)
        out[system.name] = system
    out.update(hat_systems())
    return out
