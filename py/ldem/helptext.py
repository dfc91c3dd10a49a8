"""Help texts of the command line (`ldem ...`, `ldem study ...`), and its
parser, which the scripts of scripts/ share."""
import argparse
import dataclasses
import re

from .cube import CubeTest


EXIT_BAD_INPUT = 2  # every ldem command's and script's exit code for bad input


class ArgumentParser(argparse.ArgumentParser):
    """argparse with a one-line error (no usage dump) and exit code 2, and a
    negative number in any notation taken as the value it is (--eps-p -1e-5)."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        # argparse's own pattern knows -1 and -.5 but not -1e-5, which it took for an option and answered
        # "expected one argument" where the bounds should be said. Any "-" before a digit (or ".digit") is
        # a number here: no option of ldem looks like one.
        self._negative_number_matcher = re.compile(r"-\.?\d")

    def error(self, message):
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {message}\n")


def parameter_help(field, note: str = "", each: str = "") -> str:
    """The help of an option of a parameter, a field of ldem.CubeTest: the
    table's help, unit and domain (one choice says theirs), then note."""
    md = field.metadata
    unit = f" [{md['unit']}]" if md["unit"] else ""
    domain = "" if "choices" in md and not md.get("several") else f"; {each}{md['domain']}"
    return f"{md['help']}{unit}{domain}{note}".replace("%", "%%")


def add_parameter_option(p, field, option: str = "", note: str = "", **kw) -> None:
    """The option of one parameter, a field of ldem.CubeTest (its name, type,
    default, unit, help, domain and choices: pkg/ldem/Parameters.hpp's line);
    note: said after the table's help; kw replaces any of argparse's (a
    study's own default). Some of the choices (dampings) are one argument,
    comma-separated, that the core checks."""
    md = field.metadata
    choices = {"choices": md["choices"]} if "choices" in md and not md.get("several") else {}
    p.add_argument(option or "--" + field.name.replace("_", "-"),
                   **{"dest": field.name, "type": type(field.default), "default": field.default,
                      "metavar": None if choices else field.name.upper(), "help": parameter_help(field, note),
                      **choices, **kw})


def add_output_flags(p: argparse.ArgumentParser) -> None:
    """The options of what a run or a study writes, the same everywhere."""
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument("--figure-format", default="png", choices=("png", "pdf", "svg"),
                   help="format of the figures (pdf and svg: vector, for papers)")


class HelpFormatter(argparse.ArgumentDefaultsHelpFormatter):
    """Each option's default once, at the end of its help, and only when it
    says something (not for flags, empty lists or options without one)."""

    def _get_help_string(self, action):
        if action.default in (None, False, "", [], argparse.SUPPRESS):
            return action.help
        return super()._get_help_string(action)


def settings(pairs) -> dict:
    """--set NAME=VALUE pairs (ldem study, ldem run) as CubeTest fields of the right type."""
    fields = {f.name: f for f in dataclasses.fields(CubeTest)}
    out = {}
    for pair in pairs:
        name, sep, value = pair.partition("=")
        name = name.strip().replace("-", "_")
        if not sep or name not in fields:
            raise ValueError(f"--set takes NAME=VALUE with NAME a parameter of ldem cube --help (got '{pair}')")
        kind = type(fields[name].default)
        try:
            out[name] = kind(value)
        except ValueError:
            what = {int: "an integer", float: "a number"}[kind]
            raise ValueError(f"--set {name}: '{value}' is not {what}") from None
    return out
