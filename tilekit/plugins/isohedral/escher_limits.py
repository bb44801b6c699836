"""The size limits and defaults of escherization (``tilekit escherize``), in a module without
imports so that the command line can name them without loading NumPy."""

#: Goal polygons have at least 3 and at most this many vertices (after dropping repeats).
MAX_GOAL_POINTS = 20_000
#: A goal file larger than this is refused before it is read (bytes).
MAX_GOAL_BYTES = 5_000_000
#: Resampled points per outline (``--samples``): default and bounds; one evaluation costs
#: O(n log n) for the alignment and O(n k^2) for the projection of k control coordinates.
DEFAULT_SAMPLES = 128
MIN_SAMPLES, MAX_SAMPLES = 16, 2048
#: Starts of the parameter search per type (``--starts``): default and upper bound.
DEFAULT_STARTS = 4
MAX_STARTS = 64
#: Interior control points per fundamental edge shape (``--edge-points``): default and bounds.
DEFAULT_EDGE_POINTS = 4
MAX_EDGE_POINTS = 24
#: Ranked types written (``--top``): at most the 81 unmarked types.
DEFAULT_TOP = 5
MAX_TOP = 81
#: Worker processes (``--workers``) at most.
MAX_WORKERS = 64
#: Interior points of the splitting path of dihedral Escherization (``--path-points``).
DEFAULT_PATH_POINTS = 4
MAX_PATH_POINTS = 24
#: Two goals whose areas differ by more than this factor are refused (dihedral Escherization
#: matches the two pieces of one tile at the goals' relative size).
MAX_GOAL_AREA_RATIO = 25.0
