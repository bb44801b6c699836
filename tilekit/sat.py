"""The SAT layer every family shares: build a CNF, add cardinality constraints, solve.

One small vocabulary over python-sat, so that the Wang rectangle/torus encoding, the
polyomino Heesch and periodic-tiling searches and anything a third party writes agree on
solver names, time limits and the shape of an answer::

    >>> from tilekit.sat import CNF, solve
    >>> cnf = CNF()
    >>> a, b, c = cnf.new_vars(3)
    >>> cnf.add([a, b, c])
    >>> cnf.at_most([a, b, c], 1)           # pysat.card encoding, auxiliaries numbered for you
    >>> answer = solve(cnf, assumptions=[-a, -b])
    >>> answer.satisfiable, answer.value(c)
    (True, True)
    >>> solve(cnf, assumptions=[a, b]).satisfiable
    False

Incremental use keeps one solver alive between questions (learned clauses survive)::

    >>> with IncrementalSolver(cnf) as s:
    ...     first = s.solve(assumptions=[a]).satisfiable
    ...     s.add([-a])
    ...     second = s.solve(assumptions=[a]).satisfiable
    >>> first, second
    (True, False)

**Time limits.** ``time_limit`` on :func:`solve` or :meth:`IncrementalSolver.solve` is a
:class:`tilekit.budget.Budget` or a number of CPU seconds of the calling thread (counted from the
call); the answer is ``satisfiable=None`` when it is spent. CPU seconds, not wall-clock ones, so
that an answer does not depend on the machine's load; the budget's wall-clock cap still ends a
starved solve. Solvers that python-sat can interrupt (:data:`INTERRUPTIBLE`) are stopped by a
watchdog thread in this process that reads the solving thread's CPU clock; the others (CaDiCaL,
Lingeling) solve in a forked child process that is killed when the budget, charged with the
child's own CPU seconds, is spent — the child inherits the clauses (and an incremental solver's
state) by fork, nothing is pickled. The answer of a child does not teach the parent's
incremental solver its learned clauses.
"""

from __future__ import annotations

import collections
import contextlib
import gc
import math
import multiprocessing
import os
import threading
import time
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any

from tilekit.budget import Budget
from tilekit.errors import ParameterError, SolverLimit

#: Solver names we accept: python-sat's, and CryptoMiniSat 5 through pycryptosat (the optional
#: ``cms`` extra), the solver of Kaplan's heesch-sat.
SAT_SOLVERS = ("cadical195", "cadical153", "glucose4", "glucose42", "minisat22", "maplechrono", "lingeling",
               "gluecard4", "minicard", "cryptominisat5")
#: Solvers stopped in process when a time limit is spent (python-sat's interrupt, CryptoMiniSat's
#: own limit); the others run in a forked child under a time limit, killed when it is spent.
INTERRUPTIBLE = ("glucose4", "glucose42", "minisat22", "maplechrono", "gluecard4", "minicard", "cryptominisat5")
#: Solvers with native at-most-k constraints (:meth:`CNF.add_atmost`): Glucose and MiniSat
#: with cardinality propagation (Gluecard, Minicard)
NATIVE_ATMOST = ("gluecard4", "minicard")
#: Taken through pycryptosat, not python-sat.
CMS = "cryptominisat5"
#: python-sat's C entry points for adding a clause: solver name -> (handle attribute, function)
_C_ADD = {"glucose4": ("glucose", "glucose41_add_cl"), "glucose42": ("glucose", "glucose421_add_cl"),
          "cadical195": ("cadical", "cadical195_add_cl"), "cadical153": ("cadical", "cadical153_add_cl"),
          "minisat22": ("minisat", "minisat22_add_cl"), "maplechrono": ("maplesat", "maplechrono_add_cl"),
          "gluecard4": ("gluecard", "gluecard41_add_cl"), "minicard": ("minicard", "minicard_add_cl")}
DEFAULT_SAT_SOLVER = "cadical195"
#: pysat.card encodings by name (``CNF.at_most(..., encoding="totalizer")``).
CARD_ENCODINGS = ("seqcounter", "totalizer", "kmtotalizer", "sortnetwrk", "cardnetwrk", "mtotalizer", "ladder", "pairwise")
DEFAULT_CARD_ENCODING = "seqcounter"


@contextlib.contextmanager
def gc_paused() -> Iterator[None]:
    """Build (and hand over) big clause lists with Python's cyclic garbage collector paused.

    A formula is 10^4-10^6 small lists of ints, none in a reference cycle, so every pass the
    collector makes over them while they are being allocated frees nothing; measured, those
    passes were a third of the whole polyomino classification's time. Nests; the previous
    state is restored on exit.
    """
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was:
            gc.enable()


