"""The curved family's command: ``tilekit sphere-mesh``, a printable sphere (STL, or OBJ with
coloured tiles; tiles of chosen colour classes optionally in relief) from a catalogue tiling of the sphere.

Only click and the core's cheap cli_types are loaded at the top, so ``tilekit --help``, which
adds this command, does not import NumPy.
"""

from __future__ import annotations

import click

from tilekit.cli_types import OUTPUT, BoundedInt, FiniteFloat

#: as tilekit.plugins.curved.mesh (kept here so that --help imports no NumPy; a test keeps them equal)
DEFAULT_RINGS, MAX_RINGS = 4, 32


@click.command(name="sphere-mesh")
@click.argument("name")
@click.option("-o", "--output", "out", required=True, type=OUTPUT,
              help="Output file: .stl (binary, millimetres) or .obj (with a .mtl beside it: a colour per kind of tile).")
@click.option("--size-mm", type=FiniteFloat(10_000.0, min=1.0), default=60.0, show_default=True,
              help="The sphere's diameter in millimetres.")
@click.option("--rings", type=BoundedInt(1, MAX_RINGS), default=DEFAULT_RINGS, show_default=True,
              help="Rings of triangles from each tile's centre to its outline (how closely the mesh follows the sphere).")
@click.option("--relief-mm", type=float, default=None,
              help="Raise the tiles of the colour classes --raise-colour (default 0, the first colour) this many mm "
                   "above the ball, with vertical walls: 0 < relief <= a quarter of --size-mm.")
@click.option("--raise-colour", "raise_colours", type=int, multiple=True, metavar="CLASS",
              help="A colour class to raise with --relief-mm (repeatable; default 0).")
@click.option("--set", "settings", multiple=True, metavar="KEY=VALUE",
              help="A tiling option, e.g. samples=16 (points per edge of the outline).")
@click.pass_context
def sphere_mesh_command(ctx: click.Context, name: str, out: str, size_mm: float, rings: int,
                        relief_mm: float | None, raise_colours: tuple[int, ...], settings: tuple[str, ...]) -> None:
    """Write a tiling of the sphere as a printable mesh: one closed surface of triangles (every
    edge in two), the tiles' boundaries on it; .obj colours the tiles by kind; --relief-mm
    raises the tiles of colour class 0 (or --raise-colour) with vertical walls.

    \b
    Examples:
      tilekit sphere-mesh truncated-icosahedron -o ball.stl --size-mm 80
      tilekit sphere-mesh 3.4.4.4 -o rhombicuboctahedron.obj
      tilekit sphere-mesh 3.4.3.4 -o relief.stl --relief-mm 3
    """
    # start-up cost: the mesh writer loads NumPy, only when the command runs
    from tilekit.plugins.curved.mesh import write_mesh
    from tilekit.text import parse_settings

    state = ctx.find_root().obj
    tiling = state.catalogue().tiling(name)
    options = parse_settings(settings)
    if options:
        tiling = tiling.configure(**options)
    if raise_colours and relief_mm is None:
        raise click.UsageError("--raise-colour chooses the tiles --relief-mm raises: give --relief-mm too")
    tiles, triangles = write_mesh(tiling, out, size_mm=size_mm, rings=rings, relief_mm=relief_mm,
                                  raise_colours=raise_colours or (0,))
    click.echo(f"wrote {out} ({tiles} tiles, {triangles} triangles)")


@click.command(name="laves-types")
@click.argument("name")
@click.pass_context
def laves_types_command(ctx: click.Context, name: str) -> None:
    """List the isohedral types of a spherical Laves tiling's topology: one per subgroup of its
    symmetry group (up to conjugacy) that is transitive on its faces, with the tile's incidence
    symbol under that group, the tile's symmetries in it and its edge kinds. Each group is a
    value of --set group=... for tilekit render.

    \b
    Examples:
      tilekit laves-types '[3^4]'
      tilekit laves-types rhombic-dodecahedron
    """
    # start-up cost: the group code loads NumPy, only when the command runs
    from tilekit.errors import ParameterError
    from tilekit.plugins.curved.laves import LavesTiling, isohedral_types
    from tilekit.text import text_table

    tiling = ctx.find_root().obj.catalogue().tiling(name)
    if not isinstance(tiling, LavesTiling):
        raise ParameterError(f"{name} is not a Laves tiling of the curved family; laves-types takes one such as "
                             "[3.4.3.4], V4.6.6 or rhombic-dodecahedron")
    types = isohedral_types(tiling)
    rows = [(t.group, t.order, t.incidence_symbol, t.tile_symmetry, t.edge_kinds, ", ".join(t.same_symbol) or "-")
            for t in types]
    click.echo(f"[{tiling.configuration}]: {tiling.faces} faces, {len(types)} isohedral types")
    click.echo(text_table(["group", "order", "incidence symbol", "tile symmetry", "edges", "same symbol"], rows))
