"""The size limits and defaults of escherization (``tilekit escherize``), in a module without
NumPy so that the command line can name them cheaply; the goal and metric limits every
family's fits share live in tilekit.limits."""

from tilekit.limits import (  # noqa: F401 - re-exported: the isohedral CLI and fits name them from here
    DEFAULT_SAMPLES,
    MAX_GOAL_BYTES,
    MAX_GOAL_POINTS,
    MAX_SAMPLES,
    MIN_SAMPLES,
)
from tilekit.limits import MAX_FIT_WORKERS as MAX_WORKERS  # noqa: F401 - re-exported

#: Starts of the parameter search per type (``--starts``): default and upper bound.
DEFAULT_STARTS = 4
MAX_STARTS = 64
#: Interior control points per fundamental edge shape (``--edge-points``): default and bounds.
DEFAULT_EDGE_POINTS = 4
MAX_EDGE_POINTS = 24
#: Ranked types written (``--top``): at most the 81 unmarked types.
DEFAULT_TOP = 5
MAX_TOP = 81
#: Interior points of the splitting path of dihedral Escherization (``--path-points``).
DEFAULT_PATH_POINTS = 4
MAX_PATH_POINTS = 24
#: Two goals whose areas differ by more than this factor are refused (dihedral Escherization
#: matches the two pieces of one tile at the goals' relative size).
MAX_GOAL_AREA_RATIO = 25.0

