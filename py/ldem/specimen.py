"""Any specimen from a file (`ldem run specimen.toml`) or a dict of the same
shape: a shape cut out of the cubic lattice, named groups of nodes, what each
group does (held, driven, free) and what the run measures.

    test = ldem.SpecimenTest.from_file("examples/beam_3pb.toml")
    result = test.run()          # data; ldem.run_cube(test, out=...) writes the files too

The file (examples/ has one per classic test; docs/specimens.md):
    title = "..."
    [shape]      kind = "box" | "cylinder" | "dogbone" | "mask", L0 [m] and the kind's sizes [m]
    [groups.NAME] face = "z-" | plane = {x = 0.1} | line = {x = 0.1, z = 0} | box = {min, max} | point = [x, y, z]
                 (several selectors: the nodes all of them select) | union = ["a", "b"]
                 fix = ["x", "z"] (held at 0), drive = {z = -1.0} (u_z = -1 x U(t)), linear = "x"
                 (the drive's weight grows linearly from 0 to its value across the group along x)
    [measure]    support, loaded (group names), area [m^2], gauge_length [m], ligament [m^2] (U_min = E[G_f] x it),
                 probes = {cmod = {a = [..], b = [..], direction = "x"}},
                 control = "cmod" (a servo holds the probe to loading.opening_rate [m/s]),
                 stress_label, strain_label (the figures' axes: "F/(bD) [MPa]", "deflection/D [-]")
    [material], [loading], [run]: any parameter of `ldem cube --help` in those groups

Stress = the support group's reactions along the drive / area; strain = the drive's
displacement (mean over the loaded group) / gauge_length; both positive in the sense
the specimen is driven. A driven group moves as one: a rigid platen. The mask comes
from ldem.shapes; everything the run computes is in C++ (ldem._core.Simulation).
Longer than 300 lines: the file's keys, their checks (with --set's) and the specimen built from them, read top to bottom.
"""
from __future__ import annotations

import tomllib
from typing import Optional

import numpy as np

from . import _core
from .cube import PARAMETERS, TABLE_DEFAULTS, CubeResult, run_test
from .shapes import AXES, Nodes, SpecimenError, Where, check_keys, inside, module_mask, named, number, point

_PARAMS = {p["name"]: p for p in PARAMETERS}
# Cube-only parameters: a specimen says the same with its groups.
_CUBE_ONLY = {"size", "L0", "load", "top_lateral", "bottom_lateral"}
# A specimen's own defaults over the table's: its rate from its own fundamental
# period (pkg/ldem/ParameterTable.hpp, specimenOwnDefaults, says why).
SPECIMEN_DEFAULTS = _core.specimen_own_defaults()
_SECTIONS = {"title", "shape", "groups", "measure", "material", "loading", "run"}
_GROUP_KEYS = {"face", "plane", "line", "box", "point", "union", "fix", "drive", "linear"}
_MEASURE_KEYS = {"support", "loaded", "area", "gauge_length", "ligament", "probes", "control", "stress_label",
                 "strain_label"}


def select(nodes: Nodes, name: str, spec: dict, groups: dict, where: Where) -> np.ndarray:
    """The node ids a [groups.NAME] table selects."""
    key = f"groups.{name}"
    if "union" in spec:
        if not (isinstance(spec["union"], list) and spec["union"]):
            raise where(f"{key}.union", f"must be a list of group names (got {spec['union']!r})")
        ids = []
        for other in spec["union"]:
            if not named(other, groups):
                raise where(f"{key}.union", f"no group '{other}' defined before this one")
            ids.append(groups[other])
        return np.unique(np.concatenate(ids))
    sel = nodes.present.copy()
    chosen = False
    if "face" in spec:
        face = spec["face"]
        if not (isinstance(face, str) and len(face) == 2 and face[0] in AXES and face[1] in "+-"):
            raise where(f"{key}.face", f"must be one of x-, x+, y-, y+, z-, z+ (got {face!r})")
        a = AXES[face[0]]
        at = nodes.lo[a] if face[1] == "-" else nodes.hi[a]
        sel &= np.abs(nodes.x[:, a] - at) <= nodes.tol
        chosen = True
    for kind, count, example in (("plane", 1, "{x = 0.1}"), ("line", 2, "{x = 0.1, z = 0.0}")):
        if kind in spec:  # the nodes whose `count` coordinates are those given
            c = spec[kind]
            if not (isinstance(c, dict) and len(c) == count and all(a in AXES for a in c)):
                raise where(f"{key}.{kind}", f"must be {count} coordinate(s), e.g. {example} (got {c!r})")
            for axis, at in c.items():
                at = number(at, where, f"{key}.{kind}", positive=False)
                a = AXES[axis]
                inside(at, nodes.lo[a], nodes.hi[a], nodes.L0, where, f"{key}.{kind}", axis)
                sel &= np.abs(nodes.x[:, a] - at) <= nodes.tol
            chosen = True
    if "box" in spec:
        box = spec["box"]
        if not (isinstance(box, dict) and set(box) == {"min", "max"}):
            raise where(f"{key}.box", "must be {min = [x, y, z], max = [x, y, z]}")
        lo, hi = point(box["min"], where, f"{key}.box"), point(box["max"], where, f"{key}.box")
        for p in (lo, hi):
            inside(p, nodes.lo, nodes.hi, nodes.L0, where, f"{key}.box")
        sel &= np.all((nodes.x >= lo - nodes.tol) & (nodes.x <= hi + nodes.tol), axis=1)
        chosen = True
    if "point" in spec:
        k = nearest(nodes, sel, spec["point"], where, f"{key}.point")
        sel = np.zeros_like(sel)
        sel[k] = True
        chosen = True
    if not chosen:
        raise where(key, "needs a selector: face, plane, line, box, point or union")
    ids = np.flatnonzero(sel)
    if len(ids) == 0:
        raise where(key, "selects no node of the specimen")
    return ids


