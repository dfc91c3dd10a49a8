"""`ldem bench`: the ldem-bench program (pkg/tools/ldem_bench.cpp) found and run."""
from __future__ import annotations

import os
import shutil
import subprocess


def bench_program() -> str:
    """The ldem-bench program: beside the installed package's command, or in the build tree."""
    here = os.path.dirname(os.path.abspath(__file__))
    for candidate in (os.path.join(here, "..", "..", "pkg", "ldem-bench"), shutil.which("ldem-bench")):
        if candidate and os.access(candidate, os.X_OK):
            return candidate
    raise ValueError("ldem-bench not found: run install.sh (it builds and installs it)")


def cmd_bench(args) -> int:
    """One line of JSON from ldem-bench (a separate program, so that its peak
    resident memory is the run's own and no interpreter is counted)."""
    for name in ("modules", "steps", "repeats"):
        if getattr(args, name) < 1:
            raise ValueError(f"--{name} must be at least 1")
    if args.threads < 0:
        raise ValueError("--threads must be >= 0")
    cmd = [bench_program(), "--modules", str(args.modules), "--steps", str(args.steps),
           "--threads", str(args.threads), "--repeats", str(args.repeats)]
    if args.damaged:
        cmd += ["--damaged", "1"]
    return subprocess.run(cmd).returncode
