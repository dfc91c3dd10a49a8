"""The studies of `ldem study`, registered by name: each study's module ends
with register(Study(...)) (its options and its run beside its cases, tables
and report), and `ldem study` builds one sub-command per registered study, in
the order they were registered (study.command imports them)."""
from __future__ import annotations

import argparse
from dataclasses import dataclass
from typing import Callable, Dict


@dataclass(frozen=True)
class Study:
    name: str  # the sub-command: ldem study NAME
    line: str  # what it does, in one line (`ldem study` lists them; NAME --help starts with it)
    add_arguments: Callable[[argparse.ArgumentParser], None]
    run: Callable[[argparse.Namespace], int]  # the exit code; ValueError for bad input (one line, exit 2)
    description: str = ""  # more than the line, for NAME --help


STUDIES: Dict[str, Study] = {}


def register(study: Study) -> Study:
    if study.name in STUDIES:
        raise ValueError(f"two studies named {study.name!r}")
    STUDIES[study.name] = study
    return study
