"""``tilekit search KIND`` (one subcommand per registered search) and ``tilekit runs``."""

from __future__ import annotations

import json
import sys
from typing import Any

import click

from tilekit.cli import base  # base.plugin_manager: tests replace it there
from tilekit.cli.base import (
    State,
    SuggestingGroup,
    _Stopped,
    cli,
    pass_state,
)
from tilekit.cli_types import INT64_MAX, RUN_ID, BoundedInt, FiniteFloat
from tilekit.errors import NotFoundError, ParameterError
from tilekit.text import format_value as _format_value
from tilekit.text import text_table as _table

# --------------------------------------------------------------------------- search / runs



class SearchGroup(SuggestingGroup):
    """``tilekit search KIND``: one subcommand per registered search, built from its SearchParams."""

    what = "search"

    def list_commands(self, ctx: click.Context) -> list[str]:
        from tilekit.plugins import searches

        return sorted(searches(base.plugin_manager()))

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        from tilekit.plugins import searches

        search = searches(base.plugin_manager()).get(cmd_name)
        return None if search is None else _search_command(search)



_PARAM_TYPES: dict[type, click.ParamType] = {int: BoundedInt(-INT64_MAX, INT64_MAX),
                                             float: FiniteFloat(1e300), str: click.STRING}


def _search_command(search: Any) -> click.Command:
    """A click command for one Search: an option per SearchParam plus executor options."""

    def callback(**kwargs: Any) -> None:
        ctx = click.get_current_context()
        state = ctx.find_object(State)
        executor = kwargs.pop("executor")
        workers = kwargs.pop("workers")
        resume = kwargs.pop("resume")
        scheduler = kwargs.pop("scheduler")
        given = {
            p.name: kwargs[p.name]
            for p in search.params
            if ctx.get_parameter_source(p.name) not in (click.core.ParameterSource.DEFAULT, None)
        }
        if resume is not None and given:
            raise ParameterError(
                f"--resume {resume} continues the run with its stored parameters; drop "
                + ", ".join("--" + k.replace("_", "-") for k in given)
            )
        params = None if resume is not None else {k: v for k, v in kwargs.items() if v is not None}
        _run_search_cli(state, search.name, params, executor, workers, resume, scheduler)

    from tilekit.search import describe_params

    options: list[click.Parameter] = []
    for p, line in zip(search.params, describe_params(search)):
        flag = "--" + p.name.replace("_", "-")
        help_text = line.split(": ", 1)[-1] + (" [required]" if p.required else "")
        if p.choices is not None:
            help_text += f" (one of {', '.join(map(str, p.choices))})"
        elif p.min is not None or p.max is not None:
            help_text += f" (range {p.min if p.min is not None else '-inf'}..{p.max if p.max is not None else 'inf'})"
        if p.type is bool:
            options.append(click.Option([f"{flag}/--no-{flag[2:]}", p.name], default=p.default,
                                        help=help_text, show_default=p.default is not None))
        else:
            options.append(click.Option([flag, p.name], type=_PARAM_TYPES.get(p.type, click.STRING),
                                        default=p.default, help=help_text,
                                        show_default=p.default is not None))
    options += [
        click.Option(["--executor"], type=click.Choice(["local", "process", "dask"]), default="local",
                     show_default=True, help="Where chunks run: this process, a process pool, or dask."),
        click.Option(["--workers"], type=BoundedInt(1, 4096), help="Parallel workers (process/dask)."),
        click.Option(["--scheduler"], metavar="ADDRESS",
                     help="A running dask scheduler (default: $TILEKIT_DASK_SCHEDULER, else a local cluster)."),
        click.Option(["--resume"], type=RUN_ID, metavar="RUN_ID",
                     help="Continue an interrupted or failed run, or join one that is running."),
    ]
    return click.Command(search.name, callback=callback, params=options,
                         help=f"{search.summary} (family {search.family}).\n\n\b\nExamples:\n"
                              f"  tilekit search {search.name}\n  tilekit search {search.name} --executor process --workers 2\n"
                              f"  tilekit search {search.name} --resume RUN_ID",
                         short_help=search.summary)


