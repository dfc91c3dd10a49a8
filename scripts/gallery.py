"""The example gallery of README: runs every examples/*.toml (unless its run
folder holds its finished run already: a study's case, ldem.study.Named) and puts its curve and its crack picture side by side
in doc/gallery/NAME.png.

    /usr/bin/python3 scripts/gallery.py [--runs out/gallery] [--out doc/gallery] [--threads 1] [--only NAME ...]
"""
import argparse
import glob
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.image  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

import ldem  # noqa: E402
from ldem import study  # noqa: E402
from ldem.runner import default_writers  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", default=os.path.join("out", "gallery"), help="run folders, one per example")
    ap.add_argument("--out", default=os.path.join(ROOT, "doc", "gallery"), help="where the pictures go")
    ap.add_argument("--threads", type=int, default=1, help="OpenMP threads per run")
    ap.add_argument("--only", nargs="+", metavar="NAME", help="these examples only (e.g. beam_3pb)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    examples = {os.path.splitext(os.path.basename(p))[0]: p
                for p in sorted(glob.glob(os.path.join(ROOT, "examples", "*.toml")))}
    tests = [study.Named(ldem.SpecimenTest.from_file(path, {"threads": args.threads}), name, default_writers(), "")
             for name, path in examples.items() if not args.only or name in args.only]
    for t, s in zip(tests, study.run_cases(tests, args.runs, progress=False, log=lambda line: None)):
        name, run = t.name, study.case_dir(args.runs, t)
        pictures = [matplotlib.image.imread(os.path.join(run, p)) for p in ("curve.png", "cracks.png")]
        ratios = [p.shape[1] / p.shape[0] for p in pictures]  # side by side at the same height
        fig, axes = plt.subplots(1, 2, figsize=(4.2 * sum(ratios), 4.6), gridspec_kw={"width_ratios": ratios})
        for ax, picture in zip(axes, pictures):
            ax.imshow(picture)
            ax.axis("off")
        fig.suptitle(f"examples/{name}.toml: peak {s['peak_stress_MPa']:.3f} MPa, {s['n_bars']} bars, "
                     f"{s['wall_s']:.0f} s on {s['threads']} thread(s)", fontsize=10)
        fig.tight_layout()
        fig.savefig(os.path.join(args.out, name + ".png"), dpi=110)
        plt.close(fig)
        print(f"{name}: peak {s['peak_stress_MPa']:.4f} MPa at strain {s['strain_at_peak']:.3e}, stop "
              f"{s['stop_reason']}, energy balance error {s['energy_balance_error']:.1e}, {s['wall_s']:.0f} s")


if __name__ == "__main__":
    main()
