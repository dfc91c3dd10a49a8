"""Helpers for scene scripts (scripts/*.py) that run under /usr/bin/python3,
yade-double and yade-double-batch alike."""
from __future__ import annotations

import os
import sys

from .helptext import EXIT_BAD_INPUT, ArgumentParser
from .run_command import EXIT_FAILED


def in_yade() -> bool:
    """True inside yade-double (its Python has the yade package loaded)."""
    return "yade" in sys.modules


def parameters(defaults: dict, argv=None) -> dict:
    """The script's parameters: `defaults`, overridden by

    - the job's row of a yade-batch table (under yade-double-batch, which sets
      YADE_BATCH, PARAM_TABLE in older YADE; read with yade.utils.readParamsFromTable), or
    - `--name value` options on the command line (python3 script.py --size 0.24).

    Adds `description` (yade-batch's job description; empty outside a batch)
    and `threads` (yade's -j / --job-threads inside YADE, else all cores).
    """
    if os.environ.get("YADE_BATCH") or os.environ.get("PARAM_TABLE"):
        from yade import utils  # noqa: F401 (only under yade-double-batch)
        try:
            utils.readParamsFromTable(noTableOk=True, **defaults)
        except NameError as e:  # a column the script has no parameter for: a user's mistake, one line
            raise ValueError(f"the batch table: {e}") from None
        from yade.params import table
        values = {k: getattr(table, k) for k in defaults}
        from yade import O
        values["description"] = O.tags.get("description", "") if hasattr(O.tags, "get") else O.tags["description"]
    else:
        p = ArgumentParser(prog=os.path.basename(sys.argv[0]) or "scene",
                           description="scene script parameters (defaults in the script)")
        for k, v in defaults.items():
            p.add_argument("--" + k.replace("_", "-"), dest=k, type=type(v) if v is not None else str, default=v)
        values = vars(p.parse_args(sys.argv[1:] if argv is None else argv))
        values["description"] = ""
    if "threads" not in values:
        values["threads"] = _yade_threads() if in_yade() else 0
    return values


def _yade_threads() -> int:
    from yade import O  # noqa: F401
    return O.numThreads


def _input_error(e: Exception):
    """The one line that tells a user's mistake (a bad value: ValueError, as
    `ldem` reads it; a file that cannot be read: OSError; a YADE script run
    without YADE); None for anything else, a bug, whose traceback is wanted."""
    if isinstance(e, (ValueError, OSError)):
        return str(e)
    if isinstance(e, ModuleNotFoundError) and (e.name or "").split(".")[0] == "yade":
        return "YADE is not loaded: run this script with yade-double -n -x"
    return None


def exit_with(main, *args) -> None:
    """Runs main(*args) and ends the process with its exit code (None counts as
    0; argparse's SystemExit keeps its code; a bad input (ValueError, as `ldem`
    reads it) or a file that cannot be read (OSError) is one line on stderr and
    gives 2; any other exception, a bug, prints its traceback and gives 1).
    Scripts run by `yade-double -x` end this way, because a plain sys.exit there
    can hang in YADE's shutdown or drop into its shell."""
    code = EXIT_FAILED
    try:
        code = main(*args) or 0
    except SystemExit as e:
        code = e.code if isinstance(e.code, int) else EXIT_BAD_INPUT
    except Exception as e:
        line = _input_error(e)
        if line is None:
            import traceback
            traceback.print_exc()
        else:
            print(f"{os.path.basename(sys.argv[0]) or 'scene'}: error: {line}", file=sys.stderr)
            code = EXIT_BAD_INPUT
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)