class _Reporter:
    """Progress of a run: a rich bar on a terminal, a plain line every few seconds otherwise."""

    def __init__(self, cat: Any, name: str) -> None:
        self.cat = cat
        self.name = name
        self.run_id: int | None = None
        self.tty = sys.stderr.isatty()
        self.bar: Any = None
        self.task: Any = None
        self.last_line = 0.0
        self.started = 0.0
        self.first_done: int | None = None
        self.rows = 0
        self.rows_at = -1e9

    def __call__(self, done: int, total: int) -> None:
        import time

        now = time.monotonic()
        if self.first_done is None:
            self.first_done, self.started = done, now
        if self.run_id is not None and (now - self.rows_at >= 1.0 or done == total):
            self.rows_at = now
            self.rows = self.cat.run(self.run_id).rows
        rows = self.rows
        if self.tty:
            if self.bar is None:
                from rich.progress import (
                    BarColumn,
                    MofNCompleteColumn,
                    Progress,
                    TextColumn,
                    TimeElapsedColumn,
                    TimeRemainingColumn,
                )

                self.bar = Progress(TextColumn("[bold]{task.description}"), BarColumn(), MofNCompleteColumn(),
                                    TextColumn("chunks, {task.fields[rows]} rows"), TimeElapsedColumn(),
                                    TimeRemainingColumn(), transient=False,
                                    console=__import__("rich.console").console.Console(stderr=True))
                self.bar.start()
                self.task = self.bar.add_task(f"run {self.run_id}: {self.name}", total=total, completed=done,
                                              rows=rows or 0)
            self.bar.update(self.task, completed=done, total=total, rows=rows or 0)
            return
        if now - self.last_line < 5.0 and done != total:
            return
        self.last_line = now
        rate = (done - (self.first_done or 0)) / max(now - self.started, 1e-9)
        left = f", about {(total - done) / rate:.0f} s left" if rate > 0 and done < total else ""
        click.echo(f"run {self.run_id}: {done}/{total} chunks, {rows or 0} rows, "
                   f"{rate:.2f} chunks/s{left}", err=True)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.stop()
            self.bar = None


def _run_search_cli(state: State, name: str, params: dict[str, Any] | None, executor: str,
                    workers: int | None, resume: int | None, scheduler: str | None = None) -> None:
    from tilekit import api
    from tilekit.signals import Terminated

    cat = state.catalogue()
    reporter = _Reporter(cat, name)

    def announce(run_id: int) -> None:
        reporter.run_id = run_id

    try:
        info = api.start_run(cat, name, params, executor=executor, workers=workers, resume=resume,
                             progress=reporter, pm=state.pm, on_run=announce, scheduler=scheduler)
    except KeyboardInterrupt as exc:
        reporter.close()
        code = 143 if isinstance(exc, Terminated) else 130
        what = "terminated" if code == 143 else "interrupted"
        if reporter.run_id is None:
            raise _Stopped(f"{what} before the run was created", code) from None
        info = cat.run(reporter.run_id)
        raise _Stopped(f"run {info.id} {what} after {info.progress} chunks (kept); continue it with: "
                       f"tilekit search {name} --resume {info.id}", code) from None
    finally:
        reporter.close()
    _print_run(info)


def _print_run(info: Any) -> None:
    click.echo(f"run {info.id}: {info.kind} {info.status} ({info.progress} chunks, {info.rows} rows, "
               f"{info.seconds:.2f} s wall, {info.worker_seconds:.2f} s worker time)")
    for key, value in (info.summary or {}).items():
        click.echo(f"  {key}: {_format_value(value)}")


@cli.group(cls=SearchGroup)
def search() -> None:
    """Run a search a family provides (tilekit search KIND --help for its options).

    \b
    Examples:
      tilekit search
      tilekit search vertex-species --executor process --workers 2
      tilekit search vertex-species --resume 3
    """


_RUN_ACTIONS = ("show", "cancel", "delete")


