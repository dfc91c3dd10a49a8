"""The package's shape (docs/developers.md, ARCHITECTURE.md): layers import downwards only,
no import cycles (module-level or inside functions), no module over 300 lines
without the reason at its top, no runner of cases in scripts/ or dev/ (studies
live in ldem.study), no developer's tool in scripts/ (dev/ holds them), each
file of both named in ARCHITECTURE.md. Read from the source, nothing imported."""
import ast
import os

from conftest import ROOT

PACKAGE = os.path.join(ROOT, "py", "ldem")
# Lower layers first; a module may import its own layer or those below, never above.
LAYERS = [
    {"ldem._core"},
    {"ldem.mincut", "ldem.curves", "ldem.criteria", "ldem.cube", "ldem.shapes", "ldem.specimen", "ldem.module_rule", "ldem.yade"},  # specimen and run
    {"ldem.io", "ldem.slicing", "ldem.parallel", "ldem.progress", "ldem.plots", "ldem.report",  # writers (ldem.io.*),
     "ldem.markdown", "ldem.helptext", "ldem.signals"},                                    # pictures, reports, signals
    {"ldem.runner"},                                                   # a run wired to its files
    {"ldem.study"},                                                    # ldem.study.* included
    {"ldem.cli", "ldem.run_command", "ldem.rerun", "ldem.bench", "ldem.scene"},                     # the edges: command line, scene scripts
]
FACADES = {"ldem", "ldem.__main__"}  # the package's front doors re-export from every layer
MAX_LINES = 300


def _modules(package=PACKAGE):
    for folder, _, files in os.walk(package):
        for f in files:
            if f.endswith(".py"):
                path = os.path.join(folder, f)
                rel = os.path.relpath(path, os.path.dirname(package))[:-3].replace(os.sep, ".")
                yield (rel[: -len(".__init__")] if rel.endswith(".__init__") else rel), path


def _imports(name, path):
    """Every ldem module that module `name` imports, anywhere in its body."""
    package = name if path.endswith("__init__.py") else name.rpartition(".")[0]
    out = set()
    for node in ast.walk(ast.parse(open(path).read())):
        if isinstance(node, ast.Import):
            out |= {a.name for a in node.names if a.name.split(".")[0] == "ldem"}
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            if mod.split(".")[0] != "ldem":
                continue
            out.add(mod)
            out |= {f"{mod}.{a.name}" for a in node.names}  # `from . import io` names a module
    return out


def _graph(package=PACKAGE):
    mods = dict(_modules(package))
    graph = {}
    for name, path in mods.items():
        graph[name] = {m for m in _imports(name, path) if m in mods or m == "ldem._core"} - {name}
    return mods, graph


def _layer(mod):
    for i, layer in enumerate(LAYERS):
        if mod in layer or any(mod.startswith(top + ".") for top in layer):
            return i
    raise AssertionError(f"{mod} is in no layer of tests/py/test_architecture.py: place it")


def _upward_imports(graph):
    wrong = []
    for mod, deps in graph.items():
        if mod in FACADES:
            continue
        for dep in deps - FACADES:
            if _layer(dep) > _layer(mod):
                wrong.append(f"{mod} (layer {_layer(mod)}) imports {dep} (layer {_layer(dep)})")
    return wrong


def _cycles(graph):
    """Tarjan's strongly connected components: one of more than one module is a cycle."""
    graph = {m: d - FACADES for m, d in graph.items() if m not in FACADES}
    index, low, stack, on, cycles, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v), on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                cycles.append(sorted(comp))

    for v in list(graph):
        if v not in index:
            visit(v)
    return cycles


def test_every_module_has_a_layer_and_imports_only_downwards():
    mods, graph = _graph()
    assert {"ldem.study.cases", "ldem.cube", "ldem.yade.cube", "ldem.runner"} <= set(mods), sorted(mods)
    wrong = _upward_imports(graph)
    assert not wrong, "upward imports:\n" + "\n".join(wrong)


