"""Help texts of the command line (`ldem ...`, `ldem study ...`)."""
import argparse


def add_parameter_option(p, field, option: str = "", note: str = "", **kw) -> None:
    """The option of one parameter, a field of ldem.CubeTest (its name, type,
    default, unit, help, domain and choices: pkg/ldem/Parameters.hpp's line);
    note: said after the table's help; kw replaces any of argparse's (a
    study's own default)."""
    md = field.metadata
    unit = f" [{md['unit']}]" if md["unit"] else ""
    choices = {"choices": md["choices"]} if "choices" in md else {}
    domain = "" if choices else f"; {md['domain']}"
    p.add_argument(option or "--" + field.name.replace("_", "-"),
                   **{"dest": field.name, "type": type(field.default), "default": field.default,
                      "metavar": None if choices else field.name.upper(),
                      "help": f"{md['help']}{unit}{domain}{note}".replace("%", "%%"), **choices, **kw})


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