def nearest(nodes: Nodes, among: np.ndarray, value, where: Where, key: str) -> int:
    """The node (of those `among`) nearest the point `value`, within L0 of it, which lies in the specimen's box."""
    p = point(value, where, key)
    inside(p, nodes.lo, nodes.hi, nodes.L0, where, key)
    d = np.where(among, np.linalg.norm(nodes.x - p, axis=1), np.inf)
    k = int(np.argmin(d))
    if not d[k] <= nodes.L0:
        raise where(key, f"no node of the specimen within L0 of {list(p)}")
    return k


def _directions(value, where: Where, key: str) -> list:
    if not (isinstance(value, list) and all(named(v, AXES) for v in value)):
        raise where(key, f"must be a list of directions among x, y, z (got {value!r})")
    return [AXES[v] for v in value]


class Build:
    """What a description makes: the lattice, groups, prescribed DOFs, measures, parameters."""

    def __init__(self, data: dict, where: Where, overrides: Optional[dict] = None):
        check_keys(data, _SECTIONS, where, "")
        for s in ("shape", "groups", "measure"):
            if not isinstance(data.get(s), dict):
                raise where(s, "missing (every specimen needs [shape], [groups.NAME] and [measure])")
        self.title = str(data.get("title", "specimen"))
        self.params = _parameters(data, where, overrides or {})
        self.L0, self.n, self.mask = module_mask(data["shape"], where)
        self.params["L0"] = self.L0
        self.params["size"] = self.L0 * self.n[0]
        try:  # the bounds that tie the parameters to L0 (pkg/ldem/Relations.hpp)
            self.cpp_params().validate()
        except ValueError as e:
            raise _named(e, where, overrides or {}) from None
        nodes = Nodes(self.n, self.L0, self.mask)
        self.groups, owner = {}, {}
        node, dim, weight = [], [], []
        for name, spec in data["groups"].items():
            key = f"groups.{name}"
            if not isinstance(spec, dict):
                raise where(key, "must be a table")
            check_keys(spec, _GROUP_KEYS, where, key + ".")
            ids = select(nodes, name, spec, self.groups, where)
            self.groups[name] = ids
            actions = [(d, 0.0) for d in _directions(spec.get("fix", []), where, f"{key}.fix")]
            drive = spec.get("drive", {})
            if not isinstance(drive, dict) or any(a not in AXES for a in drive):
                raise where(f"{key}.drive", f"must be a table of weights by direction, e.g. {{z = -1.0}} (got {drive!r})")
            actions += [(AXES[a], number(w, where, f"{key}.drive.{a}", positive=False)) for a, w in drive.items()]
            scale = np.ones(len(ids))
            if "linear" in spec:
                a = AXES[spec["linear"]] if named(spec["linear"], AXES) else None
                if a is None or not drive:
                    raise where(f"{key}.linear", "must be x, y or z, on a group with a drive")
                c = nodes.x[ids, a]
                span = c.max() - c.min()
                if not span > 0:
                    raise where(f"{key}.linear", "the group has no extent along that direction")
                scale = (c - c.min()) / span
            for d, w in actions:
                for i, n_ in enumerate(ids):
                    if (n_, d) in owner:
                        raise where(key, f"node at {list(nodes.x[n_])} direction {'xyz'[d]} is also prescribed by "
                                         f"group '{owner[n_, d]}'")
                    owner[n_, d] = name
                    node.append(n_), dim.append(d), weight.append(w * scale[i] if w else 0.0)
        self.prescribed = (np.array(node, np.int32), np.array(dim, np.uint8), np.array(weight))
        self.measures = self._measures(data["measure"], nodes, where)

    def _measures(self, m: dict, nodes: Nodes, where: Where) -> dict:
        check_keys(m, _MEASURE_KEYS, where, "measure.")
        out = {}
        for k in ("support", "loaded"):
            if not named(m.get(k), self.groups):
                raise where(f"measure.{k}", f"must name a group (got {m.get(k)!r}; groups: {', '.join(self.groups)})")
            out[k] = m[k]
        node, dim, weight = self.prescribed
        loaded = np.isin(node, self.groups[out["loaded"]])
        driven = sorted({int(d) for d, w in zip(dim[loaded], weight[loaded]) if w != 0})
        if len(driven) != 1:
            raise where("measure.loaded", f"group '{out['loaded']}' must be driven along one direction "
                                          f"(it is along {['xyz'[d] for d in driven] or 'none'})")
        out["dim"] = driven[0]
        if np.intersect1d(self.groups[out["support"]], self.groups[out["loaded"]]).size:
            raise where("measure.loaded", f"groups '{out['support']}' and '{out['loaded']}' share nodes: the "
                                          "support's reactions and the separation need two apart")
        along = loaded & (dim == driven[0])
        out["mean_drive_weight"] = float(weight[along].sum() / len(self.groups[out["loaded"]]))
        out["area"] = number(m.get("area"), where, "measure.area")
        out["gauge_length"] = number(m.get("gauge_length"), where, "measure.gauge_length")
        out["ligament"] = number(m["ligament"], where, "measure.ligament") if "ligament" in m else 0.0  # 0: no U_min
        for k in ("stress_label", "strain_label"):  # what stress and strain are for this specimen
            if not isinstance(m.get(k, ""), str):
                raise where(f"measure.{k}", f"must be a text, an axis label (got {m[k]!r})")
            out[k] = m.get(k, "")
        probes = m.get("probes", {})
        if not isinstance(probes, dict):
            raise where("measure.probes", "must be a table of probes by name")
        out["probes"] = []
        for name, q in probes.items():
            key = f"measure.probes.{name}"
            if not isinstance(q, dict):
                raise where(key, "must be {a = [x, y, z], b = [x, y, z], direction = 'x'} (a: optional)")
            check_keys(q, {"a", "b", "direction"}, where, key + ".")
            if not named(q.get("direction"), AXES):
                raise where(f"{key}.direction", f"must be x, y or z (got {q.get('direction')!r})")
            a = nearest(nodes, nodes.present, q["a"], where, f"{key}.a") if "a" in q else -1
            if "b" not in q:
                raise where(f"{key}.b", "missing: the point whose displacement is read")
            b = nearest(nodes, nodes.present, q["b"], where, f"{key}.b")
            out["probes"].append((name, int(a), int(b), AXES[q["direction"]]))
        names = [q[0] for q in out["probes"]]
        if "control" in m and not named(m["control"], names):
            raise where("measure.control", f"must name a probe (got {m['control']!r}; probes: {', '.join(names)})")
        out["control"] = names.index(m["control"]) if "control" in m else -1
        if (out["control"] >= 0) != (self.params["opening_rate"] > 0):
            raise where("measure.control" if "control" in m else "loading.opening_rate",
                        "opening control needs both measure.control (a probe) and loading.opening_rate > 0")
        return out

    def cpp_params(self):
        p = _core.CubeTestParams()
        for k, v in self.params.items():
            p[k] = v
        return p


