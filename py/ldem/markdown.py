"""The cells, tables and sentences of the studies' markdown reports
(ldem.report and the mesh and refinement reports): plain text from plain data."""
from __future__ import annotations

from typing import Sequence


def stop_rule(p: dict) -> str:
    """What ends a run of parameters p, in words (an older run's parameters may lack a newer stop's)."""
    stop = p.get("stop_at", "separation")
    if stop == "past_peak":
        rule = f"{p['peak_stop_strain_ratio']:g} x the mean strain at the peak"
    else:
        rule = {"separation": "separation (no chain of intact bars joins the faces)", "load_loss": "load loss",
                "converged": f"separation, or U converged (growth below {p.get('converged_growth', 0.01):g} over "
                             f"the last doubling of the strain past load loss)"}[stop]
    return f"{p['load']}: {rule}, or mean strain {p['final_strain']:g}"


def num_cell(v, fmt) -> str:
    """A table cell: '-' for a value that does not exist (e.g. U_num of a run that did not separate)."""
    return "-" if v in ("", None) else format(float(v), fmt)


def mean_cv_cell(mean, cv, fmt: str = ".3f") -> str:
    """'mean (CV)', the CV '-' where it does not exist (one specimen: ldem.study.tables.mean_cv)."""
    return f"{format(float(mean), fmt)} ({num_cell(cv, '.3f')})"


def md_table(header: Sequence[str], rows: Sequence[Sequence]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(x) for x in r) + " |" for r in rows]
    return "\n".join(lines)


def pct(a, b) -> str:
    """a against b, in per cent with its sign."""
    return f"{100 * (a - b) / b:+.1f} %"


def tail_drive_words(p: dict) -> str:
    """What the drive does once the load is lost, for the report's table (runs
    before tail_drive was declared ran the fixed drive)."""
    drive = p.get("tail_drive", "fixed")
    if drive == "constant_velocity":
        return f"the drive keeps its velocity, {p['drive_velocity']:g} m/s (tail_drive constant_velocity)"
    speedup = f"the drive speeds up {p.get('loss_speedup', 1):g} times"
    if drive == "fixed":
        return speedup
    if drive != "adaptive":
        raise ValueError(f"the report has no words for tail_drive {drive!r}")
    pace = p.get("crack_pace", 1.0)  # runs before the pace was declared ran without it
    secant = p.get("crack_secant", 0.0)
    near = (f" or near the peak (secant below {secant:g} of the elastic, stress above {p['crack_band']:g} of the peak)"
            if secant > 0 else "")
    before = (f"; before the load loss at {pace:g} of the rate while cracks run and K/W > {p['crack_kinetic']:g}"
              f"{near}" if pace < 1 else "")
    return (f"{speedup}, then adaptively up to {p['tail_max_speedup']:g} times while no bar softens and the chains "
            f"are slack (tail_load {p['tail_load']:g}, tail_drag {p['tail_drag']:g}, tail_step {p['tail_step']:g}"
            f"{before}; docs/cube.md)")


def damping_words(ps) -> str:
    """The damping of the cases (their parameters ps), for the report's table:
    the relative tail and the sizes that had it (runs before tail_damping was
    declared damped the absolute velocity to the end)."""
    rel = [q for q in ps if q.get("tail_damping") == "relative"]
    where = "" if len(rel) == len(ps) else " at " + ", ".join(f"{s:g}" for s in sorted({q["size"] for q in rel})) + " m"
    tail = (f"; from the load loss on{where}, of each node's velocity less its mean over "
            f"{rel[0]['damping_filter_periods']:g} fundamental periods (tail_damping relative)" if rel else "")
    return f"zeta = {ps[0]['zeta']:g} on omega_1 (D_f = 2 zeta omega_1, mass-proportional){tail}"


def loss_fraction_words(ps) -> str:
    """The load loss's stress fraction of the cases (their parameters ps), and
    the loads and sizes that had another one (the study's triangular hinges)."""
    first, other = ps[0]["stop_fraction"], {}
    for q in ps:
        if q["stop_fraction"] != first:
            other.setdefault((q["stop_fraction"], q["load"]), set()).add(q["size"])
    words = "; ".join(f"{f:g} x peak for the {ld} cubes of " + ", ".join(f"{s:g}" for s in sorted(sizes)) + " m"
                      for (f, ld), sizes in sorted(other.items()))
    return f"{first:g} x peak" + (f" ({words})" if words else "")


def load_loss_words(ps) -> str:
    """The report's load-loss rule for the cases (their parameters ps; the first one's window and drive)."""
    p = ps[0]
    window = f"{p['split_window']:g} s" if p.get("split_window") else "two fundamental periods"
    return (f"bars broke and the stress averaged over {window} < {loss_fraction_words(ps)}; then "
            + tail_drive_words(p))


def cost_section(case_rows) -> list:
    """The Cost section: per load, the cases' wall times added up (what the
    study costs one case at a time), the longest, and the commits they ran on."""
    rows = []
    for load in dict.fromkeys(r["load"] for r in case_rows):
        mine = [r for r in case_rows if r["load"] == load]
        walls = [float(r["wall_s"]) for r in mine if r.get("wall_s", "") != ""]
        commits = sorted({str(r.get("git_commit") or "")[:7] or "?" for r in mine})
        threads = sorted({str(r.get("threads", "")) for r in mine})
        rows.append([load, str(len(mine)), ", ".join(threads), f"{sum(walls):.0f}", f"{max(walls, default=0):.0f}",
                     ", ".join(commits)])
    return ["## Cost", "", "The cases' wall times (`wall_s` in `cases.csv`, set-up to stop) added up, per load:", "",
            md_table(["load", "cases", "threads per case", "sum of wall times [s]", "longest case [s]", "commits"],
                     rows), ""]
