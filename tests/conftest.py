"""Shared fixtures: catalogue URLs on SQLite and, when a server is given, PostgreSQL.

``TILEKIT_TEST_POSTGRES`` (or ``--postgres URL``) names a PostgreSQL server URL whose user may
create databases, e.g. ``postgresql+psycopg://tilekit:tilekit@127.0.0.1:5432/postgres``
(README's test command starts one through .ci/services.sh). Tests that take ``db_url`` run
once per backend; each PostgreSQL test gets a database of its own, dropped afterwards. Without
a server the PostgreSQL cases fail: they are part of the suite, not optional.
"""

from __future__ import annotations

import uuid

import pytest
from cliutil import ENV, CatalogueCLI, postgres_server

try:
    from hypothesis import settings as _hypothesis_settings

    # Speed is measured in benchmarks/, never asserted in unit tests: Hypothesis' default 200 ms
    # deadline per example can fail property tests on a loaded CI machine (two xdist workers
    # on two cores), so the suite runs without it.
    _hypothesis_settings.register_profile("tilekit", deadline=None, print_blob=True)
    _hypothesis_settings.load_profile("tilekit")
except ImportError:  # pragma: no cover - hypothesis is in the test extra
    pass


def pytest_addoption(parser):
    parser.addoption("--postgres", default=None, metavar="URL",
                     help=f"PostgreSQL server URL for the catalogue tests (default: ${ENV})")




@pytest.fixture
def postgres_url(request):
    """A fresh, empty PostgreSQL database on the test server (skips without a server)."""
    server = postgres_server(request.config)
    if not server:
        pytest.fail(f"the PostgreSQL tests need a server: set {ENV} or --postgres "
                    "(README's test command starts one through .ci/services.sh)")
    import sqlalchemy as sa

    admin = sa.create_engine(server, isolation_level="AUTOCOMMIT")
    name = f"tilekit_test_{uuid.uuid4().hex[:12]}"
    with admin.connect() as conn:
        conn.execute(sa.text(f'CREATE DATABASE "{name}"'))
    url = sa.engine.make_url(server).set(database=name).render_as_string(hide_password=False)
    try:
        yield url
    finally:
        with admin.connect() as conn:
            conn.execute(sa.text(f'DROP DATABASE IF EXISTS "{name}" WITH (FORCE)'))
        admin.dispose()


@pytest.fixture(params=["sqlite", "postgresql"])
def db_url(request, tmp_path):
    """A catalogue URL: a new SQLite file, or a new PostgreSQL database."""
    if request.param == "sqlite":
        return f"sqlite:///{tmp_path / 'catalogue.sqlite'}"
    return request.getfixturevalue("postgres_url")


def _sigint_ignored() -> bool:
    """Whether this process ignores SIGINT at the OS level (then every child inherits it)."""
    try:
        with open("/proc/self/status") as fh:
            for line in fh:
                if line.startswith("SigIgn:"):
                    return bool(int(line.split()[1], 16) >> (2 - 1) & 1)
    except OSError:
        return False
    return False


def pytest_configure(config):
    """A shell starts a background job (``cmd &``, as CI runners and ``nohup`` do) with SIGINT
    ignored, Python then keeps it ignored, and every subprocess a test starts inherits that:
    the run layer's Ctrl-C tests would fail for a reason that is not theirs. Tests run with
    the default handler, as in a terminal."""
    import signal

    if _sigint_ignored():
        signal.signal(signal.SIGINT, signal.default_int_handler)


def pytest_collection_modifyitems(config, items):
    """``@pytest.mark.exhaustive``: minutes each on the 2-core CI machine, beyond the ``slow``
    tests CI runs; they run with ``TILEKIT_EXHAUSTIVE=1`` (docs/benchmarks.md names them)."""
    import os

    if os.environ.get("TILEKIT_EXHAUSTIVE") == "1":
        return
    skip = pytest.mark.skip(reason="exhaustive: set TILEKIT_EXHAUSTIVE=1")
    for item in items:
        if "exhaustive" in item.keywords:
            item.add_marker(skip)


@pytest.fixture(autouse=True)
def _sigint_not_left_ignored(request):
    """A test (or a library it drives) that leaves SIGINT ignored would make every later
    subprocess deaf to Ctrl-C, so the Ctrl-C tests of the run layer would fail for a reason
    that is not theirs: restore the default handler and name the test in a warning."""
    import signal
    import warnings

    yield
    if _sigint_ignored():
        signal.signal(signal.SIGINT, signal.default_int_handler)
        warnings.warn(f"{request.node.nodeid} left SIGINT ignored; restored", stacklevel=1)


@pytest.fixture
def catalogue_cli(tmp_path) -> CatalogueCLI:
    return CatalogueCLI(f"sqlite:///{tmp_path / 'cli.sqlite'}")