@cli.command(context_settings={"ignore_unknown_options": False})
@click.argument("words", nargs=-1, metavar="[show|cancel|delete] [RUN_ID]")
@click.option("--format", "fmt", type=click.Choice(["table", "json"]), default="table", show_default=True)
@pass_state
def runs(state: State, words: tuple[str, ...], fmt: str) -> None:
    """Search runs: status, progress, wall and worker time, summary.

    tilekit runs lists every run; tilekit runs RUN_ID (or runs show RUN_ID) shows one;
    tilekit runs cancel RUN_ID stops a run for good (its workers stop after their current
    chunk; recorded chunks are kept); tilekit runs delete RUN_ID removes a run with its
    chunks and results.

    \b
    Examples:
      tilekit runs
      tilekit runs show 3 --format json
      tilekit runs cancel 3
    """
    from tilekit import api

    action, run_id = _run_words(words)
    cat = state.catalogue()
    if action == "cancel":
        info = cat.cancel_run(run_id)
        click.echo(f"run {info.id} cancelled ({info.progress} chunks recorded)")
    elif action == "delete":
        click.echo(f"run {run_id} deleted ({cat.delete_run(run_id)} result rows)")
    elif fmt == "json":
        click.echo(json.dumps(api.run_data(cat, run_id), indent=2, ensure_ascii=False, default=str))
    elif run_id is None:
        _print_runs(cat.runs())
    else:
        _print_report(api.run_report(cat, run_id))


def _print_runs(infos: list[Any]) -> None:
    """The table of every run."""
    if not infos:
        click.echo("no runs yet", err=True)
        return
    rows = [[str(i.id), i.kind, i.status, i.progress, f"{i.seconds:.2f}", str(i.rows),
             json.dumps(i.summary, ensure_ascii=False) if i.summary else (i.error or "")] for i in infos]
    click.echo(_table(["id", "kind", "status", "progress", "seconds", "rows", "summary"], rows, {6: 70}))


def _print_report(report: Any) -> None:
    """One run in detail (tilekit.api.RunReport)."""
    info = report.info
    _print_run(info)
    click.echo(f"  params: {json.dumps(info.params, ensure_ascii=False)}")
    for k in ("created_at", "started_at", "finished_at"):
        value = getattr(info, k)
        if value is not None:
            click.echo(f"  {k}: {value.isoformat(sep=' ', timespec='seconds')}")
    if info.workers_alive or info.chunks_leased:
        click.echo(f"  workers alive: {info.workers_alive}, chunks leased: {info.chunks_leased}")
    if info.error:
        click.echo(f"  error: {info.error}")
    pending = [str(i) for i in report.pending]
    if pending:
        shown = ", ".join(pending[:40]) + (f", ... ({len(pending)} in all)" if len(pending) > 40 else "")
        click.echo(f"  pending chunks: {shown}")
    if report.chunk_rate is not None:
        click.echo(f"  rate: {report.chunk_rate:.2f} chunks/s, {report.row_rate:,.0f} rows/s (wall)")
    if report.worker_seconds_left is not None:
        per_chunk, left = report.worker_seconds_left
        click.echo(f"  worker time per chunk: {per_chunk:.3f} s; left: about {left:.0f} worker-seconds"
                   + (f" (about {left / info.workers_alive:.0f} s with {info.workers_alive} workers)"
                      if info.workers_alive else ""))
    click.echo(f"  results: {report.results}")


def _run_words(words: tuple[str, ...]) -> tuple[str, int | None]:
    """``()``, ``(N,)``, ``(ACTION, N)`` -> (action, run id); one-line errors otherwise."""
    def number(text: str) -> int:
        if not (text.isascii() and text.isdigit()) or len(text) > 18:
            raise ParameterError(f"run id {text!r} is not a run number (see tilekit runs)")
        return int(text)

    if not words:
        return "list", None
    if len(words) == 1:
        if words[0] in _RUN_ACTIONS:
            raise ParameterError(f"tilekit runs {words[0]} needs a RUN_ID")
        return "show", number(words[0])
    if len(words) == 2 and words[0] in _RUN_ACTIONS:
        return words[0], number(words[1])
    close = NotFoundError("runs action", words[0], _RUN_ACTIONS)
    raise ParameterError(f"{close}; usage: tilekit runs [show|cancel|delete] RUN_ID")