def check_solver(solver: str) -> str:
    """``solver`` itself, or a ParameterError naming the supported ones (or saying how to
    install pycryptosat for ``cryptominisat5``)."""
    if solver not in SAT_SOLVERS:
        raise ParameterError(f"SAT solver {solver!r} is not supported; choose one of {', '.join(SAT_SOLVERS)}")
    if solver == CMS and not have_cms():
        raise ParameterError("SAT solver 'cryptominisat5' needs pycryptosat: pip install 'tilekit[cms]' "
                             "(or choose one of " + ", ".join(x for x in SAT_SOLVERS if x != CMS) + ")")
    return solver


def have_cms() -> bool:
    """Whether pycryptosat (CryptoMiniSat 5) can be imported."""
    try:
        import pycryptosat  # noqa: F401  (optional: the cms extra)
    except ImportError:
        return False
    return True


def _flat(block: Any) -> Any:
    """A 2-D clause block as CryptoMiniSat's flat buffer: each row followed by a 0."""
    import numpy as np

    out = np.zeros((block.shape[0], block.shape[1] + 1), dtype=np.int64)
    out[:, :-1] = block
    return out.ravel()


class _Cms:
    """pycryptosat behind the few calls :func:`_run` and :class:`IncrementalSolver` make.

    Clause blocks go to the solver as flat int64 buffers (no Python list per clause), the
    list clauses in one call; a time limit is CryptoMiniSat's own (in process)."""

    def __init__(self) -> None:
        import pycryptosat

        self._s = pycryptosat.Solver(threads=1)
        self._model: Any = None

    def append(self, cnf: Any) -> None:
        if isinstance(cnf, CNF):
            if cnf.clauses:
                self._s.add_clauses(cnf.clauses)
            for block in cnf.blocks:
                self._s.add_clauses(_flat(block))
        else:
            rows = [list(map(int, c)) for c in cnf]
            if rows:
                self._s.add_clauses(rows)

    def add_clause(self, clause: list[int]) -> None:
        self._s.add_clause(clause)

    def solve(self, assumptions: list[int], time_limit: float | None) -> bool | None:
        import numpy as np

        kw = {} if time_limit is None else {"time_limit": float(time_limit)}
        # CryptoMiniSat refuses assumptions on variables no clause has mentioned; such a
        # variable is unconstrained, so the assumption holds in any model: leave it out
        top = self._s.nb_vars()
        sat, values = self._s.solve([v for v in assumptions if abs(v) <= top], **kw)
        if sat and values is not None:
            truth = np.array(values[1:], dtype=bool)
            idx = np.arange(1, len(truth) + 1, dtype=np.int64)
            self._model = np.where(truth, idx, -idx)
        else:
            self._model = None
        if sat is None:  # the time limit
            return None
        return bool(sat)

    def get_model(self) -> Any:
        return self._model

    def delete(self) -> None:
        self._s = None


#: Clauses turned into Python lists at a time when a block is handed to a solver.
BLOCK_ROWS = 1 << 16


