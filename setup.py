"""Packaging glue: ship the top-level catalogue/ and migrations/ folders inside the wheel.

Everything else lives in pyproject.toml. The data folders keep their reviewable place at
the top of the repository and are importable at run time as ``tilekit._catalogue`` and
``tilekit._migrations`` (see tilekit/resources.py).
"""

from setuptools import find_packages, setup

packages = find_packages(include=["tilekit", "tilekit.*"])
#: each built-in plugin's own Alembic branch (migrations/ beside its modules, not a package)
plugin_migrations = {p: ["migrations/*.py"] for p in packages if p.count(".") == 2 and p.startswith("tilekit.plugins.")}
packages += ["tilekit._catalogue", "tilekit._migrations"]

setup(
    packages=packages,
    package_dir={"tilekit._catalogue": "catalogue", "tilekit._migrations": "migrations"},
    package_data={
        "tilekit._catalogue": ["**/*"],
        "tilekit._migrations": ["*.py", "*.mako", "*.ini", "versions/*.py"],
        "tilekit": ["py.typed"],
        "tilekit.web": ["static/*"],
        **plugin_migrations,
    },
    include_package_data=False,
)
