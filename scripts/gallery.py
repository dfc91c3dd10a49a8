"""The example gallery of docs/specimens.md: runs every examples/*.toml (unless its run
folder holds its finished run already: a study's case, ldem.study.Named) and puts its curve and its crack picture side by side
in docs/gallery/NAME.png, at their own scale: one font size across the panels.

    /usr/bin/python3 scripts/gallery.py [--runs out/gallery] [--out docs/gallery] [--threads 1] [--only NAME ...]
                                        [--set NAME=VALUE ...]

README.md's pictures are two of these (docs/gallery/beam_3pb.png, cube_triangular.png);
tests/py/test_specimen_file.py runs this script (a short stretch: --set final_strain=...).
"""
import argparse
import glob
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.image  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import ldem  # noqa: E402
import ldem.plots  # noqa: E402,F401  (the figures' style, whose dpi the gallery keeps)
from ldem import study  # noqa: E402
from ldem.helptext import ArgumentParser, settings  # noqa: E402
from ldem.runner import default_writers  # noqa: E402
from ldem.scene import exit_with  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))


def side_by_side(pictures, title: str, path: str) -> None:
    """The pictures side by side at their own scale, one pixel for one (the same
    dpi as the run's figures: one font size across the panels), under a title."""
    height = max(p.shape[0] for p in pictures)
    padded = [np.pad(p[:, :, :3], (((height - p.shape[0]) // 2, (height - p.shape[0] + 1) // 2), (0, 0), (0, 0)),
                     constant_values=1.0) for p in pictures]  # centred, on white
    strip = np.hstack(padded)
    dpi, title_px = plt.rcParams["savefig.dpi"], 40
    fig = plt.figure(figsize=(strip.shape[1] / dpi, (strip.shape[0] + title_px) / dpi), dpi=dpi)
    ax = fig.add_axes((0.0, 0.0, 1.0, strip.shape[0] / (strip.shape[0] + title_px)))
    ax.imshow(strip, interpolation="none")
    ax.axis("off")
    fig.suptitle(title, y=1.0 - 0.25 * title_px / (strip.shape[0] + title_px), va="top")
    fig.savefig(path, dpi=dpi, bbox_inches=None)
    plt.close(fig)


def main() -> None:
    ap = ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", default=os.path.join("out", "gallery"), help="run folders, one per example")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "gallery"), help="where the pictures go")
    ap.add_argument("--threads", type=int, default=1, help="OpenMP threads per run")
    ap.add_argument("--only", nargs="+", metavar="NAME", help="these examples only (e.g. beam_3pb)")
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                    help="a parameter over every file's, as ldem run's --set (e.g. final_strain=1e-4 for a short stretch)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    examples = {os.path.splitext(os.path.basename(p))[0]: p
                for p in sorted(glob.glob(os.path.join(ROOT, "examples", "*.toml")))}
    overrides = {"threads": args.threads, **settings(args.set)}
    tests = [study.Named(ldem.SpecimenTest.from_file(path, overrides), name, default_writers(), "")
             for name, path in examples.items() if not args.only or name in args.only]
    for t, s in zip(tests, study.run_cases(tests, args.runs, progress=False, log=lambda line: None)):
        name, run = t.name, study.case_dir(args.runs, t)
        pictures = [matplotlib.image.imread(os.path.join(run, p)) for p in ("curve.png", "cracks.png")]
        # the peak in the specimen's own words (its stress label: "load F [MN]", "F/(bD) [MPa]", ...)
        title = (f"examples/{name}.toml: peak {s['peak_stress_MPa']:.4g} ({s['labels']['stress']}), "
                 f"{s['n_bars']} bars, {s['wall_s']:.0f} s on {s['threads']} thread(s)")
        side_by_side(pictures, title, os.path.join(args.out, name + ".png"))
        print(f"{name}: peak {s['peak_stress_MPa']:.4g} ({s['labels']['stress']}) at {s['strain_at_peak']:.3e} "
              f"({s['labels']['strain']}), stop {s['stop_reason']}, energy balance error "
              f"{s['energy_balance_error']:.1e}, {s['wall_s']:.0f} s")


if __name__ == "__main__":
    exit_with(main)
