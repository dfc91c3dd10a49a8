"""Help texts of the command line (`ldem ...`, `ldem study ...`)."""
import argparse


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
