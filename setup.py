"""Packaging glue: ship the top-level catalogue/ and migrations/ folders inside the wheel.

Everything else lives in pyproject.toml. The data folders keep their reviewable place at
the top of the repository and are importable at run time as ``tilekit._catalogue`` and
``tilekit._migrations`` (see tilekit/resources.py).
"""

from setuptools import find_packages, setup

packages = find_packages(include=["tilekit", "tilekit.*"])
#: each built-in plugin's own Alembic branch (migrations/ beside its modules, not a package)
#: and the files of its web pages (static/, served at /static/plugins/<name>/)
plugin_migrations = {p: ["migrations/*.py", "static/*"] for p in packages
                     if p.count(".") == 2 and p.startswith("tilekit.plugins.")}
#: data files a module reads from its own folder (e.g. the k-uniform plugin's notation table)
module_data = {p: ["*.json", "*.toml", "*.csv", "*.txt"] for p in packages}
for p, globs in plugin_migrations.items():
    module_data[p] = module_data[p] + globs
packages += ["tilekit._catalogue", "tilekit._migrations"]

setup(
    packages=packages,
    package_dir={"tilekit._catalogue": "catalogue", "tilekit._migrations": "migrations"},
    package_data={
        "tilekit._catalogue": ["**/*"],
        "tilekit._migrations": ["*.py", "*.mako", "*.ini", "versions/*.py"],
        **module_data,
        "tilekit": ["py.typed", *module_data["tilekit"]],
        "tilekit.web": ["static/*", *module_data["tilekit.web"]],
    },
    include_package_data=False,
)