class CNF:
    """Clauses over variables ``1..top``, with fresh-variable numbering and cardinality encodings.

    ``clauses`` is a plain list of lists of non-zero ints (DIMACS literals), so array code can
    ``extend`` it with ``ndarray.tolist()`` rows directly. Array code with many clauses of one
    width adds them as a *block* instead (:meth:`add_block`: a 2-D integer array, a clause
    per row), which stays an array until the solver takes it, :data:`BLOCK_ROWS` rows at a
    time: a binary clause costs 8-16 bytes there against about 140 as a list of two ints.
    """

    def __init__(self, clauses: Iterable[Sequence[int]] = (), top: int = 0) -> None:
        self.clauses: list[list[int]] = [list(map(int, c)) for c in clauses]
        self.blocks: list[Any] = []
        #: native at-most-k constraints ``(literals, k)`` for solvers in :data:`NATIVE_ATMOST`
        self.atmosts: list[tuple[list[int], int]] = []
        self.top = max([top, *(abs(v) for c in self.clauses for v in c)])

    def __len__(self) -> int:
        return len(self.clauses) + sum(len(b) for b in self.blocks) + len(self.atmosts)

    def add_atmost(self, lits: Sequence[int], k: int) -> None:
        """At most ``k`` of ``lits``, kept as one native constraint: only a solver in
        :data:`NATIVE_ATMOST` takes it (a Gluecard constraint is one object, where a clausal
        encoding of at-most-one over g literals is about 3g clauses)."""
        lits = [int(v) for v in lits]
        if lits:
            self.top = max(self.top, max(abs(v) for v in lits))
            self.atmosts.append((lits, int(k)))

    def add_atmost_groups(self, flat: Any, starts: Any, extra: Any, k: int = 1) -> None:
        """Many native at-most-``k`` constraints at once: group g is ``flat[starts[g]:starts[g+1]]``
        plus ``extra[g]`` (integer arrays of non-zero literals). The lists are cut from one
        ``tolist`` of each array, with no per-literal check (:meth:`add_atmost` is the checked
        one-at-a-time form)."""
        import numpy as np

        flat, starts, extra = (np.asarray(a, dtype=np.int64) for a in (flat, starts, extra))
        if not len(starts):
            return
        if not flat.all() or not extra.all():
            raise ParameterError("at-most constraints hold non-zero literals")
        self.top = max(self.top, int(np.abs(flat).max(initial=0)), int(np.abs(extra).max()))
        lits, ends = flat.tolist(), [*starts[1:].tolist(), len(flat)]
        self.atmosts += [([*lits[a:b], e], k) for a, b, e in zip(starts.tolist(), ends, extra.tolist())]

    def literals(self) -> int:
        """How many literals the clauses hold (a solver's memory grows with them)."""
        return sum(len(c) for c in self.clauses) + sum(int(b.size) for b in self.blocks)

    def add_block(self, block: Any) -> None:
        """Add one clause per row of the 2-D integer array ``block`` (non-zero literals)."""
        if getattr(block, "ndim", 0) != 2 or block.dtype.kind not in "iu":
            raise ParameterError(f"a clause block is a 2-D integer array, not {type(block).__name__}")
        if block.size:
            if block.shape[1] == 0 or not block.all():
                raise ParameterError("a clause block's rows are non-empty clauses of non-zero literals")
            self.top = max(self.top, int(abs(block).max()))
            self.blocks.append(block)

    def rows(self) -> Iterator[list[int]]:
        """Every clause as a list of ints: the list clauses, then the blocks' rows, converted
        :data:`BLOCK_ROWS` at a time."""
        yield from self.clauses
        for block in self.blocks:
            for start in range(0, len(block), BLOCK_ROWS):
                yield from block[start:start + BLOCK_ROWS].tolist()

    def new_var(self) -> int:
        """One fresh variable."""
        self.top += 1
        return self.top

    def new_vars(self, n: int) -> range:
        """``n`` fresh consecutive variables."""
        start = self.top + 1
        self.top += int(n)
        return range(start, self.top + 1)

    def reserve(self, top: int) -> None:
        """Declare that variables up to ``top`` are in use (an encoding numbered its own)."""
        self.top = max(self.top, int(top))

    def add(self, clause: Sequence[int]) -> None:
        """Add one clause (a disjunction of literals)."""
        clause = [int(v) for v in clause]
        if not clause or 0 in clause:
            raise ParameterError(f"a clause is a non-empty list of non-zero literals, not {clause!r}")
        self.top = max(self.top, *(abs(v) for v in clause))
        self.clauses.append(clause)

    def extend(self, clauses: Iterable[Sequence[int]]) -> None:
        """Add many clauses; literals above ``top`` raise ``top``."""
        rows = [list(c) for c in clauses]
        if rows:
            self.top = max(self.top, max(abs(v) for c in rows for v in c))
        self.clauses.extend(rows)

    def _card(self, kind: str, lits: Sequence[int], k: int, encoding: str) -> None:
        from pysat.card import CardEnc, EncType  # loaded with pysat.solvers only when used

        if encoding not in CARD_ENCODINGS:
            raise ParameterError(f"cardinality encoding {encoding!r} is unknown; choose one of {', '.join(CARD_ENCODINGS)}")
        lits = [int(v) for v in lits]
        if lits:
            self.top = max(self.top, max(abs(v) for v in lits))
        enc = getattr(CardEnc, kind)(lits=lits, bound=int(k), top_id=self.top, encoding=getattr(EncType, encoding))
        self.top = max(self.top, enc.nv)
        self.clauses.extend(enc.clauses)

    def at_most(self, lits: Sequence[int], k: int, encoding: str = DEFAULT_CARD_ENCODING) -> None:
        """At most ``k`` of ``lits`` are true."""
        self._card("atmost", lits, k, encoding)

    def at_least(self, lits: Sequence[int], k: int, encoding: str = DEFAULT_CARD_ENCODING) -> None:
        """At least ``k`` of ``lits`` are true."""
        self._card("atleast", lits, k, encoding)

    def exactly(self, lits: Sequence[int], k: int, encoding: str = DEFAULT_CARD_ENCODING) -> None:
        """Exactly ``k`` of ``lits`` are true."""
        self._card("equals", lits, k, encoding)