def _parameters(data: dict, where: Where, overrides: dict) -> dict:
    """Every CubeTest parameter of the material, loading and run groups: the
    file's values over the defaults (SPECIMEN_DEFAULTS over the table's), then
    the overrides (--set). A strain_rate given without rate_periods is the rate
    driven: the file's over the default rule (c), --set's over the file's."""
    out = {**TABLE_DEFAULTS, **SPECIMEN_DEFAULTS}
    given = [(section, k, v, False) for section in ("material", "loading", "run")
             for k, v in (data.get(section) or {}).items()]
    given += [(_PARAMS[k]["group"] if k in _PARAMS else "set", k, v, True) for k, v in overrides.items()]
    def blame(section: str, k: str, message: str, overridden: bool) -> SpecimenError:  # --set's by its option
        return SpecimenError(f"--set {k}: {message}") if overridden else where(f"{section}.{k}", message)
    for section, k, v, overridden in given:
        if k not in _PARAMS or k in _CUBE_ONLY or _PARAMS[k]["group"] != section:
            raise blame(section, k, "not a parameter of this section" if k in _PARAMS and k not in _CUBE_ONLY else
                        ("a cube-test parameter: a specimen says it with its groups" if k in _CUBE_ONLY
                         else "unknown parameter (see ldem cube --help)"), overridden)
        kind = _PARAMS[k]["kind"]
        named = kind in ("choice", "names")
        ok = isinstance(v, str) if named else (isinstance(v, (int, float)) and not isinstance(v, bool))
        if not ok or (kind == "int" and not isinstance(v, int)):
            expected = _PARAMS[k]["domain"] if named else kind
            raise blame(section, k, f"must be {expected} (got {v!r})", overridden)
        out[k] = float(v) if kind == "float" else v
    for layer in (False, True):  # the file, then --set: the later one's choice of rate stands
        said = {k: v for _, k, v, overridden in given if overridden == layer}
        if "rate_periods" in said:
            out["rate_periods"] = float(said["rate_periods"])
        elif "strain_rate" in said:
            out["rate_periods"] = 0.0
    p = _core.CubeTestParams()
    for k, v in out.items():
        p[k] = v
    try:
        p.material.validate(), p.loading.validate(), p.run.validate()
    except ValueError as e:
        raise _named(e, where, overrides) from None
    return out


