"""docs/architecture.png: the layers of the ldem package, read from the one
place they are declared and checked, tests/py/test_architecture.py (LAYERS).

    /usr/bin/python3 dev/architecture_figure.py
"""
import ast
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import FancyArrowPatch, FancyBboxPatch  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ROLES = ["C++ core (pkg/): lattice, law, random field, integrator, specimen, loop",
         "specimen and run: returns data", "writers by name, the central slice, pictures, reports (from data)",
         "a run given its writers", "studies of any test: cases, executors, cubes, beams, ablation",
         "the edges: command line, scene scripts"]


def layers():
    tree = ast.parse(open(os.path.join(ROOT, "tests", "py", "test_architecture.py")).read())
    for node in tree.body:
        if isinstance(node, ast.Assign) and getattr(node.targets[0], "id", "") == "LAYERS":
            return [sorted(m.replace("ldem.", "") for m in layer) for layer in ast.literal_eval(node.value)]
    raise SystemExit("LAYERS not found in tests/py/test_architecture.py")


def main():
    ls = layers()
    fig, ax = plt.subplots(figsize=(9.5, 0.95 * len(ls) + 0.6))
    for i, (mods, role) in enumerate(zip(ls, ROLES)):
        y = i * 1.0
        ax.add_patch(FancyBboxPatch((0.02, y + 0.12), 0.96, 0.66, boxstyle="round,pad=0.01",
                                    fc=plt.cm.Blues(0.2 + 0.12 * i), ec="#335"))
        ax.text(0.04, y + 0.52, f"layer {i}", fontsize=9, color="#223", va="center")
        ax.text(0.16, y + 0.55, "   ".join(mods), fontsize=11, weight="bold", va="center", family="monospace")
        ax.text(0.16, y + 0.28, role, fontsize=8.5, va="center", color="#333")
        if i:
            ax.add_patch(FancyArrowPatch((0.9, y + 0.12), (0.9, y - 0.22), arrowstyle="-|>", mutation_scale=12,
                                         color="#335"))
    ax.text(0.92, len(ls) - 0.1, "imports go down only", fontsize=8, ha="right", color="#335")
    ax.set_xlim(0, 1), ax.set_ylim(-0.05, len(ls) + 0.05)
    ax.axis("off")
    fig.tight_layout()
    out = os.path.join(ROOT, "docs", "architecture.png")
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
