"""ldem: truss-like lattice Discrete Element Method (Riera and Iturrioz) for
fracture and size effects in concrete. See README.md for the manual.

    import ldem
    result = ldem.CubeTest(size=0.12, load="uniform", seed=1).run()     # data
    result = ldem.run_cube(ldem.CubeTest(size=0.12), out="out/cube")   # and its files
"""
from ._core import InstabilityError, Material, Simulation  # noqa: F401
from .cube import CURVE_COLUMNS, CubeResult, CubeTest  # noqa: F401
from .runner import run_cube  # noqa: F401
from .specimen import SpecimenTest  # noqa: F401

__version__ = "0.1.0"