@dataclass
class SatAnswer:
    """One solver call: ``satisfiable`` is True (with a ``model``), False (proved), or None
    (the time limit expired first)."""

    satisfiable: bool | None
    model: list[int] | None
    solver: str
    seconds: float
    stats: dict[str, int] = field(default_factory=dict)

    def value(self, var: int) -> bool:
        """The model's value of variable ``var`` (variables the solver never saw are False)."""
        if self.model is None:
            raise ParameterError("no model: the answer is not satisfiable")
        return 0 < var <= len(self.model) and self.model[var - 1] > 0

    def values(self, variables) -> Any:
        """The model's values of many variables at once, as a NumPy bool array (variables the
        solver never saw are False): the vectorised :meth:`value` for decoding encodings."""
        import numpy as np  # measured start-up cost: the SAT layer itself does not need NumPy

        if self.model is None:
            raise ParameterError("no model: the answer is not satisfiable")
        m = np.asarray(self.model, dtype=np.int64)
        v = np.asarray(variables, dtype=np.int64)
        inside = (v > 0) & (v <= len(m))
        out = np.zeros(v.shape, dtype=bool)
        out[inside] = m[v[inside] - 1] > 0
        return out

    def true_vars(self) -> list[int]:
        """The variables set true in the model."""
        return [v for v in (self.model or ()) if v > 0]


def _clauses_of(cnf: CNF | Iterable[Sequence[int]]) -> Iterable[list[int]]:
    if isinstance(cnf, CNF):
        return cnf.rows() if cnf.blocks else cnf.clauses
    if isinstance(cnf, list) and (not cnf or isinstance(cnf[0], list)):
        return cnf  # already rows of literals: no copy (encodings hand over 10^5+ clauses)
    return [list(c) for c in cnf]


def _stats(s: Any) -> dict[str, int]:
    try:
        return {k: int(v) for k, v in (s.accum_stats() or {}).items()}
    except (NotImplementedError, AttributeError):
        return {}


class _Watchdog:
    """One daemon thread that calls each armed function when its budget is spent: the time
    limits of interruptible solves, without starting a thread per solve (a ``threading.Timer``
    each cost more than a small corona formula's whole solve, measured on the polyform
    classifications). A budget counts CPU seconds, which no clock can wait for: the thread sleeps
    until the earliest moment the budget could be spent (:meth:`Budget.wake_in`: a thread uses
    at most one CPU second a second) and looks again, so a busy solve is stopped on time and a
    starved one costs a few more wake-ups."""

    #: Least wall-clock seconds between two looks at one budget.
    RECHECK = 0.002

    def __init__(self) -> None:
        self._cond = threading.Condition()
        self._jobs: dict[int, tuple[float, Budget, Callable[[], Any]]] = {}
        self._fired: set[int] = set()
        self._next = 0
        self._pid = -1  # the process whose thread runs (a forked child starts its own)
        self._wake = 0.0  # when the thread wakes next (inf: only when notified)

    def arm(self, budget: Budget, fn: Callable[[], Any]) -> int:
        with self._cond:
            if self._pid != os.getpid():
                self._pid = os.getpid()
                self._wake = 0.0  # notified until the new thread sets its wake-up
                self._jobs.clear()
                self._fired.clear()
                threading.Thread(target=self._loop, name="tilekit-sat-watchdog", daemon=True).start()
            self._next += 1
            when = time.monotonic() + budget.wake_in()
            self._jobs[self._next] = (when, budget, fn)
            if when < self._wake:  # earlier than the thread's wake-up: wake it to wait less
                self._cond.notify()
            return self._next

    def disarm(self, token: int) -> bool:
        """Forget ``token``; whether its function was called."""
        with self._cond:
            self._jobs.pop(token, None)
            fired = token in self._fired
            self._fired.discard(token)
            return fired

    def _loop(self) -> None:
        with self._cond:
            while True:
                now = time.monotonic()
                for token in [t for t, (w, _, _) in self._jobs.items() if w <= now]:
                    _, budget, fn = self._jobs[token]
                    later = budget.wake_in()
                    if later > 0.0:  # not spent yet (its thread waited for the CPU): look again
                        self._jobs[token] = (now + max(later, self.RECHECK), budget, fn)
                        continue
                    del self._jobs[token]
                    self._fired.add(token)
                    fn()
                self._wake = min((w for w, _, _ in self._jobs.values()), default=math.inf)
                self._cond.wait(None if math.isinf(self._wake) else max(0.0, self._wake - time.monotonic()))


