"""The 17 wallpaper groups by name: IUC short names and Conway's orbifold symbols, the one
table every family reads (§3.2, §3.6.3)."""

from __future__ import annotations

#: The 17 wallpaper groups: IUC short name -> Conway's orbifold symbol (x for a cross-cap).
ORBIFOLD: dict[str, str] = {
    "p1": "o",
    "p2": "2222",
    "pm": "**",
    "pg": "xx",
    "cm": "*x",
    "pmm": "*2222",
    "pmg": "22*",
    "pgg": "22x",
    "cmm": "2*22",
    "p4": "442",
    "p4m": "*442",
    "p4g": "4*2",
    "p3": "333",
    "p3m1": "*333",
    "p31m": "3*3",
    "p6": "632",
    "p6m": "*632",
}


#: Orbifold symbol -> IUC short name.
IUC: dict[str, str] = {v: k for k, v in ORBIFOLD.items()}


def orbifold_symbol(cones: list[int] | tuple[int, ...] = (), boundaries: list[list[int]] | tuple = (),
                    handles: int = 0, crosscaps: int = 0) -> str:
    """Conway's orbifold symbol, the one spelling every family writes: ``o`` per handle, the
    cone orders, ``*`` and its corner orders per mirror boundary, ``x`` per cross-cap, in the
    order given. Orders are written as digits run together (``*632``) while all are at most
    9; when one exceeds 9 every order is separated by a comma (``*10,3,2``, ``12,6*2``), as
    Conway, Burgiel and Goodman-Strauss write orders past 9 (*The Symmetries of Things*,
    2008), so a symbol reads back one way only."""
    orders = [*cones, *(v for b in boundaries for v in b)]
    sep = "," if any(v >= 10 for v in orders) else ""
    text = "o" * handles + sep.join(map(str, cones))
    text += "".join("*" + sep.join(map(str, b)) for b in boundaries)
    return text + "x" * crosscaps


#: The longest orbifold symbol whose other spellings are worked out (digit runs are split).
MAX_ORBIFOLD_TEXT = 40


def orbifold_spellings(text: str) -> list[str]:
    """Every way ``text`` may spell an orbifold symbol in :func:`orbifold_symbol`'s form, for
    queries: itself, and when it has orders run together without commas (``*1032``, an old
    spelling), each split of its digit runs into orders >= 2 written as
    :func:`orbifold_symbol` would (``*10,3,2``, ``*103,2``, ...); a spelling with commas
    also answers to its digits run together."""
    text = text.strip()
    if len(text) > MAX_ORBIFOLD_TEXT or not text or any(c not in "0123456789,*ox" for c in text):
        return [text]
    import re

    parts = re.findall(r"\d[\d,]*|[^\d,]+", text)
    options: list[list[str]] = []
    for part in parts:
        if not part[0].isdigit():
            options.append([part])
            continue
        if "," in part:
            options.append([part, part.replace(",", "")])
            continue
        splits = [[int(part[a:b]) for a, b in zip((0, *cut), (*cut, len(part)))]
                  for n in range(len(part)) for cut in _cuts(len(part), n)]
        options.append([",".join(map(str, s)) if any(v >= 10 for v in s) else "".join(map(str, s))
                        for s in splits if all(v >= 2 and str(v)[0] != "0" for v in s)] or [part])
    out = {""}
    for opt in options:
        out = {a + b for a in out for b in opt}
    return sorted(out | {text})


def _cuts(length: int, n: int) -> list[tuple[int, ...]]:
    from itertools import combinations

    return list(combinations(range(1, length), n))
