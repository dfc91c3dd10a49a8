"""`ldem bench --damaged`: the time step of a cube past its peak, beside the elastic one."""
import json


def test_damaged_case_starts_past_the_peak_and_reports_both_speeds(cli):
    r = cli("bench", "--modules", "6", "--steps", "20", "--repeats", "1", "--threads", "1", "--damaged")
    assert r.returncode == 0, r.stderr
    b = json.loads(r.stdout)
    # Timed from load loss: the stress has fallen well below its peak, bars
    # have softened and broken, and their rows are on the law's slow path.
    assert b["damaged_stop_reason"] == "load_lost"
    assert b["damaged_from_step"] > 20 + 10
    assert abs(b["damaged_stress_over_peak"]) < 0.5  # (it rings around zero)
    assert b["broken_bar_share"] > 0 and b["damaged_bar_share"] > b["broken_bar_share"]
    assert 0 < b["damaged_softening_row_share"] <= b["damaged_softening_row_share_after"] <= 1
    assert b["ns_per_bar_step"] > 0 and b["damaged_ns_per_bar_step"] > 0
    assert abs(b["damaged_over_elastic"] - b["damaged_ns_per_bar_step"] / b["ns_per_bar_step"]) < 0.01 * b[
        "damaged_over_elastic"] + 1e-3


def test_plain_bench_has_no_damaged_case(cli):
    r = cli("bench", "--modules", "4", "--steps", "5", "--repeats", "1", "--threads", "1")
    assert r.returncode == 0, r.stderr
    assert not any(k.startswith("damaged") for k in json.loads(r.stdout))
