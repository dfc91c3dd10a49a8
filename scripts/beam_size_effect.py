"""The size effect of the beams of scripts/gregoire2013.py (issue 13 item 5):
nominal strength sigma_N = 1.5 F S / (b D^2) (S = 2.5 D the span, b the
thickness) of every case; for each notch depth, Bažant's size-effect law
sigma_N = B f_t / sqrt(1 + D / D0) fitted to the cases (least squares on
1/sigma_N^2, which the law makes linear in D: 1/sigma_N^2 = (1 + D/D0) / (B f_t)^2),
B and D0 with 95 % confidence intervals, the brittleness number beta = D / D0 of
each size; for the unnotched beams, the slope of log sigma_N against log D (a
Weibull-type size effect is a straight line there, sigma_N ~ D^(-n/m)). The
same for the beams with a uniform G_f (cases_cv0/, `gregoire2013.py uniform`),
when they are there: what the random field does. Writes size_effect.md,
size_effect.csv, size_effect.png and cracks.png (the first specimen of each
beam) into the folder.

    /usr/bin/python3 scripts/beam_size_effect.py results/beams/gregoire2013
"""
import glob
import json
import os
import re
import sys

import numpy as np

from ldem import io

FT = 3.9e6
B_THICK = 0.05


def cases(folder: str, sub: str = "cases") -> list:
    out = []
    for path in sorted(glob.glob(os.path.join(folder, sub, "*", "summary.json"))):
        m = re.search(r"D([0-9.]+)_n([0-9.]+)_s(\d+)", path)
        s = json.load(open(path))
        if s.get("status") != "done":
            continue
        D = float(m.group(1)) / 1e3
        F = s["peak_stress_MPa"] * 1e6  # the force [N]: area 1
        out.append({"D_m": D, "notch": float(m.group(2)), "seed": int(m.group(3)), "F_N": F,
                    "sigma_N_MPa": 1.5 * F * 2.5 * D / (B_THICK * D * D) / 1e6})
    return out


def fit_sel(D: np.ndarray, s: np.ndarray):
    """Bažant's law by linear regression of Y = 1/sigma^2 on D: Y = a + c D with
    a = 1/(B f_t)^2 and D0 = a / c; 95 % intervals by the delta method."""
    A = np.column_stack([np.ones_like(D), D])
    Y = 1.0 / s ** 2
    coef, res, *_ = np.linalg.lstsq(A, Y, rcond=None)
    a, c = coef
    dof = max(len(D) - 2, 1)
    sigma2 = float(np.sum((Y - A @ coef) ** 2)) / dof
    cov = sigma2 * np.linalg.inv(A.T @ A)
    B = 1.0 / np.sqrt(a) / (FT / 1e6)
    D0 = a / c
    gB = np.array([-0.5 * a ** -1.5 / (FT / 1e6), 0.0])
    gD0 = np.array([1.0 / c, -a / c ** 2])
    t = 2.0 if dof > 30 else {1: 12.7, 2: 4.30, 3: 3.18, 4: 2.78, 5: 2.57}.get(dof, 2.1)
    return B, t * np.sqrt(gB @ cov @ gB), D0, t * np.sqrt(gD0 @ cov @ gD0)


def table(rows: list, title: str) -> tuple:
    """The lines of size_effect.md for one set of cases, and the fits by notch."""
    lines = [f"## {title} ({len(rows)} cases)", "",
             "| notch / D | D [mm] | specimens | sigma_N [MPa] (CV) | beta = D/D0 |", "|---|---|---|---|---|"]
    fits = {}
    for notch in sorted({r["notch"] for r in rows}):
        sel = [r for r in rows if r["notch"] == notch]
        D = np.array([r["D_m"] for r in sel])
        s = np.array([r["sigma_N_MPa"] for r in sel])
        if notch > 0 and len(set(D)) >= 3:
            fits[notch] = fit_sel(D, s)
        for d in sorted(set(D)):
            v = s[D == d]
            beta = f"{d / fits[notch][2]:.2f}" if notch in fits else "-"
            cv = f"{v.std(ddof=1) / v.mean():.3f}" if len(v) > 1 else "-"
            lines.append(f"| {notch:g} | {d * 1e3:g} | {len(v)} | {v.mean():.3f} ({cv}) | {beta} |")
    lines += ["", "Bažant's law sigma_N = B f_t / sqrt(1 + D/D0), f_t = 3.9 MPa:", ""]
    for notch, (B, dB, D0, dD0) in fits.items():
        lines.append(f"- notch {notch:g} D: B = {B:.3f} +- {dB:.3f}, D0 = {D0 * 1e3:.1f} +- {dD0 * 1e3:.1f} mm")
    plain = [r for r in rows if r["notch"] == 0]
    if len({r["D_m"] for r in plain}) >= 2:
        slope = np.polyfit(np.log([r["D_m"] for r in plain]), np.log([r["sigma_N_MPa"] for r in plain]), 1)[0]
        lines.append(f"- unnotched: d log sigma_N / d log D = {slope:.3f} (Weibull with n = 2 dimensions: -2/m)")
    return lines + [""], fits


def main(folder: str) -> None:
    rows = cases(folder)
    if not rows:
        sys.exit(f"{folder}: no finished case")
    lines, fits = table(rows, "Random G_f (CV 1), six specimens per beam")
    uniform, uniform_fits = cases(folder, "cases_cv0"), {}
    if uniform:
        more, uniform_fits = table(uniform, "Uniform G_f (CV 0), one specimen per beam")
        lines += more
    open(os.path.join(folder, "size_effect.md"), "w").write("# Size effect of the beams\n\n" + "\n".join(lines))
    io.write_table(os.path.join(folder, "size_effect.csv"), [dict(r, Gf_cv=1.0) for r in rows] +
                   [dict(r, Gf_cv=0.0) for r in uniform], ["Gf_cv", "D_m", "notch", "seed", "F_N", "sigma_N_MPa"])
    _figure(folder, rows, fits, uniform, uniform_fits)
    _cracks(folder)
    print("\n".join(lines))


def _figure(folder, rows, fits, uniform, uniform_fits):
    from ldem import plots  # noqa: F401  (the style)
    import matplotlib.pyplot as plt

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
           title="nominal strength against depth (lines: Bažant's law; dashed: uniform G_f)")
    ax.legend()
    plots.save(fig, os.path.join(folder, "size_effect.png"))


def _cracks(folder):
    """cracks.png: the crack pictures of the first specimen of each beam, D across, notch down."""
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


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join("results", "beams", "gregoire2013"))
