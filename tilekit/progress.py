"""A progress bar on the terminal's stderr (rich) as a context manager that yields the function
advancing it; shared by the commands that stream long outputs (``tilekit render``, ``wang synth``)."""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator


@contextlib.contextmanager
def terminal_bar(description: str, total: float, count_text: str, *, shown: bool = True
                 ) -> Iterator[Callable[[int], None]]:
    """A bar ``description`` of ``total`` units, its count drawn by the rich format ``count_text``
    (e.g. ``"{task.completed:,} tiles"``), stopped on leaving; with ``shown`` false, no bar and
    an advance function that does nothing."""
    if not shown:
        yield lambda units: None
        return
    # rich loads only when a bar is drawn (start-up cost of every command otherwise)
    from rich.console import Console
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    bar = Progress(TextColumn("[bold]{task.description}"), BarColumn(), TextColumn(count_text),
                   TimeElapsedColumn(), console=Console(stderr=True))
    task = bar.add_task(description, total=total)
    bar.start()
    try:
        yield lambda units: bar.update(task, advance=units)
    finally:
        bar.stop()
