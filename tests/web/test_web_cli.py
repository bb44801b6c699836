"""``tilekit serve``, the render limit function and the packaging of the static files."""

from __future__ import annotations

import subprocess
import sys
import time
import zipfile
from pathlib import Path

import pytest
from click.testing import CliRunner

from tilekit.cli import cli
from tilekit.web.limits import RenderTooLarge, check_render_size, estimate_tiles

ROOT = Path(__file__).resolve().parents[2]


def test_serve_help_and_defaults():
    result = CliRunner().invoke(cli, ["serve", "--help"])
    assert result.exit_code == 0
    for text in ("--host", "127.0.0.1", "--port", "8000", "--writable", "--max-tiles"):
        assert text in result.output


def test_serve_bad_catalogue_is_one_line(tmp_path):
    bad = tmp_path / "not.sqlite"
    bad.write_text("this is not a database")
    result = CliRunner().invoke(cli, ["--catalogue", str(bad), "serve"])
    assert result.exit_code == 2
    assert result.output.count("\n") == 1 and result.output.startswith("error: ")


def test_serve_refuses_workers_and_cache_the_memory_cannot_hold(tmp_path):
    """64 workers that may each grow to 1 TiB before recycling: refused before anything starts,
    one line naming the options, exit 2."""
    cat = tmp_path / "c.sqlite"
    result = CliRunner().invoke(cli, ["--catalogue", str(cat), "serve", "--port", "0", "--render-workers", "64",
                                      "--worker-mb", str(1 << 20)])
    assert result.exit_code == 2, result.output
    assert result.output.count("\n") == 1 and "--render-workers" in result.output and "memory" in result.output


def test_serve_runs_on_loopback(web_catalogue):
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    proc = subprocess.Popen([sys.executable, "-c", "from tilekit.cli import main; main()",
                             "--catalogue", str(web_catalogue.path), "serve", "--port", str(port)],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        import httpx

        deadline = time.monotonic() + 60
        while True:
            try:
                r = httpx.get(f"http://127.0.0.1:{port}/api/families", timeout=5)
                break
            except httpx.TransportError:
                if proc.poll() is not None or time.monotonic() > deadline:
                    proc.kill()
                    pytest.fail(f"tilekit serve did not start: {proc.communicate()[1][-2000:]}")
                time.sleep(0.2)
        assert r.status_code == 200 and "isohedral" in {f["name"] for f in r.json()["families"]}
        r = httpx.post(f"http://127.0.0.1:{port}/api/runs/{web_catalogue.web_test_run}/cancel", timeout=5)
        assert r.status_code == 403
    finally:
        proc.terminate()
        _, err = proc.communicate(timeout=20)
    assert f"on http://127.0.0.1:{port}/ (read-only)" in err


class _Estimating:
    name = "fake"

    def __init__(self, n):
        self.n = n
        self.seen = None

    def estimate_tiles(self, region=None):
        self.seen = region
        return self.n


def test_check_render_size_prefers_the_tilings_own_estimate():
    t = _Estimating(25_000)
    with pytest.raises(RenderTooLarge) as info:
        check_render_size(t, (0, 0, 1, 1), 3)
    assert t.seen == (0, 0, 1, 1)
    assert info.value.estimate == 25_000 and info.value.limit == 20_000
    assert "about 25,000 tiles; the limit is 20,000" in str(info.value)
    assert check_render_size(_Estimating(10), (0, 0, 1, 1)) == 10
    assert check_render_size(_Estimating(25_000), (0, 0, 1, 1), limit=30_000) == 25_000


def test_conservative_estimates(web_catalogue):
    import types

    square = web_catalogue.tiling("4^4")
    # an object without estimate_tiles: four times the region's area over the smallest tile's
    bare = types.SimpleNamespace(prototiles=square.prototiles, name="bare")
    area = 4 * (10 * 10) / min(p.area for p in square.prototiles)
    assert estimate_tiles(bare, (0, 0, 10, 10)) == pytest.approx(area, rel=1e-6)
    patch = square.patch((0, 0, 10, 10))
    assert len(patch) <= estimate_tiles(square, (0, 0, 10, 10))  # the tiling's own estimate bounds it
    p3 = web_catalogue.tiling("penrose-p3")
    assert len(p3.configure(depth=5).patch(p3.default_region())) <= estimate_tiles(p3, p3.default_region(), 5)


@pytest.mark.slow
def test_wheel_ships_the_static_files(tmp_path):
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q",
                    "-w", str(tmp_path), str(ROOT)], check=True, capture_output=True)
    (wheel,) = tmp_path.glob("tilekit-*.whl")
    names = set(zipfile.ZipFile(wheel).namelist())
    static = {f"tilekit/web/static/{p.name}" for p in (ROOT / "tilekit" / "web" / "static").iterdir()}
    assert static and static <= names
    # the plugins' page scripts (tilekit_web_static) ship beside their modules
    plugin_static = {str(p.relative_to(ROOT)) for p in (ROOT / "tilekit" / "plugins").glob("*/static/*")}
    assert {"tilekit/plugins/isohedral/static/editor.js", "tilekit/plugins/substitution/static/penrose.js"} <= plugin_static
    assert plugin_static <= names
