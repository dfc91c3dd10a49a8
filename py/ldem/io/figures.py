"""The pictures of a run (curve, energies, cracks) and a study case's central
slice (slice.npz, with its cracks.png). The slice is computed by
ldem.slicing, drawn by ldem.plots. Registers the writers "figures" and "slice"."""
from __future__ import annotations

import os

import numpy as np

from .. import parallel
from ..cube import label_words, labels
from ..slicing import central_slice
from .files import atomic
from .registry import register_writer

SLICE = "slice.npz"


class Figures:
    """curve.FMT and energies.FMT (rank 0), cracks.FMT (the central slice;
    under MPI every rank gives its bars, rank 0 draws) at the end of the run;
    FMT: run.options["figure_format"] (png, pdf or svg)."""

    def __init__(self, run):
        from .. import plots  # matplotlib only where pictures are drawn: `ldem cube --no-plots` starts faster

        self.out, self.fmt = run.out, run.options.get("figure_format", "png")
        if self.fmt not in plots.FIGURE_FORMATS:
            raise ValueError(f"unknown figure format '{self.fmt}' (expected one of {', '.join(plots.FIGURE_FORMATS)})")

    def finish(self, result) -> None:
        from .. import plots

        path = lambda name: os.path.join(self.out, f"{name}.{self.fmt}")  # noqa: E731
        if parallel.is_root():
            plots.curve_figure(result, path("curve"))
            plots.energy_figure(result, path("energies"))
        piece = central_slice(result.sim)
        if piece is not None:
            strain = label_words(labels(result.test)["strain"])[0]  # the specimen's own (a beam's deflection/D)
            plots.crack_figure_from_slice(*piece, path("cracks"), title=f"{result.test.describe()}\n"
                                          f"{strain} {result.curve['mean_strain'][-1]:.2e}")


def write_slice(path: str, segments, states) -> None:
    """The central slice of a run (ldem.slicing.central_slice), for study figures."""
    with atomic(path) as tmp:
        np.savez_compressed(tmp, segments=np.asarray(segments, dtype=np.float32), states=states)


def read_slice(path: str) -> tuple:
    with np.load(path) as z:
        return z["segments"], z["states"]


class Slice:
    """A study case's slice.npz (the central slice, whence the study's crack
    figures) and its cracks.png, titled run.options["title"]."""

    def __init__(self, run):
        self.out, self.title = run.out, run.options.get("title", "")

    def finish(self, result) -> None:
        from .. import plots

        piece = central_slice(result.sim)
        if piece is None:  # under MPI, a rank other than 0: its bars went to rank 0
            return
        seg, state = piece
        write_slice(os.path.join(self.out, SLICE), seg, state)
        plots.crack_figure_from_slice(seg, state, os.path.join(self.out, "cracks.png"),
                                      title=self.title or result.test.describe())


register_writer("figures", Figures, 10, "curve, energies and cracks pictures (figure_format: png, pdf or svg)")
register_writer("slice", Slice, 50, "slice.npz (the central slice a study draws) and its cracks.png")
