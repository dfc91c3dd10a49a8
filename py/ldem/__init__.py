"""ldem: truss-like lattice Discrete Element Method (Riera and Iturrioz) for
fracture and size effects in concrete. See README.md and docs/ for the manual.

    import ldem
    result = ldem.CubeTest(size=0.12, load="uniform", seed=1).run()     # data
    result = ldem.run_cube(ldem.CubeTest(size=0.12), out="out/cube")   # and its files
"""
import os

# Idle OpenMP threads sleep rather than spin (GOMP spins 300,000 rounds
# first): beside other jobs a spinning thread takes the core its partner
# waits for (a 0.12 m cube 15 times slower); read by the OpenMP runtime when
# _core loads it, so set before; a user's own setting stands.
os.environ.setdefault("OMP_WAIT_POLICY", "passive")

from ._core import InstabilityError, Material, Simulation  # noqa: E402,F401
from .cube import CURVE_COLUMNS, CubeResult, CubeTest  # noqa: E402,F401
from .runner import run_cube  # noqa: E402,F401
from .specimen import SpecimenTest  # noqa: E402,F401

__version__ = "0.1.0"