_WATCHDOG = _Watchdog()


def _run(s: Any, assumptions: list[int], budget: Budget | None) -> tuple[bool | None, list[int] | None, dict[str, int]]:
    """Solve on the live pysat solver ``s`` (interrupted by the shared watchdog when ``budget``
    is spent; no answer at once when it already is)."""
    if budget is not None and budget.spent():
        return None, None, {}
    if isinstance(s, _Cms):
        answer = s.solve(assumptions, None if budget is None else budget.remaining())
        return answer, (s.get_model() if answer else None), {}
    if budget is None:
        answer = s.solve(assumptions=assumptions)
    else:
        token = _WATCHDOG.arm(budget, s.interrupt)
        try:
            answer = s.solve_limited(assumptions=assumptions, expect_interrupt=True)
        finally:
            fired = _WATCHDOG.disarm(token)
        if answer is None or fired:
            s.clear_interrupt()
    return answer, (s.get_model() if answer else None), _stats(s)


def _child_cpu(pid: int) -> float | None:
    """CPU seconds (user and system) a child process has used, from /proc; None where unreadable."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as f:
            fields = f.read().rsplit(b")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, IndexError, ValueError):
        return None


def _in_child(job: Any, solver: str, budget: Budget) -> tuple[bool | None, list[int] | None, dict[str, int]]:
    """Run ``job()`` in a forked process and kill it when ``budget``, charged with the child's
    CPU seconds, is spent (for solvers such as CaDiCaL that python-sat cannot interrupt). The
    child inherits everything by fork."""
    if budget.spent():
        return None, None, {}
    ctx = multiprocessing.get_context("fork")
    parent, child = ctx.Pipe(duplex=False)

    def target() -> None:
        # only the parent reads: with its end closed here, a parent that died breaks the pipe
        # (the send fails and this process ends) instead of blocking the send for ever
        parent.close()
        answer = job()
        child.send((answer, time.process_time()))  # a forked child's CPU clock starts at 0
        child.close()

    start = time.monotonic()
    proc = ctx.Process(target=target, daemon=True)
    proc.start()
    child.close()
    cpu = 0.0
    try:
        while True:
            # where /proc is not readable the child's wall-clock time stands for its CPU time
            seen = _child_cpu(proc.pid)
            cpu = time.monotonic() - start if seen is None else seen
            left = min(budget.remaining() - cpu, budget.wake_in())
            if left <= 0.0:
                return None, None, {}
            if parent.poll(max(left, _Watchdog.RECHECK)):
                try:
                    answer, cpu = parent.recv()
                except EOFError:
                    raise SolverLimit(f"the {solver} process ended without an answer (exit code {proc.exitcode})") from None
                return answer
    finally:
        budget.charge(cpu)
        if proc.is_alive():
            proc.kill()
        proc.join()
        parent.close()


def solve(
    cnf: CNF | Iterable[Sequence[int]],
    assumptions: Sequence[int] = (),
    solver: str = DEFAULT_SAT_SOLVER,
    time_limit: Budget | float | None = None,
) -> SatAnswer:
    """Solve ``cnf`` once under ``assumptions`` with ``solver`` (a name in :data:`SAT_SOLVERS`).

    With ``time_limit`` (a :class:`Budget`, or CPU seconds of the calling thread from this call
    on) the answer is ``satisfiable=None`` when it is spent (see the module docstring for how it
    is enforced).
    """
    from pysat.solvers import Solver  # measured start-up cost: ~45 ms, only when solving

    check_solver(solver)
    clauses = _clauses_of(cnf)
    atmosts = cnf.atmosts if isinstance(cnf, CNF) else []
    if atmosts and solver not in NATIVE_ATMOST:
        raise ParameterError(f"native at-most constraints need one of {', '.join(NATIVE_ATMOST)}, not {solver}")
    assumptions = [int(v) for v in assumptions]
    start = time.perf_counter()
    budget = Budget.of(time_limit)
    here = budget is None or solver in INTERRUPTIBLE

    def job() -> tuple[bool | None, list[int] | None, dict[str, int]]:
        if solver == CMS:
            c = _Cms()
            c.append(cnf if isinstance(cnf, CNF) else clauses)
            return _run(c, assumptions, budget)
        with gc_paused():
            s = Solver(name=solver, bootstrap_with=clauses)
            for lits, k in atmosts:
                s.add_atmost(lits, k)
        with s:
            # in a child the parent kills it when the budget is spent; here the watchdog interrupts
            return _run(s, assumptions, budget if here else None)

    answer, model, stats = job() if here else _in_child(job, solver, budget)
    return SatAnswer(answer, model, solver, time.perf_counter() - start, stats)


class IncrementalSolver:
    """One live solver for a sequence of questions: add clauses, solve under assumptions,
    add more, solve again. Use as a context manager (or call :meth:`close`)."""

    def __init__(self, cnf: CNF | Iterable[Sequence[int]] = (), solver: str = DEFAULT_SAT_SOLVER) -> None:
        from pysat.solvers import Solver  # measured start-up cost: ~45 ms, only when solving

        self.solver = check_solver(solver)
        if solver == CMS:
            self._s = _Cms()
            self._s.append(cnf)
        else:
            with gc_paused():
                self._s = Solver(name=solver)
            self.extend(cnf)
        self.calls = 0

    def __enter__(self) -> IncrementalSolver:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        """Free the solver."""
        if self._s is not None:
            self._s.delete()
            self._s = None

    def add(self, clause: Sequence[int]) -> None:
        """Add one clause for every later question."""
        self._s.add_clause([int(v) for v in clause])

    def extend(self, clauses: Iterable[Sequence[int]]) -> None:
        """Add many clauses (a :class:`CNF` or rows of literals).

        The rows go to the solver object's own ``add_clause`` through ``map`` (measured: the
        per-clause loop of python-sat's ``append_formula`` cost more than the solver itself
        for the 10^4-10^5 short clauses of a corona formula); CryptoMiniSat takes a
        :class:`CNF`'s blocks as flat buffers."""
        atmosts = clauses.atmosts if isinstance(clauses, CNF) else []
        if atmosts and self.solver not in NATIVE_ATMOST:
            raise ParameterError(f"native at-most constraints need one of {', '.join(NATIVE_ATMOST)}, not {self.solver}")
        if isinstance(self._s, _Cms):
            self._s.append(clauses)
            return
        with gc_paused():
            collections.deque(map(self._adder(), _clauses_of(clauses)), maxlen=0)
            add = self._atmost_adder()
            for lits, k in atmosts:
                add(lits, k)

    def _adder(self) -> Any:
        """The cheapest call adding one clause: python-sat's C function bound to this
        solver's handle where its name is known (the return value only repeats what the next
        solve says), else the solver object's ``add_clause``."""
        inner = self._s.solver
        known = _C_ADD.get(self.solver)
        if known is not None:
            import functools

            import pysolvers

            handle, name = known
            fn = getattr(pysolvers, name, None)
            if fn is not None and getattr(inner, handle, None) is not None:
                return functools.partial(fn, getattr(inner, handle))
        return inner.add_clause

    def _atmost_adder(self) -> Any:
        """As :meth:`_adder` for native at-most-k constraints (Gluecard's C call; it returns
        False when the constraint makes the formula unsatisfiable, which the next solve says
        too)."""
        if self.solver == "gluecard4":
            import functools

            import pysolvers

            handle = getattr(self._s.solver, "gluecard", None)
            if handle is not None and hasattr(pysolvers, "gluecard41_add_am"):
                return functools.partial(pysolvers.gluecard41_add_am, handle)
        return self._s.add_atmost

    def solve(self, assumptions: Sequence[int] = (), time_limit: Budget | float | None = None) -> SatAnswer:
        """Answer the formula so far under ``assumptions``; ``None`` when ``time_limit`` (a
        :class:`Budget`, or CPU seconds of the calling thread from this call on) is spent."""
        assumptions = [int(v) for v in assumptions]
        start = time.perf_counter()
        budget = Budget.of(time_limit)
        self.calls += 1
        if budget is None or self.solver in INTERRUPTIBLE:
            answer, model, stats = _run(self._s, assumptions, budget)
        else:
            s = self._s
            answer, model, stats = _in_child(lambda: _run(s, assumptions, None), self.solver, budget)
        return SatAnswer(answer, model, self.solver, time.perf_counter() - start, stats)
