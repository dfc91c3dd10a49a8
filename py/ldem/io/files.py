"""The output folder and whole-or-absent files: what every writer of ldem.io
writes through."""
from __future__ import annotations

import contextlib
import os
import platform


@contextlib.contextmanager
def atomic(path: str):
    """Yields a temporary name beside path (same extension); renamed to path
    when the block ends without error, removed otherwise: a file is whole or
    absent, never cut by a full disk or a kill."""
    folder, base = os.path.split(path)
    tmp = os.path.join(folder, f".{base}.{os.getpid()}.tmp{os.path.splitext(base)[1]}")
    try:
        yield tmp
        os.replace(tmp, path)
    except BaseException as e:
        with contextlib.suppress(OSError):
            os.remove(tmp)
        if isinstance(e, OSError):
            raise naming(e, path) from e
        raise


def naming(e: OSError, path: str) -> OSError:
    """The same error, naming the file the user knows (not a temporary one)."""
    return OSError(e.errno, e.strerror or str(e), path)


def prepare_dir(path: str) -> None:
    """Creates the output folder and checks it is writable, before any computing."""
    try:
        os.makedirs(path, exist_ok=True)
        # A name of this process's own: every MPI rank checks the same folder at once.
        probe = os.path.join(path, f".ldem-write-test.{platform.node()}.{os.getpid()}")
        with open(probe, "w"):
            pass
        os.remove(probe)
    except OSError as e:
        raise ValueError(f"cannot write to output folder {path}: {e.strerror}") from None


def write_text(path: str, text: str) -> None:
    with atomic(path) as tmp, open(tmp, "w") as f:
        f.write(text)
