"""numba's compiled cache goes to a per-user folder, never beside tilekit's installed modules.

Issue 26: a regular install let ``cache=True`` write .nbi/.nbc files into
site-packages/tilekit/**/__pycache__; after ``pip install -e`` replaced the install those files
made an empty namespace package that shadowed it. The cache must land in the user cache folder,
fall back to the temporary folder, and be switched off when neither is writable.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

MODULE = textwrap.dedent(
    """
    from tilekit.jit import njit

    @njit(cache=True)
    def twice(x):
        return 2 * x
    """
)


def _compile(tmp_path: Path, env_extra: dict[str, str]) -> tuple[Path, subprocess.CompletedProcess]:
    pkg = tmp_path / "pkg"
    pkg.mkdir(exist_ok=True)
    (pkg / "jitted.py").write_text(MODULE)
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    env.update(env_extra)
    env["PYTHONPATH"] = os.pathsep.join([str(pkg), str(ROOT)])
    done = subprocess.run(
        [sys.executable, "-c", "import jitted, tilekit.jit as j; print(jitted.twice(21)); print(j.cache_dir())"],
        env=env, capture_output=True, text=True, timeout=300,
    )
    assert done.returncode == 0, done.stderr
    return pkg, done


def _cache_files(folder: Path) -> list[Path]:
    return [p for p in folder.rglob("*") if p.suffix in {".nbi", ".nbc"}]


def test_cache_goes_to_the_user_cache_folder_not_beside_the_module(tmp_path):
    pkg, done = _compile(tmp_path, {"XDG_CACHE_HOME": str(tmp_path / "cache"), "HOME": str(tmp_path)})
    assert done.stdout.split()[0] == "42"
    assert _cache_files(pkg) == []
    assert _cache_files(tmp_path / "cache" / "tilekit" / "numba")


def test_an_unwritable_cache_folder_falls_back_to_the_temporary_folder(tmp_path):
    blocker = tmp_path / "not-a-folder"
    blocker.write_text("a file where the cache folder's parent should be")
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    pkg, done = _compile(tmp_path, {"XDG_CACHE_HOME": str(blocker), "HOME": str(tmp_path), "TMPDIR": str(tmp)})
    assert done.stdout.split()[0] == "42"
    assert _cache_files(pkg) == []
    assert _cache_files(tmp)


def test_with_no_writable_folder_functions_compile_without_a_disk_cache(tmp_path, monkeypatch):
    import tempfile

    import tilekit.jit as jit

    blocker = tmp_path / "not-a-folder"
    blocker.write_text("x")
    monkeypatch.setenv("XDG_CACHE_HOME", str(blocker))
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    monkeypatch.setattr(tempfile, "gettempdir", lambda: str(blocker / "tmp"))
    jit.cache_dir.cache_clear()
    try:
        assert jit.cache_dir() is None
        twice = jit.njit(cache=True)(lambda x: 2 * x)
        assert twice(21) == 42
    finally:
        jit.cache_dir.cache_clear()
    assert _cache_files(tmp_path) == []


def test_a_user_set_numba_cache_dir_is_respected(tmp_path):
    mine = tmp_path / "mine"
    pkg, done = _compile(tmp_path, {"NUMBA_CACHE_DIR": str(mine), "HOME": str(tmp_path)})
    assert Path(done.stdout.split()[1]).parent == mine
    assert _cache_files(mine) and _cache_files(pkg) == []


def test_the_cache_folder_changes_with_any_source_of_tilekit(tmp_path):
    """numba checks a cached function against its own file only: a caller cached before its callee
    (in another module) changed kept the old callee (``heesch._least_holes`` failed to type after
    ``lattice._empty_components`` took a new argument). The folder is named by all of tilekit's
    sources, so any change starts a fresh cache."""
    import tilekit.jit as jit

    src = tmp_path / "src"
    (src / "sub").mkdir(parents=True)
    (src / "a.py").write_text("x = 1\n")
    (src / "sub" / "b.py").write_text("y = 2\n")
    first = jit.fingerprint(src)
    assert jit.fingerprint(src) == first
    (src / "sub" / "b.py").write_text("y = 3  # callee changed\n")
    os.utime(src / "sub" / "b.py", ns=(1, 1))
    assert jit.fingerprint(src) != first
    jit.cache_dir.cache_clear()
    try:
        here = jit.cache_dir()
        assert here is not None
        assert here.name == f"src-{jit.fingerprint(ROOT / 'tilekit')}"
    finally:
        jit.cache_dir.cache_clear()


def test_fingerprint_folders_unused_for_a_week_are_pruned(tmp_path):
    import tilekit.jit as jit

    old, recent = tmp_path / "src-old", tmp_path / "src-recent"
    old.mkdir()
    recent.mkdir()
    other = tmp_path / "not-ours"
    other.mkdir()
    week = jit.STALE_SECONDS + 60
    for p in (old, other):
        os.utime(p, (os.path.getmtime(p) - week, os.path.getmtime(p) - week))
    jit._prune(tmp_path, keep="src-current")
    assert not old.exists() and recent.exists() and other.exists()


def test_every_compiled_loop_of_tilekit_goes_through_tilekit_jit():
    offenders = [
        str(p.relative_to(ROOT))
        for p in (ROOT / "tilekit").rglob("*.py")
        if p.name != "jit.py" and ("from numba import" in p.read_text() or "import numba" in p.read_text())
    ]
    assert offenders == []


@pytest.mark.slow
def test_a_regular_install_writes_nothing_into_its_package_folder(tmp_path):
    """pip's regular (non-editable) install, then work that compiles every numba kernel family."""
    subprocess.run(
        [sys.executable, "-m", "pip", "install", "--no-deps", "--no-build-isolation", "-q",
         "--target", str(tmp_path / "site"), str(ROOT)],
        check=True, capture_output=True, timeout=600,
    )
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    env.update(PYTHONPATH=str(tmp_path / "site"), XDG_CACHE_HOME=str(tmp_path / "cache"),
               HOME=str(tmp_path), TILEKIT_CATALOGUE=f"sqlite:///{tmp_path / 'c.sqlite'}")
    code = textwrap.dedent(
        """
        import tilekit, tilekit.lattice as L
        assert tilekit.__file__.startswith(%r), tilekit.__file__
        from tilekit.plugins.polyomino.classify import classify
        from tilekit.plugins.polyomino.model import Polyomino
        p = Polyomino.parse('xx./.xx')
        print(classify(p.grid, p.cells, p.analysis).verdict)
        from tilekit.catalogue import open_catalogue
        til = open_catalogue().tiling('penrose-p3').configure(depth=9)
        print(len(til.patch(til.default_region())))
        """
    ) % str(tmp_path / "site")
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=600,
                          cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert _cache_files(tmp_path / "site") == []
