"""`python -m ldem`, `ldem` of a pip installation (console) and py/bin/ldem:
the handlers of SIGINT and SIGTERM first, then the command line's imports
(numpy, the core, the studies, matplotlib: seconds on a busy machine)."""
import sys

from .signals import exit_while_starting


def console() -> None:
    exit_while_starting()
    from .cli import main

    sys.exit(main())


if __name__ == "__main__":
    console()
