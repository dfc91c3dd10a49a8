"""The quarter-rate test of the predicted dashpot's step: per size and load, seeds 1-3,
P (default rate) against Q (a quarter of it): peak and fracture energy (uniform: at the
load loss; triangular: at the shorter run's last mean strain), each seed and the means;
and P against the committed study (the default step) where comparable."""
import csv, json, os, sys
import numpy as np

E = "/tmp/ev"
study = {(r["load"], r["size_m"], int(r["seed"])): r for r in csv.DictReader(open("/work/main/results/size-effect/cases.csv"))}

def load(d):
    rows = list(csv.DictReader(open(f"{d}/curve.csv")))
    s = json.load(open(f"{d}/summary.json"))
    col = lambda k: np.array([float(r[k]) for r in rows])
    return {"e": col("mean_strain"), "F": col("stress_MPa"), "Uf": col("fracture_J"), "s": s}

for load_ in ("uniform", "triangular"):
    for size in ("0.48", "0.96"):
        dp, de, sp, se, wp, wq, steps = [], [], [], [], [], [], []
        lines = []
        for seed in (1, 2, 3):
            P, Q = (f"{E}/{v}_{size}_{load_}_s{seed}" for v in "PQ")
            if not all(os.path.exists(f"{x}/summary.json") for x in (P, Q)):
                continue
            p, q = load(P), load(Q)
            if load_ == "uniform":
                ep, eq = p["s"]["load_loss"]["fracture_energy_J"], q["s"]["load_loss"]["fracture_energy_J"]
                until = None
            else:
                until = min(p["e"][-1], q["e"][-1])
                ep, eq = (float(np.interp(until, r["e"], r["Uf"])) for r in (p, q))
            pk_p, pk_q = p["s"]["peak_stress_MPa"], q["s"]["peak_stress_MPa"]
            dp.append(pk_p / pk_q - 1), de.append(ep / eq - 1)
            st = study[(load_, size, seed)]
            sp.append(pk_p / float(st["peak_stress_MPa"]) - 1)
            if load_ == "uniform":
                se.append(ep / float(st["U_loss_J"]) - 1)
            wp.append(p["s"]["wall_s"]), wq.append(q["s"]["wall_s"]), steps.append((p["s"]["steps"], int(st["steps"])))
            lines.append(f"  seed {seed}: peak {pk_p:.5g} / {pk_q:.5g} MPa ({dp[-1]*100:+.2f} %), energy {ep:.4g} / {eq:.4g} J "
                         f"({de[-1]*100:+.2f} %){'' if until is None else f' at mean strain {until:.4g}'}; "
                         f"against the study's step: peak {sp[-1]*100:+.2f} %"
                         + (f", U at load loss {se[-1]*100:+.2f} %" if se else "")
                         + f"; steps {steps[-1][0]} (study {steps[-1][1]}), walls {wp[-1]:.0f} / {wq[-1]:.0f} s; balance {p['s']['energy_balance_error']:.2g}")
        if not dp:
            continue
        n = len(dp)
        m = lambda x: np.mean(x) * 100
        sem = lambda x: (np.std(x, ddof=1) / np.sqrt(len(x)) * 100) if len(x) > 1 else float("nan")
        print(f"{size} m {load_} ({n} seeds): quarter-rate peak {m(dp):+.2f} % (SE {sem(dp):.2f}), energy {m(de):+.2f} % (SE {sem(de):.2f});"
              f" against the study's step: peak {m(sp):+.2f} %" + (f", U at load loss {m(se):+.2f} %" if se else ""))
        print("\n".join(lines))
