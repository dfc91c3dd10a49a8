"""Why the large uniform cubes are weaker (issue 10, item 7).

    /usr/bin/python3 scripts/peak_ablation.py SIZE SEEDS [THREADS [RUNS]]   e.g. 0.48 1,2,3 1
      RUNS: load:variant pairs, e.g. uniform:rollers,triangular:base (default: every pair)
    /usr/bin/python3 scripts/peak_ablation.py --table RUNS.jsonl        the markdown table of those runs

One factor at a time on a cube (both loads), each run stopped past its peak,
one JSON line per run: peak, its
strain, damaged bars at the peak (pre-peak nonlinearity) and where the damage is
(mean height of the damaged-or-broken bars over H, and the share within one module
of the lower face)."""
import json, sys
import numpy as np


def table(path):
    """Per load and variant, the means over the seeds and their change against base."""
    runs = [json.loads(line) for line in open(path)]
    print("| load | variant | seeds | peak [MPa] | change | strain at peak | change | damaged / broken bars at "
          "the peak | energy error (max) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for load in dict.fromkeys(r["load"] for r in runs):
        group = lambda v: [r for r in runs if r["load"] == load and r["variant"] == v]
        base = group("base")
        b_peak, b_strain = np.mean([r["peak_MPa"] for r in base]), np.mean([r["strain_at_peak"] for r in base])
        for v in dict.fromkeys(r["variant"] for r in runs if r["load"] == load):
            g = group(v)
            peak, strain = np.mean([r["peak_MPa"] for r in g]), np.mean([r["strain_at_peak"] for r in g])
            print(f"| {load} | {v} | {len(g)} | {peak:.4f} | {100 * (peak / b_peak - 1):+.1f} % | {strain:.3e} | "
                  f"{100 * (strain / b_strain - 1):+.1f} % | {np.mean([r['damaged_at_peak'] for r in g]):.0f} / "
                  f"{np.mean([r['broken_at_peak'] for r in g]):.0f} | {max(r['energy_error'] for r in g):.1e} |")


if sys.argv[1] == "--table":
    table(sys.argv[2])
    sys.exit(0)

import ldem  # noqa: E402

size = float(sys.argv[1]); seeds = [int(s) for s in sys.argv[2].split(",")]
threads = int(sys.argv[3]) if len(sys.argv) > 3 else 0
VARIANTS = {"base": {}, "rollers": {"bottom_lateral": "free"}, "rate/2": {"strain_rate": 0.01},
            "rate*2": {"strain_rate": 0.04}, "no smooth start": {"ramp_time": 1e-9},
            "G_f per module": {"Gf_draw": "module"}}
runs = [(ld, v) for ld in ("uniform", "triangular") for v in VARIANTS]
if len(sys.argv) > 4:
    runs = [tuple(r.split(":")) for r in sys.argv[4].split(",")]
for load, name in runs:
    kw = VARIANTS[name]
    for seed in seeds:
        t = ldem.CubeTest(size=size, load=load, seed=seed, threads=threads, stop_at="load_loss",
                          final_strain=3e-4 if load == "uniform" else 2e-4, **kw)
        r = t.run()
        s, c = r.summary, r.curve
        i = int(np.argmin(np.abs(c["mean_strain"] - s["strain_at_peak"])))
        sim = r.sim
        bars = sim.lattice.bar_table()
        z0 = np.asarray(sim.lattice.z0)
        kappa = np.asarray(sim.kappa)
        hurt = kappa > sim.eps_p
        zmid = 0.5 * (z0[bars["n1"]] + z0[bars["n2"]]) / size
        out = {"load": load, "variant": name, "seed": seed, "peak_MPa": s["peak_stress_MPa"],
               "strain_at_peak": s["strain_at_peak"], "damaged_at_peak": int(c["damaged_bars"][i]),
               "broken_at_peak": int(c["broken_bars"][i]), "end_strain": float(c["mean_strain"][-1]),
               "hurt_mean_height": float(zmid[hurt].mean()) if hurt.any() else None,
               "hurt_share_lowest_module": float((zmid[hurt] < 1.0 / t.modules()).mean()) if hurt.any() else None,
               "energy_error": s["energy_balance_error"]}
        print(json.dumps(out), flush=True)