def test_no_import_cycles():
    _, graph = _graph()
    assert not _cycles(graph), f"import cycles: {_cycles(graph)}"


def test_the_checks_see_a_cycle_and_an_upward_import(tmp_path):
    """The checks on a made-up package whose cube imports runner inside a
    function (upward) and runner imports cube: both are found."""
    pkg = tmp_path / "ldem"
    (pkg / "study").mkdir(parents=True)
    (pkg / "__init__.py").write_text("from .cube import CubeTest\n")
    (pkg / "cube.py").write_text("def run():\n    from .runner import run_cube\n")
    (pkg / "runner.py").write_text("from . import io\nfrom .cube import CubeTest\n")
    (pkg / "io.py").write_text("import os\n")
    (pkg / "study" / "__init__.py").write_text("from ..io import x\nfrom .cases import y\n")
    (pkg / "study" / "cases.py").write_text("import ldem.cube\n")
    _, graph = _graph(str(pkg))
    assert graph["ldem.study"] == {"ldem.io", "ldem.study.cases"} and graph["ldem.study.cases"] == {"ldem.cube"}
    assert _upward_imports(graph) == ["ldem.cube (layer 1) imports ldem.runner (layer 3)"]
    assert _cycles(graph) == [["ldem.cube", "ldem.runner"]]


def test_no_long_module_without_its_reason():
    long = []
    for name, path in _modules():
        text = open(path).read()
        n = text.count("\n")
        doc = ast.get_docstring(ast.parse(text)) or ""
        if n > MAX_LINES and "Longer than 300 lines:" not in doc:
            long.append(f"{name}: {n} lines")
    assert not long, "modules over 300 lines with no 'Longer than 300 lines: <reason>' in their docstring: " + \
        ", ".join(long)



# -- ldem.study: one folder per registered study, the shared modules beside them -----------
STUDY = os.path.join(PACKAGE, "study")


def _registered_studies(study=STUDY):
    """{registered name: the module that registers it}, read from every register(Study("name", ...)) call."""
    found = {}
    for name, path in _modules(os.path.dirname(study)):
        if not name.startswith("ldem.study"):
            continue
        for node in ast.walk(ast.parse(open(path).read())):
            if isinstance(node, ast.Call) and getattr(node.func, "id", "") == "register" and node.args \
                    and isinstance(node.args[0], ast.Call) and getattr(node.args[0].func, "id", "") == "Study":
                found[ast.literal_eval(node.args[0].args[0])] = name
    return found


def _study_order(study=STUDY):
    """The study folders in the order study/__init__.py imports them (that of `ldem study`'s list)."""
    order = []
    for node in ast.parse(open(os.path.join(study, "__init__.py")).read()).body:
        if isinstance(node, ast.ImportFrom) and node.level == 1:
            names = [node.module.split(".")[0]] if node.module else [a.name for a in node.names]
            order += [n for n in names if os.path.isdir(os.path.join(study, n)) and n not in order]
    return order


def _defined(path):
    """The names a module's own body binds: its functions, classes, assignments and imports' names."""
    names = set()
    for node in ast.parse(open(path).read()).body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.Assign):
            names |= {t.id for t in node.targets if isinstance(t, ast.Name)}
        elif isinstance(node, ast.Import) or isinstance(node, ast.ImportFrom) and node.module:
            names |= {(a.asname or a.name).split(".")[0] for a in node.names}  # (`from . import x` is x itself)
    return names


