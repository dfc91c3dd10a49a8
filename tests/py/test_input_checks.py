"""Every input checked before any large allocation (issue 40, item 3): the
lattice's memory estimate for ldem cube, ldem run and the Python API (one C++
function, pkg/ldem/Lattice.hpp checkFits), and the bounds that tie parameters
(pkg/ldem/Relations.hpp), each refused with its message and exit code 2."""
import math
import os
import resource
import re

import pytest

import ldem
from ldem import _core
from conftest import ROOT, subprocess_env

TINY = ["--size", "0.04", "--threads", "1", "--no-progress", "--no-plots"]


def _error(r) -> str:
    assert r.returncode == 2, (r.returncode, r.stderr)
    assert "Traceback" not in r.stderr
    errors = [line for line in r.stderr.strip().splitlines() if ": warning: " not in line]
    assert len(errors) == 1, r.stderr
    return errors[0]


def test_a_specimen_file_too_big_is_refused_at_once_with_the_estimate(cli, tmp_path):
    """examples/beam_3pb.toml with L0 = 0.0001 (3500 x 500 x 1000 modules) ran
    until killed; under a memory limit it ended in numpy's traceback. Now the
    estimate of ldem cube refuses it before the module mask is drawn."""
    text = open(os.path.join(ROOT, "examples", "beam_3pb.toml")).read().replace("L0 = 0.01", "L0 = 0.0001")
    path = tmp_path / "beam.toml"
    path.write_text(text)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    r = cli("run", str(path), "--out", str(tmp_path / "o"), "--no-progress")
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    line = _error(r)
    assert "shape.L0: a lattice of 3500 x 500 x 1000 modules (24" in line and " GB; this machine has " in line, line
    assert "MPI" not in line
    # At once: by the child's own CPU time, which a busy machine does not inflate as it does the wall
    # (drawing the 1.75e9-module mask alone would take minutes).
    cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    assert cpu < 10, cpu
    with pytest.raises(ValueError, match="needs about 24"):  # the Python API: the same check
        ldem.SpecimenTest.from_file(str(path))


def test_a_cube_beyond_any_rank_gets_no_mpi_advice(cli, tmp_path):
    line = _error(cli("cube", "--size", "20", "--out", str(tmp_path / "o"), "--no-progress"))
    assert "1000 x 1000 x 1000 modules (14" in line and "needs about 1400 GB; this machine has" in line, line
    assert "MPI" not in line


@pytest.mark.direct
def test_mpi_advice_only_when_the_memory_holds_the_lattice():
    """Past 32-bit node ids (2^31 bars) one process cannot number the lattice;
    ranks on this machine can hold it only if its memory can."""
    n = 600  # 600^3 modules: 3.0e9 bars, 303 GB
    assert _core.memory_estimate(n, n, n) == 100 * _core.expected_bar_count(n, n, n)
    short = _core.lattice_misfit(n, n, n, 100e9)
    assert "needs about 303 GB; this machine has 100 GB" in short and "MPI" not in short
    big = _core.lattice_misfit(n, n, n, 1e12)
    assert "32-bit node ids" in big and "MPI ranks" in big
    assert _core.lattice_misfit(20, 20, 20, 1e12) == ""


def _under_ulimit(room: float, code: str, *args):
    """Python `code` in a subprocess with ldem imported, its address space then
    limited (ulimit -v, RLIMIT_AS) to its size plus `room` bytes; sys.argv[1:] = args."""
    import subprocess
    import sys

    limit = ("import os, resource, sys; from ldem import _core, cli; "
             "size = int(open('/proc/self/statm').read().split()[0]) * os.sysconf('SC_PAGE_SIZE'); "
             f"resource.setrlimit(resource.RLIMIT_AS, (size + {room:.0f}, resource.RLIM_INFINITY)); ")
    return subprocess.run([sys.executable, "-c", limit + code, *args], capture_output=True, text=True, timeout=120,
                          env=subprocess_env())


def test_memory_is_checked_against_the_address_space_limit(tmp_path):
    """Under ulimit -v the room is the limit less the process's size, not the
    machine's memory (25 GB here, where a 196 M-bar beam under a 4 GB limit
    built for 65 s before an allocation failed): the 150^3 cube (44 M bars,
    about 4.4 GB) is refused at once under 2 GB of room, naming the limit; the
    80^3 cube (0.67 GB) fits it."""
    r = _under_ulimit(2e9, "print(*_core.memory_limit(), sep=';'); _core.check_fits(80, 80, 80)")
    assert r.returncode == 0, r.stderr
    room, which = r.stdout.strip().split(";")
    assert which == "the address-space limit (ulimit -v) leaves" and 1.9e9 < float(room) <= 2e9
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    r = _under_ulimit(2e9, "sys.exit(cli.main(sys.argv[1:]))", "cube", "--size", "3", "--out", str(tmp_path / "o"),
                      "--no-progress", "--threads", "1")
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    assert re.fullmatch(r"ldem cube: error: a lattice of 150 x 150 x 150 modules \(4\d{7} bars\) needs about 4\.\d+ GB; "
                        r"the address-space limit \(ulimit -v\) leaves 1\.9\d GB", _error(r)), r.stderr
    cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)  # at once, as a busy machine's wall is not
    assert cpu < 30 and not (tmp_path / "o" / "curve.csv").exists(), cpu


