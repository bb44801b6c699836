"""``tilekit prototile NAME [--index I] -o FILE`` (issue 26): one prototile of any family as a
picture, GeoJSON or a cut file. The exported polygon is read back and compared with the
tiling's own prototile: the same outline point for point, its area and perimeter."""

from __future__ import annotations

import json

import numpy as np
import pytest
import shapely
from cliutil import assert_one_line_error


@pytest.fixture(scope="module")
def cli(tmp_path_factory):
    from cliutil import CatalogueCLI

    return CatalogueCLI(f"sqlite:///{tmp_path_factory.mktemp('prototile') / 'cli.sqlite'}")


@pytest.fixture(scope="module")
def cat(cli):
    from tilekit import open_catalogue

    cli.run("list", "--count")
    c = open_catalogue(cli.url)
    yield c
    c.close()


# one tiling of each family, with the options that change its tile
CASES = [
    ("IH16", ["--edge", "b=0,0:0.3,0.2:1,0"], {"edges": ["b=0,0:0.3,0.2:1,0"]}),
    ("IH41", ["--param", "0.1,0.2"], {"params": [0.1, 0.2]}),
    ("cairo", [], {}),
    ("3.4.6.4", [], {}),
    ("pentomino-F", [], {}),
    ("hat", [], {}),
    ("penrose-p3", [], {}),
    ("jeandel-rao-11", [], {}),
    ("multigrid-5", [], {}),
]


@pytest.mark.parametrize(("name", "args", "options"), CASES, ids=[c[0] for c in CASES])
def test_geojson_of_every_prototile_is_the_prototile(cli, cat, tmp_path, name, args, options):
    tiling = cat.tiling(name)
    if options:
        tiling = tiling.configure(**options)
    protos = tiling.prototiles
    for index, proto in enumerate(protos):
        out = tmp_path / f"{index}.geojson"
        r = cli.run("prototile", name, "--index", str(index), *args, "-o", str(out))
        assert r.exit_code == 0, r.output
        assert f"prototile {index} of {len(protos)}" in r.stdout
        features = json.loads(out.read_text())["features"]
        assert len(features) == 1
        ring = np.array(features[0]["geometry"]["coordinates"][0], dtype=float)
        if np.allclose(ring[0], ring[-1]):
            ring = ring[:-1]
        assert ring.shape == proto.outline.shape
        assert np.allclose(ring, proto.outline, atol=1e-9)
        poly, mine = shapely.Polygon(ring), shapely.Polygon(proto.outline)
        assert poly.is_valid and abs(poly.area - mine.area) < 1e-9 * max(1.0, mine.area)


def test_an_isohedral_tile_carries_its_edge_shapes(cli, cat, tmp_path):
    plain = tmp_path / "plain.geojson"
    shaped = tmp_path / "shaped.geojson"
    assert cli.run("prototile", "IH16", "-o", str(plain)).exit_code == 0
    assert cli.run("prototile", "IH16", "--edge", "b=0,0:0.3,0.2:1,0", "-o", str(shaped)).exit_code == 0
    a = json.loads(plain.read_text())["features"][0]["geometry"]["coordinates"][0]
    b = json.loads(shaped.read_text())["features"][0]["geometry"]["coordinates"][0]
    assert len(b) > len(a)  # each b edge gained the shape's interior point
    # the two b edges are J edges (IH16 is IJJJJI, §5.2): what one gains the other loses
    assert abs(shapely.Polygon(a).area - shapely.Polygon(b).area) < 1e-9


def test_dxf_and_svg_of_a_laves_tile(cli, cat, tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    proto = cat.tiling("cairo").prototiles[0]
    out = tmp_path / "cairo.dxf"
    r = cli.run("prototile", "cairo", "-o", str(out), "--mm-per-unit", "10")
    assert r.exit_code == 0 and "5 sides" in r.stdout, r.output
    doc = ezdxf.readfile(str(out))
    length = 0.0
    for e in doc.modelspace():
        pts = np.array([p[:2] for p in (e.get_points("xy") if e.dxftype() == "LWPOLYLINE" else e.points())])
        closed = e.closed if e.dxftype() == "LWPOLYLINE" else e.is_closed
        if closed:
            pts = np.vstack([pts, pts[:1]])
        length += float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())
    perimeter = float(shapely.Polygon(proto.outline).length)
    assert abs(length - 10 * perimeter) < 1e-6 * length  # millimetres
    svg = tmp_path / "cairo.svg"
    assert cli.run("prototile", "cairo", "-o", str(svg)).exit_code == 0
    assert svg.read_text().count("<path") >= 1


def test_bad_requests_are_one_line(cli, tmp_path):
    assert_one_line_error(cli.run("prototile", "penrose-p3", "--index", "2", "-o", str(tmp_path / "x.svg")),
                          "--index 2: penrose-p3 has 2 prototiles (--index 0..1; 0: thin, 1: thick)")
    assert_one_line_error(cli.run("prototile", "IH16", "-o", str(tmp_path / "x.csv")), "no tile table")
    assert_one_line_error(cli.run("prototile", "IH16", "-o", str(tmp_path / "x.txt")), "must end in one of")
    assert_one_line_error(cli.run("prototile", "nosuch", "-o", str(tmp_path / "x.svg")), "unknown tiling 'nosuch'")
    assert_one_line_error(cli.run("prototile", "IH16", "--index", "-1", "-o", str(tmp_path / "x.svg")))