def _study_shape(study=STUDY):
    """What breaks the study package's shape: a registered study that is not
    registered by the __init__ of its own folder (its name, a hyphen made an
    underscore), a folder that is no registered study, a shared module (a
    file at study/'s top) that imports a study's folder, a study that
    imports one listed after it (a study may build on an earlier one), and a
    name of a study's __init__ that hides a module of its folder (the
    package's attribute would be the name, not the module)."""
    prefix = "ldem.study."
    registered = _registered_studies(study)
    folders = {f for f in os.listdir(study) if os.path.isfile(os.path.join(study, f, "__init__.py"))}
    wrong = [f"study {n!r} is registered in {m}, not in {prefix}{n.replace('-', '_')} (its folder's __init__.py)"
             for n, m in sorted(registered.items()) if m != prefix + n.replace("-", "_")]
    wrong += [f"study/{f}/ is a folder of no registered study" for f in sorted(folders)
              if f not in {n.replace("-", "_") for n in registered}]
    _, graph = _graph(os.path.dirname(study))
    for f in sorted(folders):
        modules = {m[:-3] for m in os.listdir(os.path.join(study, f)) if m.endswith(".py")}
        wrong += [f"{prefix}{f}'s {n} hides its module {n}.py" for n in sorted(_defined(os.path.join(study, f,
                                                                                                 "__init__.py")) & modules)]
    order = _study_order(study)
    for mod, deps in sorted(graph.items()):
        parts = mod.split(".")
        if parts[:2] != ["ldem", "study"] or len(parts) < 3:
            continue  # ldem.study itself, the facade, imports every study
        studies = sorted(d for d in deps if d.startswith(prefix) and d.split(".")[2] in folders)
        if parts[2] not in folders:
            wrong += [f"{mod} (shared) imports the study {d}" for d in studies]
        elif parts[2] in order:
            wrong += [f"{mod} imports {d}, a study listed after it" for d in studies
                      if d.split(".")[2] in order and order.index(d.split(".")[2]) > order.index(parts[2])]
    return wrong


def test_each_registered_study_is_a_folder_of_its_name_and_the_shared_modules_import_none():
    """`ldem study NAME` is study/NAME/ (size-effect: size_effect/): its
    command, cases, tables and report in one folder; what studies share
    (cases, executors, tables, options, ...) sits at study/'s top level and
    imports no study; a study builds only on those listed before it."""
    assert {"size-effect", "beams", "seed-settings"} <= set(_registered_studies()), _registered_studies()
    assert _study_order()[:2] == ["size_effect", "damping"] and _study_order()[-1] == "seed_settings", _study_order()
    wrong = _study_shape()
    assert not wrong, "the study package's shape:\n" + "\n".join(wrong)


def test_the_study_check_sees_a_flat_study_a_stray_folder_a_hidden_module_and_imports_upward(tmp_path):
    study = tmp_path / "ldem" / "study"
    for folder in ("fine", "stray", "flat_one", "later"):
        (study / folder).mkdir(parents=True)
    (tmp_path / "ldem" / "__init__.py").write_text("")
    (study / "__init__.py").write_text("from . import fine, flat\nfrom .later import x\n")
    (study / "registry.py").write_text("def register(s):\n    return s\n")
    (study / "cases.py").write_text("from .fine import helper\n")
    (study / "fine" / "__init__.py").write_text("from ..registry import Study, register\nfrom ..later import y\n"
                                                "register(Study('fine', 'line', None, None))\n")
    (study / "later" / "__init__.py").write_text("from ..registry import Study, register\nfrom ..fine import z\n"
                                                 "register(Study('later', 'line', None, None))\n"
                                                 "from .tables import write\ndef tables(args):\n    pass\n")
    (study / "later" / "tables.py").write_text("def write():\n    pass\n")
    (study / "stray" / "__init__.py").write_text("")
    (study / "flat_one" / "__init__.py").write_text("")
    (study / "flat.py").write_text("from .registry import Study, register\n"
                                   "register(Study('flat-one', 'line', None, None))\n")
    assert _study_shape(str(study)) == [
        "study 'flat-one' is registered in ldem.study.flat, not in ldem.study.flat_one (its folder's __init__.py)",
        "study/stray/ is a folder of no registered study",
        "ldem.study.later's tables hides its module tables.py",
        "ldem.study.cases (shared) imports the study ldem.study.fine",
        "ldem.study.fine imports ldem.study.later, a study listed after it"]

