"""Cross-references of the k-uniform records to Čtrnáct and Kopczyński's tessellation catalogue
(zenorogue/tes-catalog): the shipped table derived from its files, and ``tilekit import
tes-catalog`` on a folder of .tes files written here.

Published figures: OEIS A068599 (k-uniform tilings: 11, 20, 61, 151, 332, 673, 1472 for
k = 1..7) and the catalogue's own split by the number m of vertex types (its folder names;
/work/shared/design/FACTS.md): k = 3: 22, 39; k = 4: 33, 85, 33; k = 5: 74, 149, 94, 15;
k = 6: 100, 284, 187, 92, 10; k = 7: 175, 572, 426, 218, 74, 7.
"""

from __future__ import annotations

import itertools
import json
import re
from collections import Counter

import pytest

from tilekit.plugins.kuniform.search import chunks, records_for, tilings_with_types
from tilekit.plugins.kuniform.tescatalog import (
    TABLE,
    TABLE_MAX_K,
    shipped,
    symbol_key,
    tes_catalog_id,
)
from tilekit.regular.notation import VertexType

A068599 = [11, 20, 61, 151, 332, 673, 1472]
SPLITS = {3: [22, 39], 4: [33, 85, 33], 5: [74, 149, 94, 15], 6: [100, 284, 187, 92, 10],
          7: [175, 572, 426, 218, 74, 7]}
_ID = re.compile(r"^k-uniform/(\d\d)/(?:(\d+) \([\d]+\)/|(\d+)/)?[^/]+$")


def test_the_shipped_table_holds_each_k_and_split_once():
    """The table (built from the catalogue's files by the .tes reader) has one identifier per
    tiling: A068599's count for each k, and the catalogue's split by vertex types, which
    the identifiers' folders give."""
    data = json.loads(TABLE.read_text())
    ids = shipped()
    assert data["max_k"] == TABLE_MAX_K == 7 and data["commit"]
    assert all(re.fullmatch(r"[0-9a-f]{16}", key) for key in ids)
    assert len(set(ids.values())) == len(ids)  # no file twice
    by_k: Counter = Counter()
    by_km: Counter = Counter()
    for ident in ids.values():
        m = _ID.match(ident)
        assert m, ident
        k = int(m.group(1))
        by_k[k] += 1
        by_km[k, int(m.group(2) or m.group(3) or 1)] += 1
    assert [by_k[k] for k in range(1, 8)] == A068599
    assert {str(k): n for k, n in by_k.items()} == data["count_by_k"]
    for k, split in SPLITS.items():
        assert [by_km[k, m] for m in range(2, 2 + len(split))] == split, k


@pytest.mark.parametrize("k", [1, 2, 3])
def test_every_record_to_k3_has_its_file(k):
    """Each tiling the search finds for k <= 3 has a table entry, filed under its k and its
    number of vertex types, and no two share one."""
    seen = set()
    for chunk in chunks({"k": k}):
        types = [VertexType.parse(t).polygons for t in chunk["types"]]
        for sym in tilings_with_types(types):
            ident = tes_catalog_id(sym.encode())
            assert ident is not None, sym.encode()
            m = _ID.match(ident)
            assert int(m.group(1)) == k and int(m.group(2) or m.group(3) or 1) == len(set(types)), ident
            seen.add(ident)
    assert len(seen) == A068599[k - 1]


def test_symbol_key_is_a_hash_of_the_encoding():
    assert symbol_key("4,8,8/3,3,3/0,1,2/1,0,2/0,2,1") != symbol_key("4,8,8/3,3,3/0,1,2/1,0,2/0,1,2")
    assert len(symbol_key("x")) == 16


OCTAGONS = """## truncated square tiling, written by hand
e2.
angleunit(deg)
unittile(135,135,135,135,135,135,135,135)
unittile(90,90,90,90)
repeat(0,4)
repeat(1,4)
conway("(0 0')(1)")
"""


def test_import_attaches_ids_and_refuses_bad_files(tmp_path):
    """``tilekit import tes-catalog DIR`` sets tes_catalog on the record a file draws (4.8^2,
    matched by D-symbol), reports a malformed file on one line and exits 2, and counts a file
    of a k the catalogue holds that draws no record in it."""
    from tests.cliutil import CatalogueCLI
    from tilekit.catalogue import open_catalogue

    url = f"sqlite:///{tmp_path / 'x.sqlite'}"
    cat = open_catalogue(url)
    cat.upsert(records_for([(4, 8, 8)]))
    cat.close()
    tree = tmp_path / "checkout" / "files" / "tessellations" / "k-uniform" / "01"
    (tree / "mine").mkdir(parents=True)
    (tree / "mine" / "octagons.tes").write_text(OCTAGONS)
    (tree / "bad.tes").write_text(OCTAGONS.replace("135,", "130,"))
    (tree / "square.tes").write_text("e2.\nangleunit(deg)\nunittile(90,90,90,90)\nrepeat(0,4)\nconway(\"(0)\")\n")
    cli = CatalogueCLI(url)
    r = cli.run("import", "tes-catalog", str(tmp_path / "checkout"))
    assert r.exit_code == 2, r.output
    refused = [line for line in r.output.splitlines() if line.startswith("refused:")]
    assert len(refused) == 1 and "bad.tes" in refused[0] and "not a regular 8-gon" in refused[0], r.output
    assert "1 records got a tes_catalog identifier; 1 files draw no record" in r.output, r.output
    assert cli.count("k-uniform", "tes_catalog=k-uniform/01/mine/octagons") == 1
    r = cli.run("import", "tes-catalog", str(tmp_path))
    assert r.exit_code == 2 and "no tes-catalog k-uniform tree here" in r.output, r.output


@pytest.mark.parametrize("args, needle", [(["--max-k", "13"], "13"), (["--max-k", "x"], "x")])
def test_import_bad_options(tmp_path, args, needle):
    from tests.cliutil import CatalogueCLI

    r = CatalogueCLI(f"sqlite:///{tmp_path / 'y.sqlite'}").run("import", "tes-catalog", str(tmp_path), *args)
    assert r.exit_code == 2 and needle in r.output, r.output


def test_table_keys_do_not_collide_on_the_records_to_k2():
    keys = [symbol_key(s.encode()) for types in itertools.combinations_with_replacement(
        [VertexType.parse(t).polygons for t in ("3^6", "3^4.6", "4^4", "3^3.4^2", "3^2.4.3.4")], 2)
        for s in tilings_with_types(types)]
    assert len(keys) == len(set(keys))
