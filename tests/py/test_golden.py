"""Pinned results (tests/golden/, written by tests/golden/update.py): the default
0.12 m cube, uniform to separation and triangular to mean strain 0.002, on one
thread, must give exactly the golden summary, energies and curve (bitwise), and
2 and 3 threads exactly the same curve on a shorter run (past the peak,
with bars broken). A change of the physics updates the golden files in the same
commit, with the reason in its message (README, Tests)."""
import json
import os

import numpy as np
import pytest

import ldem
from conftest import load_file

golden = load_file("golden_update", "tests", "golden", "update.py")

# Mean strains of the shorter runs: past the peak (uniform 1.64e-4, triangular
# 1.71e-4), 133 and 110 bars broken; 38,283 and 85,441 steps.
SHORT_STRAIN = {"cube_0.12_uniform_s1": 2.5e-4, "cube_0.12_triangular_s1": 2.0e-4}
REGENERATE = "if the physics changed on purpose, run tests/golden/update.py and commit the files with the reason"


def _load_golden(name):
    js, csv = golden.golden_paths(name)
    with open(js) as f, open(csv, "rb") as g:
        return json.load(f), g.read()


@pytest.fixture(scope="module")
def one_thread(tmp_path_factory):
    """Each golden case on one thread, run once for the module: (pinned dict, curve.csv bytes, result)."""
    runs = {}

    def get(name):
        if name not in runs:
            out = str(tmp_path_factory.mktemp(name))
            result = golden.run(name, 1, out)
            with open(os.path.join(out, "curve.csv"), "rb") as f:
                runs[name] = (golden.pinned(result), f.read(), result)
        return runs[name]
    return get


@pytest.mark.parametrize("name", list(golden.CASES))
def test_one_thread_matches_golden_exactly(name, one_thread):
    want, want_csv = _load_golden(name)
    got, got_csv, _ = one_thread(name)
    differ = {k: (want.get(k), got.get(k)) for k in set(want) | set(got) if want.get(k) != got.get(k)}
    assert not differ, f"{name}: golden (want, got) differ: {differ}; {REGENERATE}"
    if got_csv != want_csv:
        a, b = want_csv.decode().splitlines(), got_csv.decode().splitlines()
        first = next((i for i, (x, y) in enumerate(zip(a, b)) if x != y), min(len(a), len(b)))
        pytest.fail(f"{name}: curve.csv differs from line {first + 1} ({len(a)} golden lines, {len(b)} now): "
                    f"{a[first] if first < len(a) else None!r} != {b[first] if first < len(b) else None!r}; "
                    f"{REGENERATE}")


@pytest.mark.parametrize("threads", [2, 3])
@pytest.mark.parametrize("name", list(golden.CASES))
def test_more_threads_give_the_same_bits(name, threads, one_thread, tmp_path):
    """The same rows, bit for bit, as the one-thread run up to SHORT_STRAIN (the
    full runs on 2 and 3 threads were compared by update.py when it wrote the files)."""
    _, _, full = one_thread(name)
    short = golden.run(name, threads, str(tmp_path), final_strain=SHORT_STRAIN[name])
    assert short.summary["stop_reason"] == "final_strain"
    assert short.curve["broken_bars"][-1] > 100  # past the peak, the cracking well under way
    m = len(short.curve["step"])
    if short.curve["step"][-1] not in full.curve["step"]:
        m -= 1  # the stop's own row, off the record grid
    assert m > 150
    for col in ldem.CURVE_COLUMNS:
        assert np.array_equal(short.curve[col][:m], full.curve[col][:m]), col
    # The peak came before SHORT_STRAIN: tracked at every step, it is the same bits.
    for k in ("peak_stress_MPa", "strain_at_peak", "edge_strain_at_peak", "dt_s", "omega1_rad_s", "omega_d_rad_s",
              "omega_max_rad_s", "clamped_bars"):
        assert short.summary[k] == full.summary[k], k


def test_summary_gives_the_step_over_the_undamped_limit(one_thread):
    """dt / (2/omega_max): at the defaults dt_safety 0.9 of 2/omega_max itself, which the
    dashpots read at the predicted velocity leave whole while zeta_high <= 0.5 (docs/performance.md)."""
    _, _, run = one_thread("cube_0.12_uniform_s1")
    s = run.summary
    assert s["dt_over_undamped_limit"] == pytest.approx(s["dt_s"] * s["omega_max_rad_s"] / 2, rel=1e-15)
    assert f"{s['dt_over_undamped_limit']:.3f}" == "0.900"


def test_golden_default_cube_is_what_readme_says():
    """docs/cube.md, `ldem cube`: '0.12 m, seed 1: load lost at 1.07e-3 with 0.566 U_min
    dissipated, separated at 6.2e-2 with 0.951 U_min'."""
    g, _ = _load_golden("cube_0.12_uniform_s1")
    u_min = g["min_fracture_energy_J"]
    assert f"{g['load_loss']['mean_strain']:.2e}" == "1.07e-03"
    assert f"{g['load_loss']['fracture_energy_J'] / u_min:.3f}" == "0.566"
    assert f"{g['separation']['mean_strain']:.1e}" == "6.2e-02"
    assert f"{g['U_ratio']:.3f}" == "0.951"
    # The parameters pinned are CubeTest's defaults (but the triangular cap).
    defaults = {k: v for k, v in ldem.CubeTest().parameters().items() if k != "threads"}
    assert g["parameters"] == json.loads(json.dumps(defaults))
    t, _ = _load_golden("cube_0.12_triangular_s1")
    assert t["parameters"] == dict(json.loads(json.dumps(defaults)), load="triangular", final_strain=0.002)