# What a script may not do: run cases side by side or keep case folders (ldem.study does).
CASE_RUNNER_IMPORTS = {"multiprocessing", "concurrent.futures", "distributed", "dask"}
CASE_RUNNER_NAMES = {"run_case", "run_cases", "run_all", "case_dir", "finished", "is_finished", "_done"}


def _case_runner_parts(path):
    """The imports and function definitions of a script that make it a case runner."""
    found = []
    for node in ast.walk(ast.parse(open(path).read())):
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else [node.module or ""]
            found += [f"imports {n}" for n in names
                      if any(n == m or n.startswith(m + ".") for m in CASE_RUNNER_IMPORTS)]
        elif isinstance(node, ast.FunctionDef) and node.name in CASE_RUNNER_NAMES:
            found.append(f"defines {node.name}()")
        elif isinstance(node, ast.Attribute) and node.attr in ("ProcessPoolExecutor", "Pool"):
            found.append(f"uses {node.attr}")
    return found


def _files(folder):
    return sorted(os.listdir(os.path.join(ROOT, folder)))


def test_no_script_runs_cases_itself():
    """scripts/ keeps what users copy or run under YADE, dev/ the developers'
    tools; a series of runs with folders, resume and processes is a study
    (ldem.study)."""
    wrong = [f"{d}/{f}: {part}" for d in ("scripts", "dev") for f in _files(d) if f.endswith(".py")
             for part in _case_runner_parts(os.path.join(ROOT, d, f))]
    assert not wrong, "case runners in scripts/ or dev/:\n" + "\n".join(wrong)


def test_the_script_check_sees_a_case_runner(tmp_path):
    script = tmp_path / "runner.py"
    script.write_text("import multiprocessing\nfrom concurrent.futures import ProcessPoolExecutor\n"
                      "def finished(case):\n    return True\npool = multiprocessing.Pool(2)\n")
    assert _case_runner_parts(str(script)) == ["imports multiprocessing", "imports concurrent.futures",
                                               "defines finished()", "uses Pool"]


# What makes a file a developer's tool (dev/), never a user's copy: it times the
# benchmark program (ldem-bench, through ldem.bench or by its name).
DEV_TOOL_MARK = r"ldem[-_.]bench\b|from ldem import bench\b"


def _developer_tool_marks(path):
    import re
    return sorted(set(re.findall(DEV_TOOL_MARK, open(path).read())))


def test_scripts_hold_no_developer_tool():
    """scripts/ holds what users copy (issue 38 item 4); a benchmark, its MPI
    runs and the documentation's figures are in dev/."""
    wrong = [f"scripts/{f}: {m}" for f in _files("scripts")
             for m in _developer_tool_marks(os.path.join(ROOT, "scripts", f))]
    assert not wrong, "developer's tools in scripts/ (move them to dev/):\n" + "\n".join(wrong)
    # (the mark is the benchmark program; bench_threads.py times whole `ldem cube` runs instead)
    assert all(_developer_tool_marks(os.path.join(ROOT, "dev", f)) for f in _files("dev")
               if f.startswith("bench") and f != "bench_threads.py")


def test_the_tool_check_sees_a_benchmark(tmp_path):
    script = tmp_path / "timing.sh"
    script.write_text("bench=$(command -v ldem-bench)\n$bench --modules 48\n")
    assert _developer_tool_marks(str(script)) == ["ldem-bench"]
    script.write_text("import ldem.bench\nprint(ldem.bench.bench_program())\n")
    assert _developer_tool_marks(str(script)) == ["ldem.bench"]
    script.write_text("srun ldem cube --size 2.0  # a user's run, on a cluster\n")
    assert _developer_tool_marks(str(script)) == []