@pytest.mark.direct
def test_the_memory_limit_is_the_machines_available_memory_without_a_smaller_one():
    """With no ulimit -v and no cgroup limit below it, the room is MemAvailable (/proc/meminfo)."""
    room, which = _core.memory_limit()
    with open("/proc/meminfo") as f:
        available = next(float(line.split()[1]) * 1024 for line in f if line.startswith("MemAvailable:"))
    if which == "this machine has available":
        assert room == pytest.approx(available, rel=0.2)  # (it moves with the other processes)
    else:  # a container's limit, below what the machine has
        assert which == "the cgroup's memory limit (memory.max) leaves" and room <= 1.2 * available


BRITTLE = "every bar is perfectly brittle: all 130 drew a G_f below E A eps_p^2 L / (2 A_f) (4.01199 N/m"


@pytest.mark.parametrize("args,message", [
    (["--Gf-mean", "1e-30"], BRITTLE),
    (["--c-a", "1e-300"], "every bar is perfectly brittle: all 130 drew a G_f below E A eps_p^2 L / (2 A_f) "
                          "(5.5566e+299 N/m for a normal bar), with Gf_mean 100 N/m: raise Gf_mean or c_a "
                          "(the bound goes as 1 / c_a)"),
    (["--Gf-mean", "2", "--Gf-cv", "0", "--c-a", "1e-3"], "= 473 N/m (E, nu, eps_p, c_a and L0 = 0.02 m); "
                                                          "raise Gf_mean or c_a (the bound goes as 1 / c_a)"),
    (["--c-a", "1.5"], "c_a must be in (0, 1] (got 1.5)"),
    (["--Gf-mean", "2", "--Gf-cv", "0"], "Gf_mean 2 N/m (the same in every bar, Gf_cv 0) makes every bar "
                                         "perfectly brittle: it is below E A eps_p^2 L / (2 A_f) = 3.41 N/m"),
    (["--Gf-mean", "1e6"], "Gf_mean 1e+06 N/m gives a bar the limit strain eps_r = 2 c_a G_f / (E phi eps_p L0) = "
                           "15.7, above 1"),
    (["--ramp-time", "1e9"], "ramp_time 1e+09 s is above eps_p / strain_rate = 0.00315 s"),
    (["--final-strain", "1e-9"], "comes before the first record (at mean strain"),
    (["--strain-rate", "1e-9"], "steps of 2.95e-06 s to strain eps_p: more than 1000000 before any bar can crack"),
])
def test_absurd_inputs_are_refused_with_their_rule(cli, tmp_path, args, message):
    line = _error(cli("cube", *TINY, "--out", str(tmp_path / "o"), *args))
    assert message in line, line


def test_brittle_bars_by_construction_are_warned_of(cli, tmp_path):
    """Gf_mean 3.8 N/m with Gf_cv 0: below the normal bars' 4.01 N/m, above the
    diagonals' 3.41: the normal bars are brittle, the run goes on with a warning.
    (Half its bars snapping at once, this cube's energy balance closes to 0.4-1.2 %
    depending on the last bits of its smooth start: the tolerance is not what is tested.)"""
    r = cli("cube", *TINY, "--out", str(tmp_path / "o"), "--Gf-mean", "3.8", "--Gf-cv", "0", "--energy-tolerance", "0.03")
    assert r.returncode == 0, r.stderr
    assert "warning: Gf_mean 3.8 N/m is below E phi eps_p^2 L0 / (2 c_a) = 4.01 N/m" in r.stderr
    assert "66 of 130 bars had eps_r < eps_p" in r.stdout


def test_the_help_states_the_rules_with_true_numbers(cli):
    material = ldem.CubeTest().params().material
    assert _core.brittle_fracture_energy(material, 0.02, False) == pytest.approx(4.0, abs=0.05)
    assert _core.brittle_fracture_energy(material, 0.02, False) / material.eps_p == pytest.approx(6.4e4, rel=0.01)
    text = " ".join(cli("cube", "--help").stdout.split())
    for rule in ("(4.0 N/m for a normal bar at the defaults) is perfectly brittle",
                 "(6.4e4 N/m at the defaults)", "at most eps_p / strain_rate", "at most 1: a bar's fracture area at most a module's face",
                 "it can never reach the peak", "more than 1e-6 eps_p in one step"):
        assert rule in text, rule