def _named(error: ValueError, where: Where, overrides) -> SpecimenError:
    """A parameter's error (its message starts with its name): at its --set option, or at its key in the file."""
    name = str(error).split()[0]
    return SpecimenError(f"--set {name}: {error}") if name in overrides else \
        where(f"{_PARAMS[name]['group'] if name in _PARAMS else 'parameters'}.{name}", str(error))


class SpecimenTest:
    """A specimen and its run parameters, from a description (a dict shaped as
    the file) or a file. Runs like ldem.CubeTest: run() returns the data,
    ldem.run_cube(test, out=...) writes curve.csv, summary.json and figures."""

    def __init__(self, description: dict, path: str = "", text: str = "", overrides: Optional[dict] = None):
        self.description, self.path = description, path
        self.build = Build(description, Where(text, path), overrides)
        self.overrides = dict(overrides or {})
        for k in ("final_strain", "energy_tolerance", "seed", "stop_at", "strain_rate", "eps_p"):
            setattr(self, k, self.build.params[k])

    @classmethod
    def of(cls, **sections) -> "SpecimenTest":
        """From keyword arguments, one per section of the file (dicts shaped as the file's)."""
        return cls(sections)

    @classmethod
    def from_file(cls, path: str, overrides: Optional[dict] = None) -> "SpecimenTest":
        try:
            with open(path, "rb") as f:
                text = f.read().decode()
        except OSError as e:
            raise SpecimenError(f"{path}: {e.strerror or e}") from None
        except UnicodeDecodeError:
            raise SpecimenError(f"{path}: not a text file") from None
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError as e:
            raise SpecimenError(f"{path}: not valid TOML: {e}") from None
        return cls(data, path, text, overrides)

    def describe(self) -> str:
        return f"{self.build.title}, seed {self.seed}"

    def axis_labels(self) -> tuple:
        """(strain, stress) axis labels of the figures: measure.strain_label and stress_label ("": none)."""
        return self.build.measures["strain_label"], self.build.measures["stress_label"]

    def parameters(self) -> dict:
        """What reproduces the run: the description and the parameters it gives."""
        return {"description": self.description, "parameters": self.build.params}

    def simulation(self):
        b = self.build
        p = b.cpp_params()
        mask = np.ascontiguousarray(b.mask.transpose(2, 1, 0)).ravel().astype(np.uint8)  # [i + nx (j + ny k)]
        return _core.Simulation(*b.n, b.L0, mask, {k: v.astype(np.int32) for k, v in b.groups.items()},
                                *b.prescribed, b.measures, p.material, p.loading, p.run)

    def run(self, observers=(), simulation=None, previous_rows=()) -> CubeResult:
        """The run to its stop rule (separation of the support and loaded
        groups, load loss with run.stop_at = "load_loss", or run.final_strain),
        as ldem.CubeTest.run, with a column NAME_m per probe."""
        return run_test(self, observers, simulation, previous_rows, [q[0] for q in self.build.measures["probes"]])