def test_architecture_names_every_script_and_tool():
    """ARCHITECTURE.md says what each file of scripts/ and dev/ is: a new one is
    placed and described, never left beside the others unexplained."""
    text = open(os.path.join(ROOT, "ARCHITECTURE.md")).read()
    unnamed = [f"{d}/{f}" for d in ("scripts", "dev") for f in _files(d) if f"`{f}`" not in text]
    assert not unnamed, "not in ARCHITECTURE.md: " + ", ".join(unnamed)


# -- the C++ core: a bar law is one header in pkg/ldem/laws/ ----------------------------
LAWS = os.path.join(ROOT, "pkg", "ldem", "laws")
LAW_INTERFACE = {"BarLaw.hpp", "SecantLaw.hpp", "Registry.hpp"}  # what every law shares, and the list of them


def _law_internals(header):
    """The names a law keeps to itself: its class, its namespace, and the functions in that namespace."""
    import re
    text = open(header).read()
    names = set(re.findall(r"^(?:class|using) (\w+(?:Law|Shape))\b", text, re.M))
    names |= set(re.findall(r"^struct (\w+Shape)\b", text, re.M))
    for ns in re.findall(r"^namespace (\w+) \{", text, re.M):
        if ns == "ldem":
            continue
        names.add(ns + "::")
        body = text.split(f"namespace {ns} {{", 1)[1].split(f"}}  // namespace {ns}", 1)[0]
        names |= set(re.findall(r"^inline [\w:<>]+ (\w+)\(", body, re.M))
        names |= set(re.findall(r"^struct (\w+)", body, re.M))
    return names


def _cpp_sources_outside_laws():
    for top in (os.path.join(ROOT, "pkg"), os.path.join(ROOT, "py", "src")):
        for folder, _, files in os.walk(top):
            if os.path.abspath(folder).startswith(os.path.abspath(LAWS)):
                continue
            for f in files:
                if f.endswith((".hpp", ".cpp")):
                    yield os.path.join(folder, f)


def _references(names, sources):
    import re
    found = []
    for path in sources:
        text = open(path).read()
        for name in names:
            pattern = re.escape(name) if name.endswith("::") else r"\b" + re.escape(name) + r"\b"
            if re.search(pattern, text):
                found.append(f"{os.path.relpath(path, ROOT)} names {name}")
    return found


def test_no_cpp_file_outside_the_laws_names_a_laws_internals():
    """computeInternalForces, barEnergies, Simulation and the bindings go through the
    law's interface (laws/BarLaw.hpp) and the registry: only pkg/ldem/laws/ names a
    law's class, namespace or functions (the law's own tests in tests/cpp may)."""
    headers = [os.path.join(LAWS, f) for f in sorted(os.listdir(LAWS)) if f.endswith(".hpp") and f not in LAW_INTERFACE]
    assert headers, "no law in pkg/ldem/laws/"
    internals = set().union(*map(_law_internals, headers))
    assert {"HillerborgLaw", "hillerborg::", "limitStrain", "secantRatio", "dissipatedEnergy"} <= internals, internals
    wrong = _references(internals, _cpp_sources_outside_laws())
    assert not wrong, "a law's internals named outside pkg/ldem/laws/:\n" + "\n".join(wrong)


def test_the_law_check_sees_a_direct_call(tmp_path):
    """The check above on a made-up source that calls the law's force directly."""
    src = tmp_path / "Simulation.cpp"
    src.write_text("double f = hillerborg::axialForce(eps, k, EA, epsP, epsR);\nlimitStrain(1, 2, 3, 4, 5);\n")
    internals = _law_internals(os.path.join(LAWS, "Hillerborg.hpp"))
    assert sorted(_references(internals, [str(src)])) == [
        f"{os.path.relpath(src, ROOT)} names {n}" for n in sorted(["axialForce", "hillerborg::", "limitStrain"])]
