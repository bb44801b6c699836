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