@pytest.mark.direct
def test_the_ramp_time_is_held_to_the_rate_rate_periods_derives():
    """rate_periods N sets the rate from the drive's own omega_d at set-up:
    eps_p / strain_rate = N T_d. The smooth start's bound (ramp_time at most
    eps_p / strain_rate, pkg/ldem/Relations.hpp) is that rate's: 3 T_d here,
    a tenth of the bound of the strain_rate given beside it (0.02 /s)."""
    base = dict(size=0.04, rate_periods=3.0, strain_rate=0.02, threads=1)
    Td = 2 * math.pi / ldem.CubeTest(**base).simulation().omega_d
    assert ldem.CubeTest(**base).eps_p / 0.02 > 10 * 3 * Td  # the rate given would allow 10 times the ramp
    assert ldem.CubeTest(**base, ramp_time=0.99 * 3 * Td).simulation().ramp_time == 0.99 * 3 * Td
    with pytest.raises(ValueError, match=r"ramp_time .* s is above eps_p / strain_rate = .* s: the smooth start"):
        ldem.CubeTest(**base, ramp_time=1.01 * 3 * Td).simulation()


@pytest.mark.direct
def test_raising_c_a_is_what_lowers_the_brittle_bound():
    """The advice of the messages above: G_b = E A eps_p^2 L / (2 A_f) with A_f = c_a L0^2, so twice c_a halves it."""
    low, high = (ldem.CubeTest(c_a=c).params().material for c in (0.1, 0.2))
    for diagonal in (False, True):
        assert _core.brittle_fracture_energy(high, 0.02, diagonal) == \
            pytest.approx(_core.brittle_fracture_energy(low, 0.02, diagonal) / 2, rel=1e-12)


@pytest.mark.parametrize("args", [["--eps-p", "-1e-5"], ["--eps-p=-1e-5"]], ids=["apart", "joined"])
def test_a_negative_number_is_a_value_in_any_notation(cli, tmp_path, args):
    """argparse took -1e-5 (not -1 or -.5) for an option: "expected one argument"; now it is the value, out of bounds."""
    assert _error(cli("cube", *TINY, "--out", str(tmp_path / "o"), *args)) == \
        "ldem cube: error: eps_p must be in (0, 0.01] (got -1e-05)"
    assert not (tmp_path / "o").exists()


def test_negative_values_reach_every_commands_check(cli, tmp_path):
    assert _error(cli("cube", *TINY, "--out", str(tmp_path / "o"), "--zeta", "-2.5E-3")) == \
        "ldem cube: error: zeta must be in [0, 10] (got -0.0025)"
    line = _error(cli("run", os.path.join(ROOT, "examples", "cube_uniform.toml"), "--threads", "-1e0",
                      "--out", str(tmp_path / "o")))
    assert line == "ldem run: error: argument --threads: invalid int value: '-1e0'", line  # a value, not an option


@pytest.mark.parametrize("args,got", [
    (["--seed", str(2 ** 70)], "seed is out of range: a whole number from 0 to 9223372036854775807 "
                               "(got 1180591620717411303424)"),
    (["--threads", "-10000000"], "threads must be >= 0 (got -10000000)"),
    (["--record-every", "-123456789"], "record_every must be >= 0 (got -123456789 steps)"),
])
def test_integers_are_said_as_integers(cli, tmp_path, args, got):
    assert _error(cli("cube", *TINY, "--out", str(tmp_path / "o"), *args)) == f"ldem cube: error: {got}"


def test_integers_are_said_as_integers_from_a_file_and_python(cli, tmp_path):
    text = open(os.path.join(ROOT, "examples", "cube_uniform.toml")).read() + f"\n[run]\nseed = {2 ** 70}\n"
    path = tmp_path / "cube.toml"
    path.write_text(text)
    line = _error(cli("run", str(path), "--out", str(tmp_path / "o")))
    assert "(got 1180591620717411303424)" in line and "e+21" not in line, line
    with pytest.raises(ValueError, match=r"\(got 1180591620717411303424\)"):
        ldem.CubeTest(seed=2 ** 70).params()


def test_threads_0_is_said_once_for_every_command(cli):
    """The table's words (pkg/ldem/Parameters.hpp) in ldem cube, run and bench: ldem run said "all cores"."""
    table = next(p["help"] for p in ldem.cube.PARAMETERS if p["name"] == "threads")
    assert table.startswith("OpenMP threads (0: OMP_NUM_THREADS if set, else one per 50,000 bars")
    for command in (["cube"], ["run", "x.toml"], ["bench"]):
        text = " ".join(cli(*command[:1], "--help").stdout.split())
        assert f"--threads THREADS {table}; >= 0" in text, (command, text)
        assert "all cores" not in text
