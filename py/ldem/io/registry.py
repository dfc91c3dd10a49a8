"""Writers by name, as meshio's register_format: each writer module ends with
its register_writer calls, and a run is given a list of names. A new writer
is a new module of ldem.io; no runner changes.

A writer is a class built with a Run (what it may write about) and an output
folder; it may define
    __call__(row)    an observer of test.run: given each curve row
    finish(result)   the run is done: its final files
    failed(summary)  the run failed or was interrupted (summary says which)
    close()          always, last
Writers finish in their registered rank (the summary last: "done" in
summary.json means every file is written)."""
from __future__ import annotations

import dataclasses
from typing import Dict, List, Sequence

_WRITERS: Dict[str, tuple] = {}  # name -> (rank, class, one line of help)


@dataclasses.dataclass
class Run:
    """What a writer may need: the test, its specimen, the rows recorded
    before a restart, and the run's options (snapshots, figure_format,
    checkpoint_every, checkpoint_seconds, wall_before, title)."""
    test: object
    sim: object
    out: str
    previous: list = dataclasses.field(default_factory=list)
    options: dict = dataclasses.field(default_factory=dict)


def register_writer(name: str, cls, rank: int, doc: str) -> None:
    """cls(run) writes into run.out; rank orders the writers (low first)."""
    _WRITERS[name] = (rank, cls, doc)


def writer_names() -> List[str]:
    return sorted(_WRITERS, key=lambda n: _WRITERS[n][0])


def describe_writers() -> str:
    return "\n".join(f"  {n:<11} {_WRITERS[n][2]}" for n in writer_names())


def check_writers(names: Sequence[str]) -> List[str]:
    """names in rank order; an unknown name is a ValueError naming the known ones."""
    unknown = [n for n in names if n not in _WRITERS]
    if unknown:
        raise ValueError(f"unknown writer{'s' if len(unknown) > 1 else ''} {', '.join(map(repr, unknown))} "
                         f"(known: {', '.join(writer_names())})")
    return sorted(dict.fromkeys(names), key=lambda n: _WRITERS[n][0])


def open_writers(names: Sequence[str], run: Run) -> list:
    """The writers of names, built for run, in rank order."""
    return [_WRITERS[n][1](run) for n in check_writers(names)]
