"""Scene script: one concrete cube pulled in tension (LDEM_SPEC section 6).

Copy it, edit it, run it:
    /usr/bin/python3 scripts/cube_tension.py                       # defaults below
    /usr/bin/python3 scripts/cube_tension.py --size 0.24 --load triangular --seed 3
    yade-double -n -x scripts/cube_tension.py                      # the same inside YADE
    yade-double-batch scripts/size_effect.table scripts/cube_tension.py   # a sweep, one job per row
Each run writes curve.csv, summary.json, curve.png, energies.png, cracks.png and
bars.vtu into its folder, as `ldem cube` does. A bad value is one line and
exit code 2 (ldem.scene.exit_with).
"""
import ldem
from ldem.scene import exit_with, parameters


def main():
    # 1. Parameters: these defaults, or the yade-batch table row, or --name value.
    p = parameters(dict(size=0.12, load="uniform", seed=1, strain_rate=0.02, zeta=0.02, out="out/scenes"))

    # 2. The specimen and its loading. Every field of ldem.CubeTest can be set here:
    #    material (E, nu, rho, Gf_mean, Gf_cv, corr_length, eps_p, c_a), loading
    #    (load, strain_rate, ramp_time, top_lateral, bottom_lateral) and the run
    #    (zeta, dt, final_strain, stop_fraction, record_every, threads).
    test = ldem.CubeTest(size=p["size"], load=p["load"], seed=p["seed"], strain_rate=p["strain_rate"],
                         zeta=p["zeta"], threads=p["threads"])

    # 3. Run to split. The time-step loop is C++ (ldem._core.Simulation.run); a
    #    progress bar shows on a terminal.
    name = p["description"] or f"{p['load']}_{p['size']}m_seed{p['seed']}"
    result = ldem.run_cube(test, out=f"{p['out']}/{name}")

    # 4. The curve as numpy arrays (result.curve["stress_MPa"], ...), and the summary.
    strain, u = result.curve["mean_strain"], result.summary["U_ratio"]  # U_ratio None: not separated
    print(f"{name}: peak {result.peak_stress_MPa:.3f} MPa at strain {result.strain_at_peak:.3e}, "
          + ("not separated" if u is None else f"U_num/U_min {u:.2f}")
          + f", {len(strain)} curve rows, {result.wall_s:.1f} s")


if __name__ == "__main__":
    exit_with(main)
