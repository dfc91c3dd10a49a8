"""Every registered bar law (pkg/ldem/laws/Registry.hpp) in a whole run and
through the VTU writer: its name is a choice of the `law` parameter, its
per-bar state reaches Python through the law's interface (sim.law_state())
and bars.vtu, its damage states are those of its kappa and eps_r, and the run's
energy balance closes on its closed-form dissipated energy."""
import meshio
import numpy as np
import pytest

import ldem
from ldem import _core
from conftest import FAST

TINY = dict(FAST, size=0.04, final_strain=0.02, threads=1)


def test_the_law_parameter_offers_exactly_the_registered_laws():
    law = next(p for p in _core.parameter_table() if p["name"] == "law")
    assert list(law["choices"]) == list(_core.bar_laws)
    assert list(_core.bar_laws)[:3] == ["hillerborg", "bilinear", "exponential"]
    assert law["default"] == "hillerborg"


@pytest.mark.parametrize("law", list(_core.bar_laws))
def test_each_law_runs_and_writes_its_state_to_bars_vtu(tmp_path, law):
    # At the lagged dashpots' step, where the closed-form check was measured (at the default 0.9 of
    # 2/omega_max the tiny cube closes to 8.7e-3, 7.0e-3 and 5.4e-3).
    r = ldem.run_cube(ldem.CubeTest(**TINY, law=law, dashpot_velocity="lagged", zeta_high=0.2, dt_safety=0.8),
                      out=str(tmp_path), progress=False, writers=["summary", "vtk"])
    sim, s = r.sim, r.summary
    assert s["parameters"]["law"] == law
    # the balance closes on the law's closed-form dissipated energy (measured 3.6e-3, 2.6e-3, 2.8e-3)
    assert s["energy_balance_error"] < 5e-3, s["energy_balance_error"]
    state = sim.law_state()
    assert list(state)[0] == "kappa" and list(state)[-1] == "eps_r"
    assert all(len(v) == s["n_bars"] for v in state.values())
    cd = {k: v[0] for k, v in meshio.read(tmp_path / "bars.vtu").cell_data.items()}
    assert sorted(cd) == sorted(["damage_state", "damage", "strain", "force", "G_f", "kind", *state])
    for name, values in state.items():
        assert np.array_equal(cd[name], values), name
    kappa, eps_r, eps_p = state["kappa"], state["eps_r"], sim.eps_p
    assert np.array_equal(cd["damage_state"] == _core.BROKEN, kappa >= eps_r)
    assert np.array_equal(cd["damage_state"] == _core.DAMAGED, (kappa > eps_p) & (kappa < eps_r))
    assert (cd["damage_state"] == _core.BROKEN).sum() == r.curve["broken_bars"][-1] > 0
    # a broken bar in tension carries nothing
    broken_open = (cd["damage_state"] == _core.BROKEN) & (cd["strain"] > 0)
    assert broken_open.any() and np.all(cd["force"][broken_open] == 0)
