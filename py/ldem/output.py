"""Files of a run: the folder, the progress bar, summary.json, bars.vtu and the pictures."""
from __future__ import annotations

import os
import sys

import numpy as np

# Damage states, as in HillerborgLaw.hpp, with the study's colours.
UNDAMAGED, DAMAGED, BROKEN = 0, 1, 2
STATE_COLOURS = {UNDAMAGED: "cyan", DAMAGED: "orange", BROKEN: "red"}
STATE_NAMES = {UNDAMAGED: "undamaged", DAMAGED: "damaged", BROKEN: "broken"}


def prepare_dir(path: str) -> None:
    """Creates the output folder and checks it is writable, before any computing."""
    try:
        os.makedirs(path, exist_ok=True)
        probe = os.path.join(path, ".ldem-write-test")
        with open(probe, "w"):
            pass
        os.remove(probe)
    except OSError as e:
        raise ValueError(f"cannot write to output folder {path}: {e.strerror}") from None


class ProgressBar:
    """A tqdm bar over the mean strain, with stress and peak; silent off a terminal."""

    def __init__(self, final_strain: float, enabled=None):
        if enabled is None:
            enabled = sys.stderr.isatty()
        self._bar, self._peak, self._final = None, 0.0, final_strain
        if enabled:
            from tqdm import tqdm
            self._bar = tqdm(total=1000, unit="‰", desc="strain", file=sys.stderr,
                             bar_format="{desc}: {percentage:3.0f}%|{bar}| {postfix} [{elapsed}<{remaining}]")

    def update(self, p) -> None:
        if self._bar is None:
            return
        self._peak = max(self._peak, p.stress_bottom)
        self._bar.n = min(1000, int(1000 * p.mean_strain / self._final))
        self._bar.set_postfix_str(f"eps={p.mean_strain:.3e} sigma={p.stress_bottom * 1e-6:.3f} MPa "
                                  f"peak={self._peak * 1e-6:.3f} MPa broken={p.broken}", refresh=True)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()


def damage_states(kappa, eps_p, eps_r) -> np.ndarray:
    """0 undamaged (kappa <= eps_p), 1 damaged, 2 broken (kappa >= eps_r)."""
    s = np.where(kappa > eps_p, DAMAGED, UNDAMAGED)
    return np.where(kappa >= eps_r, BROKEN, s).astype(np.uint8)


def write_summary(result, out: str) -> None:
    result.save_summary(os.path.join(out, "summary.json"))


def write_vtu(sim, path: str) -> None:
    """Every bar as a VTK line cell with its damage state and kappa/eps_r (ParaView)."""
    import meshio

    lat = sim.lattice
    u = sim.displacement
    bars = lat.bar_table()
    points = np.column_stack([lat.x0, lat.y0, lat.z0]) + u
    kappa, eps_r = sim.kappa, sim.eps_r
    cells = [("line", np.column_stack([bars["n1"], bars["n2"]]).astype(np.int64))]
    mesh = meshio.Mesh(
        points, cells,
        point_data={"displacement": u},
        cell_data={
            "damage_state": [damage_states(kappa, sim.eps_p, eps_r).astype(np.int32)],
            "damage": [np.minimum(kappa / eps_r, 1.0)],
            "kappa": [kappa],
            "eps_r": [eps_r],
            "strain": [sim.bar_strain],
            "G_f": [sim.fracture_energy_field],
            "kind": [bars["kind"].astype(np.int32)],
        })
    meshio.write(path, mesh, file_format="vtu")


def write_outputs(result, out: str) -> None:
    from . import plots

    plots.curve_figure(result, os.path.join(out, "curve.png"))
    plots.energy_figure(result, os.path.join(out, "energies.png"))
    plots.crack_figure(result.sim, os.path.join(out, "cracks.png"),
                       title=f"{result.test.size:g} m cube, {result.test.load}, seed {result.test.seed}: "
                             f"mean strain {result.curve['mean_strain'][-1]:.2e}")
    write_vtu(result.sim, os.path.join(out, "bars.vtu"))
