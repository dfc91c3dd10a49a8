"""Help texts of the command line (`ldem ...`, `ldem study ...`)."""
import argparse


class HelpFormatter(argparse.ArgumentDefaultsHelpFormatter):
    """Each option's default once, at the end of its help, and only when it
    says something (not for flags, empty lists or options without one)."""

    def _get_help_string(self, action):
        if action.default in (None, False, "", [], argparse.SUPPRESS):
            return action.help
        return super()._get_help_string(action)
