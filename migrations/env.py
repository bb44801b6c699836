"""Alembic environment of the tilekit catalogue (configured programmatically by tilekit.catalogue).

tilekit passes an open connection in ``config.attributes["connection"]``; run from the
``alembic`` command line instead, ``sqlalchemy.url`` in the config is used. Plugin version
locations (``tilekit_migration_locations``) are added to ``version_locations`` by tilekit.
"""

from __future__ import annotations

from alembic import context
from sqlalchemy import engine_from_config, pool

from tilekit.models import METADATA

config = context.config
target_metadata = METADATA


def _configure_and_run(connection) -> None:
    context.configure(
        connection=connection,
        target_metadata=target_metadata,
        render_as_batch=connection.dialect.name == "sqlite",
        compare_type=True,
    )
    with context.begin_transaction():
        context.run_migrations()


def run_migrations_offline() -> None:
    """Emit SQL to stdout (``alembic upgrade head --sql``)."""
    context.configure(
        url=config.get_main_option("sqlalchemy.url"),
        target_metadata=target_metadata,
        literal_binds=True,
        dialect_opts={"paramstyle": "named"},
    )
    with context.begin_transaction():
        context.run_migrations()


def run_migrations_online() -> None:
    connection = config.attributes.get("connection")
    if connection is not None:
        _configure_and_run(connection)
        return
    engine = engine_from_config(
        config.get_section(config.config_ini_section, {}),
        prefix="sqlalchemy.",
        poolclass=pool.NullPool,
    )
    with engine.connect() as conn:
        _configure_and_run(conn)


if context.is_offline_mode():
    run_migrations_offline()
else:
    run_migrations_online()
