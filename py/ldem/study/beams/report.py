"""The beams' figures (reads the tables of ldem.study.beams.tables and the cases'
pictures; computes nothing). Their comparison with the measurements is
ldem.study.beams.comparison; the command line, ldem.study.beams."""
from __future__ import annotations

import glob
import os
import re

import numpy as np

from .cases import DEPTHS, FT, NOTCHES


def curves_figure(out: str, found: dict) -> None:
    """curves.png: load against CMOD of every seed, a panel per depth
    (found: write_curve_tables's (D, notch) -> {seed: curve})."""
    from ... import plots
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(13, 4), sharey=False)
    for ax, D in zip(axes, DEPTHS):
        for notch, colour in zip(NOTCHES, ("C0", "C1", "C2")):
            for seed, c in found.get((D, notch), {}).items():
                ax.plot(c["cmod_m"] * 1e3, c["stress_MPa"] * 1e3, colour, lw=0.8, alpha=0.7,
                        label=f"notch {notch:g} D" if seed == 1 else None)
        ax.set(title=f"D = {D * 1e3:g} mm", xlabel="CMOD [mm]", ylabel="load [kN]")
        ax.legend()
    plots.save(fig, os.path.join(out, "curves.png"))


def size_effect_figure(folder, rows, fits, uniform, uniform_fits) -> None:
    """size_effect.png: sigma_N of every case against D, Bažant's law fitted."""
    from ... import plots
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    fig, ax = plt.subplots()
    for k, notch in enumerate(sorted({r["notch"] for r in rows})):
        sel = [r for r in rows if r["notch"] == notch]
        D = np.array([r["D_m"] for r in sel]) * 1e3
        ax.plot(D, [r["sigma_N_MPa"] for r in sel], "o", color=f"C{k}", alpha=0.5, label=f"notch {notch:g} D")
        flat = [r for r in uniform if r["notch"] == notch]
        if flat:
            ax.plot([r["D_m"] * 1e3 for r in flat], [r["sigma_N_MPa"] for r in flat], "x", color=f"C{k}", ms=8,
                    label="uniform G_f" if k == 0 else None)
        d = np.geomspace(D.min() / 1.5, D.max() * 1.5, 50)
        for fit, style in ((fits.get(notch), "-"), (uniform_fits.get(notch), "--")):
            if fit:
                ax.plot(d, fit[0] * FT / 1e6 / np.sqrt(1 + d / (fit[2] * 1e3)), style, color=f"C{k}", lw=1)
    ax.set(xscale="log", yscale="log", xlabel="D [mm]", ylabel="sigma_N = 1.5 F S / (b D^2) [MPa]",
           title="nominal strength against depth (lines: Bažant's law" + ("; dashed: uniform G_f)" if uniform else ")"))
    for axis in (ax.xaxis, ax.yaxis):  # plain numbers: a decade or less spans these axes, 2 x 10^0 reads badly
        axis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
        axis.set_minor_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    ax.legend()
    plots.save(fig, os.path.join(folder, "size_effect.png"))


def cracks_mosaic(folder) -> None:
    """cracks.png: the crack pictures of the first specimen of each beam, D across, notch down."""
    from ... import plots  # noqa: F401  (the style)
    import matplotlib.image
    import matplotlib.pyplot as plt

    pictures = sorted(glob.glob(os.path.join(folder, "cases", "D*_n*_s1", "cracks.png")))
    if not pictures:
        return
    key = lambda p: tuple(float(x) for x in re.search(r"D([0-9.]+)_n([0-9.]+)_s1", p).groups())  # noqa: E731
    Ds, notches = sorted({key(p)[0] for p in pictures}), sorted({key(p)[1] for p in pictures})
    fig, axes = plt.subplots(len(notches), len(Ds), figsize=(5 * len(Ds), 2.3 * len(notches)), squeeze=False)
    for ax in axes.flat:
        ax.axis("off")
    for p in pictures:
        D, notch = key(p)
        ax = axes[notches.index(notch), Ds.index(D)]
        ax.imshow(matplotlib.image.imread(p))
        ax.set_title(f"D = {D:g} mm, notch {notch:g} D, seed 1", fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "cracks.png"), dpi=100)
    plt.close(fig)

