"""Progress on a terminal: a bar over the mean strain for one run, a bar over
cases for a study. Silent off a terminal."""
from __future__ import annotations

import sys


def _enabled(enabled) -> bool:
    return sys.stderr.isatty() if enabled is None else bool(enabled)


class ProgressBar:
    """A tqdm bar over the mean strain, with stress, peak and the energy
    balance so far, flagged as the summary flags it (flagged()): an observer
    of CubeTest.run. energy_scale: U_min, the energy of the cheapest plane
    crack (E[G_f] x the ligament; 0: none declared)."""

    def __init__(self, final_strain: float, enabled=None, energy_tolerance: float = 0.01,
                 energy_scale: float = 0.0):
        self._bar, self._peak, self._final = None, 0.0, final_strain
        self._tol, self._energy, self._residual = energy_tolerance, 0.0, 0.0
        self._scale = energy_scale
        if _enabled(enabled):
            from tqdm import tqdm
            self._bar = tqdm(total=1000, unit="‰", desc="strain", file=sys.stderr,
                             bar_format="{desc}: {percentage:3.0f}%|{bar}| {postfix} [{elapsed}<{remaining}]")

    def __call__(self, row: dict) -> None:
        if self._bar is None:
            return
        self._peak = max(self._peak, row["stress_MPa"])
        self._bar.n = min(1000, int(1000 * row["mean_strain"] / self._final))
        self._bar.set_postfix_str(f"eps={row['mean_strain']:.3e} sigma={row['stress_MPa']:.3f} MPa "
                                  f"peak={self._peak:.3f} MPa broken={row['broken_bars']} "
                                  f"balance={self.balance(row):.1e}"
                                  + (" ENERGY ERROR" if self.flagged() else ""), refresh=True)

    def balance(self, row: dict) -> float:
        """The energy balance error so far, as the summary computes it: the
        largest |W - K - E - F - D| over the rows, over the largest energy in
        play (W, or K + E + F + D where it is larger)."""
        total = row["kinetic_J"] + row["elastic_J"] + row["fracture_J"] + row["damping_J"]
        self._energy = max(self._energy, row["external_work_J"], total)
        residual = row["external_work_J"] - total
        self._residual = max(self._residual, abs(residual))
        return self.error()

    def error(self) -> float:
        return self._residual / self._energy if self._energy > 0 else 0.0

    def flagged(self) -> bool:
        """The summary's rule, largest residual > tolerance x the largest
        energy in play, where the summary's energy is the whole run's: until
        the energy so far passes U_min (about what a run puts in to separate
        its specimen) the residual is weighed against U_min. A residual of
        the first records, large only against the little energy in play then
        (1.2e-9 J at strain 6e-8 on a 0.06 m cube: 8.7 % of it, 3e-9 of its
        U_min), is then no alarm, as it is none in the summary at the end."""
        return self._residual > self._tol * max(self._energy, self._scale)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()


class CaseProgress:
    """Overall progress over the cases of a study."""

    def __init__(self, total: int, done: int, enabled=None):
        self._bar = None
        if _enabled(enabled):
            from tqdm import tqdm
            self._bar = tqdm(total=total, initial=done, unit="case", desc="study", file=sys.stderr)

    def step(self) -> None:
        if self._bar is not None:
            self._bar.update(1)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
