"""`ldem study`: one sub-command per registered study (ldem.study.registry;
ldem.study imports every study's module, in the order of the list), each
with the options its module adds; without a study, the list of them."""
from __future__ import annotations

import argparse

from ..helptext import HelpFormatter
from .registry import STUDIES  # filled as ldem.study imports the studies' modules


def study_lines() -> str:
    width = max(len(name) for name in STUDIES)
    return "".join(f"  {name:{width}s}  {s.line}\n" for name, s in STUDIES.items())


def cmd_list(args) -> int:
    print("ldem study NAME --help says more of each:\n" + study_lines(), end="")
    return 0


def add_parser(sub) -> None:
    p = sub.add_parser("study", help="the studies: many tests, resumable, in parallel, aggregated "
                                     "(ldem study lists them)",
                       description="Runs many tests (resumable, in parallel) and aggregates them. The studies:\n"
                                   + study_lines(), formatter_class=argparse.RawDescriptionHelpFormatter)
    p.set_defaults(func=cmd_list)
    kinds = p.add_subparsers(dest="study", metavar="STUDY", parser_class=type(p))
    for name, s in STUDIES.items():
        q = kinds.add_parser(name, help=s.line.replace("%", "%%"), formatter_class=HelpFormatter,
                             description=s.description or s.line)  # (argparse %-formats help, not descriptions)
        s.add_arguments(q)
        q.set_defaults(func=s.run)
