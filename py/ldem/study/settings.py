"""What the size-effect study sets beside CubeTest's defaults, and its cases
(`ldem study size-effect`, `ldem study damping`): the stop of each load, the
damping of the tail past the load loss, and the drive's pace."""
from __future__ import annotations

from typing import Iterable, List

from ..cube import CubeTest


# What ends a case of the size-effect study. The uniform cube separates: U_num.
# The triangular one hinges and never does. What the study reports of it (its
# table of peaks and strains at the peak, its curves and crack pictures) is in
# the record by 10 x its strain at the peak, where its stress is down to a few
# per cent of the peak, so by default it stops there (stop_at past_peak:
# dynamics/PastPeakStop.hpp). Its load loss (1 %) comes at 15-44 x (0.48-0.96
# m), 2.6 times the steps on the 0.96 m cubes: an option. Its U_final, once U
# has converged (dynamics/ConvergedStop.hpp), is another: the energy grows to
# mean strains of 0.1-0.2 as the columns beside the hinge break, which costs
# TRIANGULAR_CONVERGED_COST.
STUDY_STOP = {"uniform": "separation", "triangular": "past_peak"}
TRIANGULAR_STOPS = ("past_peak", "load_loss", "converged")
TRIANGULAR_CONVERGED_COST = ("about 55 min a 0.96 m case on 2 cores, 5.5 h for its six seeds, measured with the "
                             "fixed tail drive of 6863836 (results/archive/size-effect/study_in_an_hour.md); today's drive "
                             "bounds its drag and was not timed so far")


# Past its load loss a cube's upper half hangs from the drive, which then runs
# faster. From 0.72 m on the study damps each node's velocity less its own mean
# there (tail_damping relative, dynamics/MassDamping.hpp): the speed-up drags
# nothing, the uniform cubes take 0.39-0.42 of the steps, and U_num is within
# 0.13 % of the absolute damping's on all twelve specimens (measured at the
# constant rate, before the pace below). Below 0.72 m the tail breaks much of
# U_num and the two differ: relative damping moved the means by +1.7, +3.6 and
# -0.8 % at 0.12, 0.24 and 0.48 m, and on the two small cubes also run with no
# speed-up it was the farther from them (results/dynamics/relative_damping.md).
# So the absolute damping stays there (its drive bounds its drag).
# --set tail_damping=... sets it for every size.
RELATIVE_TAIL_FROM_M = 0.72


def tail_settings(size: float) -> dict:
    return {"tail_damping": "relative"} if size >= RELATIVE_TAIL_FROM_M else {}


# The study's drive is the cube's (cube.CUBE_DEFAULTS): it slows to a sixteenth
# of its rate near the peak and while a crack runs (dynamics/CrackPace.hpp). At
# a constant 0.02 /s a large cube snaps back at its peak while the drive keeps
# working: the 0.96 m cube's (seed 1) energy just past its load loss is 129.6 J,
# and 104.4 J at 0.000625 /s, where the rate no longer moves it
# (results/dynamics/cube_rate.md). The spec's test of a numerical aid is the
# quarter rate: paced, the 0.48 and 0.72 m cubes pass it in both loads (peaks
# within 0.08 %, energies within 1.61 %), and the 0.96 m cube's energy moves by
# +4.5 % at a mean strain of 5e-4 (+13.0 % without). It cost the study 1.71
# times its thread-seconds (results/archive/size-effect/study_paced/), the study with
# TRIANGULAR_TAIL_FRACTION below 0.77 of that (study_hinge/). --set
# crack_pace=1 runs the constant rate. A crack runs while bars soften and the
# specimen's own kinetic energy is above crack_kinetic x the work: at 1e-3 the
# triangular cube's ringing after its snap held the pace at a sixteenth for a
# third of its steps; at 1e-2 the quarter rate still passes (seed 1, 0.48 and
# 0.72 m, results/dynamics/cube_rate.md, "crack_kinetic 1e-2").

# Past its snap a triangular cube hangs on its hinge and softens slowly, at a
# tenth to a fiftieth of its peak, to the study's stop at 10 x its strain at the
# peak. From 0.72 m on (the relative tail) the tail's drive (AdaptiveDrive.hpp)
# takes over once the hinge carries less than a tenth of the peak: the study's
# triangular "load loss" is at stop_fraction 0.1 there (its columns in cases.csv).
# On the 0.72 m cube (seed 1) that takes 0.70 of the steps; U at the stop moves
# by +0.45 %, the stress past 3 x the strain at the peak by up to 1.1 % of the
# peak; a quarter of the rate moves it by up to 2.0 % (results/dynamics/cube_rate.md).
TRIANGULAR_TAIL_FRACTION = 0.1


def study_settings(size: float, load: str = "uniform", stop: str = "separation") -> dict:
    """What the size-effect study sets beside CubeTest's defaults for a cube of this size, load and stop."""
    tail = tail_settings(size)
    hinge = {"stop_fraction": TRIANGULAR_TAIL_FRACTION} if tail and (load, stop) == ("triangular", "past_peak") else {}
    return {**tail, **hinge}


def size_effect_tests(sizes: Iterable[float], seeds: int, loads: Iterable[str], triangular_stop: str = "past_peak",
                      **common) -> List[CubeTest]:
    """The study's cases; triangular_stop: what ends a triangular case (TRIANGULAR_STOPS)."""
    if triangular_stop not in TRIANGULAR_STOPS:
        raise ValueError(f"triangular_stop must be one of {', '.join(TRIANGULAR_STOPS)}, not {triangular_stop!r}")
    stop = {**STUDY_STOP, "triangular": triangular_stop}
    return [CubeTest(size=s, load=ld, seed=k, **{"stop_at": stop[ld], **study_settings(s, ld, stop[ld]), **common})
            for ld in loads for s in sizes for k in range(1, seeds + 1)]


def damping_tests(size: float, zetas: Iterable[float], loads: Iterable[str], seed: int = 1,
                  **common) -> List[CubeTest]:
    return [CubeTest(size=size, load=ld, seed=seed, zeta=z, **common) for ld in loads for z in zetas]
