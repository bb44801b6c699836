"""tilekit's web catalogue and isohedral editor (``tilekit serve``; see docs/web.md).

:func:`create_app` builds the Starlette application: HTML pages (:mod:`.app`) over a JSON
API under ``/api/`` (:mod:`.api`), both over one service layer (:mod:`.service`) that opens
the catalogue, builds and renders tilings within the tile limits (:mod:`.limits`).
"""

from tilekit.web.limits import DEFAULT_MAX_TILES, RenderTooLarge, check_render_size, estimate_tiles

__all__ = ["DEFAULT_MAX_TILES", "RenderTooLarge", "check_render_size", "create_app", "estimate_tiles"]


def create_app(*args, **kwargs):  # noqa: ANN002, ANN003 - forwards to tilekit.web.app.create_app
    # start-up cost: the app imports starlette and the catalogue; tilekit.web.limits needs neither
    from tilekit.web.app import create_app as _create

    return _create(*args, **kwargs)
