"""Compiled loops of the k-uniform search (numba): the σ0 gluing backtrack, and the minimality
test and canonical form of the symbols it completes.

The gluing search is a branchy depth-first tree search over edge ends, which does not
vectorise; in Python it spent most of a k = 5 run in its inner loop (the face walks, the
candidate filter and the assignment bookkeeping, a few microseconds each, about 10^8 of them).
These loops run the same search, step for step, on integer arrays (:func:`gluings` in
:mod:`.dsymbol` drives them and documents the search): the stack of choices is four arrays,
the candidates of a chamber are a slice of one array of chambers grouped by signature, and
a completed σ0 is copied into an output buffer. When the buffer fills, the loop returns with
its stack intact, and the next call resumes where it stopped, so completions stream out in
the order the Python search produced them.
"""

from __future__ import annotations

import numpy as np

from tilekit.jit import njit

#: Completed gluings handed back per call of the compiled search.
BATCH = 256


@njit(cache=True, nogil=True)
def _face_walk(c, s0, s1, face):  # pragma: no cover - compiled
    # (whether the <σ0, σ1>-orbit of c can still close, a chamber at an open end or -1)
    p = face[c]
    length = 1
    ends = 0
    open_end = -1
    for step0 in range(2):
        x = c
        step = step0
        while True:
            y = s0[x] if step == 0 else s1[x]
            if y < 0:
                open_end = x
                break
            if y == x:
                ends += 1
                break
            if y == c:  # a cycle: both directions meet
                if length % 2 != 0:
                    return False, -1
                return p % (length // 2) == 0, -1
            length += 1
            if length > 2 * p:
                return False, -1
            x = y
            step = 1 - step
    if open_end >= 0:
        return True, open_end
    return ends == 2 and p % length == 0, -1


@njit(cache=True, nogil=True)
def _first_open(s0, glued, offsets):  # pragma: no cover - compiled
    # the least unglued chamber of star 0 or of a star already glued to (-1 if none)
    for t in range(offsets.shape[0] - 1):
        if t == 0 or glued[t] != 0:
            for i in range(offsets[t], offsets[t + 1]):
                if s0[i] < 0:
                    return i
    return -1


@njit(cache=True, nogil=True)
def _connected(s0, s1, s2, queue, seen):  # pragma: no cover - compiled
    n = s0.shape[0]
    seen[:] = False
    seen[0] = True
    queue[0] = 0
    head = 0
    tail = 1
    while head < tail:
        x = queue[head]
        head += 1
        for y in (s0[x], s1[x], s2[x]):
            if not seen[y]:
                seen[y] = True
                queue[tail] = y
                tail += 1
    return tail == n


@njit(cache=True, nogil=True)
def _clear(s0, glued, owner, done, top, nd):  # pragma: no cover - compiled
    for i in range(nd):
        x = done[top, i]
        s0[x] = -1
        glued[owner[x]] -= 1


@njit(cache=True, nogil=True)
def glue(s1, s2, face, owner, offsets, leader, kind, sig, cand_start, cand_list, breaking,
         s0, glued, stack_d, stack_pos, stack_done, stack_nd, state, out):  # pragma: no cover - compiled
    """Run the gluing search until ``out`` is full or the search is over; return the number
    of completed σ0 rows written. ``state`` is (depth, phase: 0 new, 1 running, 2 over)."""
    n = s1.shape[0]
    queue = np.empty(n, dtype=np.int64)
    seen = np.empty(n, dtype=np.bool_)
    pa = np.empty(4, dtype=np.int64)
    pb = np.empty(4, dtype=np.int64)
    count = 0
    if state[1] == 2:
        return 0
    if state[1] == 0:
        d = _first_open(s0, glued, offsets)
        if d < 0:
            state[1] = 2
            return 0
        stack_d[0] = d
        stack_pos[0] = 0
        stack_nd[0] = 0
        state[0] = 1
        state[1] = 1
    depth = state[0]
    while depth > 0:
        top = depth - 1
        d = stack_d[top]
        _clear(s0, glued, owner, stack_done, top, stack_nd[top])
        stack_nd[top] = 0
        found = False
        nxt = -1
        home = owner[d]
        lo = cand_start[sig[d]]
        hi = cand_start[sig[d] + 1]
        while lo + stack_pos[top] < hi:
            e = cand_list[lo + stack_pos[top]]
            stack_pos[top] += 1
            if s0[e] != -1:
                continue
            t = owner[e]
            if breaking and t != home and glued[t] == 0:
                # a fresh star: only the first fresh star of its kind, at an orbit leader
                if not leader[e]:
                    continue
                first = True
                for u in range(t):
                    if u != home and glued[u] == 0 and kind[u] == kind[t]:
                        first = False
                        break
                if not first:
                    continue
            pa[0] = d
            pb[0] = e
            pa[1] = e
            pb[1] = d
            pa[2] = s2[d]
            pb[2] = s2[e]
            pa[3] = s2[e]
            pb[3] = s2[d]
            nd = 0
            fail = False
            for i in range(4):
                a = pa[i]
                if s0[a] == -1:
                    s0[a] = pb[i]
                    glued[owner[a]] += 1
                    stack_done[top, nd] = a
                    nd += 1
                elif s0[a] != pb[i]:
                    fail = True
                    break
            if fail:
                _clear(s0, glued, owner, stack_done, top, nd)
                continue
            ok = True
            nxt = -1
            for i in range(nd):
                fine, end = _face_walk(stack_done[top, i], s0, s1, face)
                if not fine:
                    ok = False
                    break
                if end >= 0 and nxt < 0:
                    nxt = end
            if ok:
                stack_nd[top] = nd
                found = True
                break
            _clear(s0, glued, owner, stack_done, top, nd)
        if not found:
            depth -= 1
            continue
        # close the face just extended before opening another
        if nxt < 0:
            nxt = _first_open(s0, glued, offsets)
        if nxt < 0:
            # every glued-to star is complete: a symbol if nothing is left, else disconnected
            complete = True
            for x in range(n):
                if s0[x] < 0:
                    complete = False
                    break
            if complete and _connected(s0, s1, s2, queue, seen):
                out[count, :] = s0
                count += 1
                if count == out.shape[0]:
                    state[0] = depth
                    return count
            continue
        stack_d[depth] = nxt
        stack_pos[depth] = 0
        stack_nd[depth] = 0
        depth += 1
    state[0] = 0
    state[1] = 2
    return count


@njit(cache=True, nogil=True)
def combo_tables(combo, gs1, gs2, gface, gleader, gsig, gdeg, star_off, s1, s2, face, degree, owner, offsets,
                 leader, kind, sig, cand_start, cand_list):  # pragma: no cover - compiled
    """Fill the search tables of one star combination (star ids ``combo``; the g... arrays
    hold every star's chambers, star g's from ``star_off[g]``): the stars' chambers side by
    side, their owner star, and the chambers grouped by signature (``cand_list``, group g
    from ``cand_start[g]``, each in increasing order); return the number of chambers."""
    n = 0
    offsets[0] = 0
    for t in range(combo.shape[0]):
        g = combo[t]
        base = n
        for j in range(star_off[g], star_off[g + 1]):
            s1[n] = gs1[j] + base
            s2[n] = gs2[j] + base
            face[n] = gface[j]
            degree[n] = gdeg[g]
            owner[n] = t
            leader[n] = gleader[j]
            n += 1
        offsets[t + 1] = n
        kind[t] = g
    keys = np.empty(n, dtype=np.int64)
    for x in range(n):
        keys[x] = gsig[star_off[combo[owner[x]]] + x - offsets[owner[x]]]
    order = np.argsort(keys, kind="mergesort")
    groups = 0
    for i in range(n):
        x = order[i]
        if i == 0 or keys[x] != keys[order[i - 1]]:
            cand_start[groups] = i
            groups += 1
        sig[x] = groups - 1
        cand_list[i] = x
    cand_start[groups] = n
    return n


@njit(cache=True, nogil=True)
def search_chunk(combos, gs1, gs2, gface, gleader, gsig, gdeg, star_off, breaking, tables, s0, glued, stack_d,
                 stack_pos, stack_done, stack_nd, state, tmp, out, out_combo):  # pragma: no cover - compiled
    """Run the gluing search of each star combination (a row of star ids in ``combos``) in
    turn and write the minimal symbols' σ0 rows to ``out`` (padded with -1) and their
    combination's row number to ``out_combo``; return how many. Returns early, resumable,
    when ``out`` has less room than ``tmp`` (one batch of completions). ``state`` is
    (depth, phase, combination, chambers) with phase as in :func:`glue`."""
    s1, s2, face, degree, owner, offsets, leader, kind, sig, cand_start, cand_list = tables
    count = 0
    while state[2] < combos.shape[0]:
        if out.shape[0] - count < tmp.shape[0]:
            return count
        if state[1] == 0 and state[0] == 0:
            n = combo_tables(combos[state[2]], gs1, gs2, gface, gleader, gsig, gdeg, star_off, s1, s2, face, degree,
                              owner, offsets, leader, kind, sig, cand_start, cand_list)
            state[3] = n
            s0[:n] = -1
            glued[:] = 0
        n = state[3]
        k = combos.shape[1]
        got = glue(s1[:n], s2[:n], face[:n], owner[:n], offsets[:k + 1], leader[:n], kind[:k], sig[:n],
                   cand_start, cand_list[:n], breaking, s0[:n], glued[:k], stack_d, stack_pos, stack_done,
                   stack_nd, state, tmp[:, :n])
        for r in range(got):
            cls = minimal_classes(tmp[r, :n], s1[:n], s2[:n], face[:n], degree[:n])
            if cls.max() == n - 1:
                out[count, :] = -1
                out[count, :n] = tmp[r, :n]
                out_combo[count] = state[2]
                count += 1
        if state[1] == 2:
            state[0] = 0
            state[1] = 0
            state[2] += 1
    return count


@njit(cache=True, nogil=True)
def minimal_classes(s0, s1, s2, face, degree):  # pragma: no cover - compiled
    """The classes of the coarsest partition compatible with σ0, σ1, σ2, m01, m12 (Moore's
    refinement), numbered from 0 in order of first chamber; equal to ``range(n)`` exactly
    when the symbol is minimal."""
    n = s0.shape[0]
    cls = np.empty(n, dtype=np.int64)
    new = np.empty(n, dtype=np.int64)
    rep = np.empty(n, dtype=np.int64)
    # start: by (face, degree)
    classes = 0
    for c in range(n):
        cls[c] = -1
    for c in range(n):
        if cls[c] >= 0:
            continue
        cls[c] = classes
        for x in range(c + 1, n):
            if cls[x] < 0 and face[x] == face[c] and degree[x] == degree[c]:
                cls[x] = classes
        classes += 1
    while True:
        # split each class by the classes of the three neighbours (first chamber leads)
        count = 0
        for c in range(n):
            new[c] = -1
        for c in range(n):
            if new[c] >= 0:
                continue
            new[c] = count
            rep[count] = c
            for x in range(c + 1, n):
                if (new[x] < 0 and cls[x] == cls[c] and cls[s0[x]] == cls[s0[c]] and cls[s1[x]] == cls[s1[c]]
                        and cls[s2[x]] == cls[s2[c]]):
                    new[x] = count
            count += 1
        if count == classes:
            return new
        classes = count
        cls[:] = new


@njit(cache=True, nogil=True)
def canonical_form(s0, s1, s2, face, degree):  # pragma: no cover - compiled
    """The least breadth-first relabelling over every start chamber, as an (n, 5) array of
    rows (σ0, σ1, σ2, m01, m12) in the new numbering; the symbol must be connected."""
    n = s0.shape[0]
    best = np.empty((n, 5), dtype=np.int64)
    cur = np.empty((n, 5), dtype=np.int64)
    number = np.empty(n, dtype=np.int64)
    order = np.empty(n, dtype=np.int64)
    have = False
    for start in range(n):
        number[:] = -1
        number[start] = 0
        order[0] = start
        size = 1
        # compare row by row while numbering: a row is final once its chamber's three
        # neighbours are numbered, which breadth-first order guarantees when it is reached
        state = 0 if have else -1  # 0: equal so far, -1: already less (or first)
        for i in range(n):
            x = order[i]
            for s in range(3):
                y = s0[x] if s == 0 else (s1[x] if s == 1 else s2[x])
                if number[y] < 0:
                    number[y] = size
                    order[size] = y
                    size += 1
            cur[i, 0] = number[s0[x]]
            cur[i, 1] = number[s1[x]]
            cur[i, 2] = number[s2[x]]
            cur[i, 3] = face[x]
            cur[i, 4] = degree[x]
            if state == 0:
                for j in range(5):
                    if cur[i, j] != best[i, j]:
                        state = -1 if cur[i, j] < best[i, j] else 1
                        break
                if state == 1:
                    break
        if state == 1:
            continue
        if state == -1 or not have:
            best[:, :] = cur
            have = True
    return best


@njit(cache=True, nogil=True)
def minimal_rows(rows, s1, s2, face, degree):  # pragma: no cover - compiled
    """For each σ0 row (with the shared σ1, σ2, labels): is the symbol minimal?"""
    ok = np.empty(rows.shape[0], dtype=np.bool_)
    n = rows.shape[1]
    for r in range(rows.shape[0]):
        cls = minimal_classes(rows[r], s1, s2, face, degree)
        ok[r] = cls.max() == n - 1
    return ok


@njit(cache=True, nogil=True)
def develop_flags(s0, s1, s2, inner, radius, cos, sin, quantum, cap):  # pragma: no cover - compiled
    """The flag walk of :func:`.realize.develop`, step for step: a breadth-first walk from the
    base flag (chamber 0, origin, direction 0, side 1) through σ0, σ1, σ2, keeping the flags
    whose vertex lies within ``radius``; a flag is keyed by its vertex rounded at ``quantum``,
    its direction (mod 24) and its side, in an open-addressing hash table. Returns the number
    of flags and their chamber, x, y, direction and side in the order first reached; the count
    is -1 when a flag is reached with two chambers, -2 when more than ``cap`` flags are met."""
    size = 1
    while size < 2 * cap:
        size *= 2
    mask = size - 1
    table = np.full(size, -1, dtype=np.int64)  # flag index per slot
    kx = np.empty(cap, dtype=np.int64)
    ky = np.empty(cap, dtype=np.int64)
    ch = np.empty(cap, dtype=np.int64)
    xs = np.empty(cap)
    ys = np.empty(cap)
    aa = np.empty(cap, dtype=np.int64)
    ss = np.empty(cap, dtype=np.int64)
    r2 = radius * radius
    ch[0], xs[0], ys[0], aa[0], ss[0], kx[0], ky[0] = 0, 0.0, 0.0, 0, 1, 0, 0
    h0 = (((0 * 1000003) ^ 0) * 31 + 0) * 2 + 1
    table[h0 & mask] = 0
    n = 1
    head = 0
    while head < n:
        c, x, y, a, s = ch[head], xs[head], ys[head], aa[head], ss[head]
        head += 1
        for move in range(3):
            if move == 0:
                c2, x2, y2, a2 = s0[c], x + cos[a], y + sin[a], (a + 12) % 24
            elif move == 1:
                c2, x2, y2, a2 = s1[c], x, y, (a + s * inner[c]) % 24
            else:
                c2, x2, y2, a2 = s2[c], x, y, a
            t = -s
            if x2 * x2 + y2 * y2 > r2:
                continue
            qx = np.int64(np.rint(x2 * quantum))
            qy = np.int64(np.rint(y2 * quantum))
            h = (((qx * 1000003) ^ qy) * 31 + a2) * 2 + (1 if t > 0 else 0)
            slot = h & mask
            while True:
                f = table[slot]
                if f < 0:
                    if n == cap:
                        return -2, ch, xs, ys, aa, ss
                    table[slot] = n
                    ch[n], xs[n], ys[n], aa[n], ss[n], kx[n], ky[n] = c2, x2, y2, a2, t, qx, qy
                    n += 1
                    break
                if kx[f] == qx and ky[f] == qy and aa[f] == a2 and ss[f] == t:
                    if ch[f] != c2:
                        return -1, ch, xs, ys, aa, ss
                    break
                slot = (slot + 1) & mask
    return n, ch[:n], xs[:n], ys[:n], aa[:n], ss[:n]
