"""ldem: truss-like lattice Discrete Element Method (Riera and Iturrioz) for
fracture and size effects in concrete. See README.md and docs/ for the manual.

    import ldem
    result = ldem.CubeTest(size=0.12, load="uniform", seed=1).run()     # data
    result = ldem.run_cube(ldem.CubeTest(size=0.12), out="out/cube")   # and its files
"""
import importlib
import importlib.util
import os

# Idle OpenMP threads sleep rather than spin (GOMP spins 300,000 rounds
# first): beside other jobs a spinning thread takes the core its partner
# waits for (a 0.12 m cube 15 times slower); read by the OpenMP runtime when
# _core loads it, so set before; a user's own setting stands.
os.environ.setdefault("OMP_WAIT_POLICY", "passive")

__version__ = "0.1.0"

# The package's names, each loaded when first asked for (PEP 562): importing
# ldem, or any of its modules, loads neither numpy nor the core, so that the
# `ldem` command hears signals from its first instant (ldem.__main__).
_NAMES = {"InstabilityError": "_core", "Material": "_core", "Simulation": "_core", "CURVE_COLUMNS": "cube",
          "CubeResult": "cube", "CubeTest": "cube", "run_cube": "runner", "SpecimenTest": "specimen"}
__all__ = sorted(_NAMES)


def __getattr__(name):
    if name in _NAMES:
        value = getattr(importlib.import_module(f".{_NAMES[name]}", __name__), name)
    elif importlib.util.find_spec(f".{name}", __name__) is not None:  # a module of the package: ldem.io, ...
        value = importlib.import_module(f".{name}", __name__)
    else:
        raise AttributeError(f"module 'ldem' has no attribute {name!r}")
    globals()[name] = value
    return value
