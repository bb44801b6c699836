"""CPU-time budgets: the time limits of the searches, counted in CPU seconds of the thread doing
the work (and of the solver processes it forks), so that a verdict does not depend on the load of
the machine; a wall-clock cap (:data:`WALL_FACTOR` times the CPU seconds) still ends a starved search.

A :class:`Budget` is made in the thread whose CPU time it counts; any thread may read it (the SAT
layer's watchdog thread does, to interrupt a solver when the budget is spent)::

    >>> from tilekit.budget import Budget
    >>> b = Budget(2.0)
    >>> b.cpu, b.wall, b.spent()
    (2.0, 20.0, False)
    >>> half = b.share(0.5)       # a sub-budget: half of what is left, counted in b too
    >>> half.cpu <= 1.0
    True
    >>> b.charge(5.0)             # CPU seconds used elsewhere (a forked solver's) count as well
    >>> b.spent(), half.spent()
    (True, True)
    >>> str(Budget(120))
    '120 CPU seconds'
"""

from __future__ import annotations

import functools
import math
import threading
import time
from collections.abc import Callable

from tilekit.errors import ParameterError

#: The wall-clock cap of a budget, as a multiple of its CPU seconds: a thread starved of the CPU
#: (a loaded machine) still ends, after at most this many times its CPU budget in wall time.
WALL_FACTOR = 10.0


def thread_cpu_clock() -> Callable[[], float]:
    """A reader of the calling thread's CPU seconds that any thread of this process may call
    (POSIX thread CPU clocks); where there are none, the process's CPU seconds."""
    try:
        cid = time.pthread_getcpuclockid(threading.get_ident())
        time.clock_gettime(cid)
    except (AttributeError, OSError):  # no per-thread CPU clocks on this platform
        return time.process_time
    return functools.partial(time.clock_gettime, cid)


class Budget:
    """``cpu`` seconds of the making thread's CPU time, plus what :meth:`charge` adds, capped
    at ``wall`` seconds of wall-clock time (default ``WALL_FACTOR * cpu``).

    :meth:`share` makes a sub-budget whose use counts in this one too; :meth:`remaining` is the
    CPU left (0 once the wall-clock cap or a parent's budget is spent)."""

    __slots__ = ("cpu", "wall", "_clock", "_cpu0", "_wall0", "_charged", "_parent", "_capped")

    def __init__(self, cpu: float, *, wall: float | None = None, parent: Budget | None = None) -> None:
        cpu = _seconds(cpu, "a CPU budget")
        self.cpu = cpu
        self.wall = WALL_FACTOR * cpu if wall is None else _seconds(wall, "a wall-clock cap")
        self._clock = thread_cpu_clock()
        self._cpu0 = self._clock()
        self._wall0 = time.monotonic()
        self._charged = 0.0
        self._parent = parent
        self._capped = False  # the wall-clock cap was what ended it

    @classmethod
    def of(cls, limit: Budget | float | None) -> Budget | None:
        """``limit`` as a budget: a Budget as it is, a number as CPU seconds of the calling
        thread from now, None as no limit."""
        if limit is None or isinstance(limit, Budget):
            return limit
        return cls(limit)

    def used(self) -> float:
        """CPU seconds used so far: the thread's since the budget was made, and those charged."""
        return self._clock() - self._cpu0 + self._charged

    def elapsed(self) -> float:
        """Wall-clock seconds since the budget was made."""
        return time.monotonic() - self._wall0

    def remaining(self) -> float:
        """CPU seconds left; 0 once the wall-clock cap has passed or a parent budget is spent."""
        left = self.cpu - self.used()
        if self._parent is not None:
            left = min(left, self._parent.remaining())
        if left > 0.0 and self.elapsed() >= self.wall:
            self._capped = True  # what ended it (said by str)
            return 0.0
        return max(0.0, left)

    def spent(self) -> bool:
        return self.remaining() <= 0.0

    def wake_in(self) -> float:
        """Wall-clock seconds before the budget can be spent at the earliest (a thread uses at
        most one CPU second a second): when a watchdog has to look again."""
        left = min(self.remaining(), self.wall - self.elapsed())
        if self._parent is not None:
            left = min(left, self._parent.wake_in())
        return max(0.0, left)

    def charge(self, seconds: float) -> None:
        """Count ``seconds`` of CPU used outside this thread (a forked solver), here and in
        the budgets this one is a share of."""
        self._charged += float(seconds)
        if self._parent is not None:
            self._parent.charge(seconds)

    def share(self, fraction: float) -> Budget:
        """A sub-budget of ``fraction`` (0 < fraction <= 1) of the CPU and wall-clock time left;
        what it uses is used here too."""
        if not (isinstance(fraction, (int, float)) and 0.0 < fraction <= 1.0):
            raise ParameterError(f"a budget's share must be a fraction in (0, 1], got {fraction!r}")
        wall_left = max(0.0, self.wall - self.elapsed())
        return Budget(fraction * self.remaining(), wall=fraction * wall_left, parent=self)

    def __str__(self) -> str:
        text = f"{self.cpu:g} CPU second{'' if self.cpu == 1 else 's'}"
        if self._capped or (self._parent is not None and self._parent._capped):
            text += f", stopped by its wall-clock cap of {self.wall:g} s"
        return text

    def __repr__(self) -> str:
        return f"Budget(cpu={self.cpu:g}, wall={self.wall:g}, used={self.used():.3f})"


def _seconds(value: float, what: str) -> float:
    try:
        seconds = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{what} must be a number of seconds, got {value!r}") from None
    if not (math.isfinite(seconds) and seconds >= 0.0):
        raise ParameterError(f"{what} must be a finite number of seconds >= 0, got {value!r}")
    return seconds
