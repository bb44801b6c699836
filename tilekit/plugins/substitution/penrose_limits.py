"""The defaults and bounds of Penrose Escherization (``tilekit escherize-penrose``), in a module
without NumPy so that the command line can name them cheaply."""

#: Starts of the quasivertex parameter search (``--starts``): default and upper bound.
DEFAULT_STARTS = 4
MAX_STARTS = 32
#: Interior control points of each of the four edge shapes a, b, c, f (``--edge-points``).
DEFAULT_EDGE_POINTS = 3
MAX_EDGE_POINTS = 12
#: Nelder-Mead evaluations per start (40 per simplex vertex of the four parameters, as the
#: isohedral fit) and of each round of the least-squares polish, and its rounds: the budget.
START_EVALUATIONS = 40 * 5
POLISH_EVALUATIONS = 60
POLISH_ROUNDS = 4
