"""Studies: many tests (cubes by size x seed x load or one parameter swept,
beams, any test object with parameters() and run()), run in parallel
processes or on a dask.distributed cluster, resumable, aggregated into tables
(the reference study's: LDEM_SPEC section 6).

    ldem study                                  the registered studies, a line each
    ldem study size-effect --out DIR [--sizes 0.12,0.24] [--seeds 6] [--loads uniform,triangular] [--jobs J]
    ldem study damping     --out DIR [--size 0.96] [--zetas 0.02,2]
    ldem study mesh        --out DIR [--sizes 0.48,0.72,0.96] [--modules 0.04,0.06,0.08,0.12] [--reference DIR]
    ldem study refinement  --out DIR [--sizes 0.12,0.24] [--L0s 0.02,0.01] [--corr-lengths 0,0.02]
    ldem study ablation    --out DIR [--size 0.48] [--seeds 3]     (or --table RUNS.jsonl)
    ldem study beams       COMMAND ...   (calibrate, predict --eps-p E, curves, compare, size-effect, ...)
    ldem study validation  NAME [--seeds 6] [--calibrate-only]
    ldem study calibration --E --nu --ft --L0 (--fc | --GF) [--out material.json]
    ldem study fracture-energy MATERIAL.json [--seeds 3] [--jobs J]

A study is one module: its cases, tables and report, then its options
(add_arguments), its run from them with the lines it prints, and
register(Study(name, line, add_arguments, run)) (registry); `ldem study NAME`
is each registered one (command). Options of a parameter (--strain-rate,
--size, the loads' choices, ...) come from the parameter table (options).

Modules, each importing only those listed before it:
  registry     the studies by name (Study, register)
  cases        case names and folders, what is finished, one case (any test object) run into its folder
  settings     what the size-effect study sets beside the cubes' defaults (stops, tail, pace), its cases
  tables       one row per case, aggregation per (load, size), the fractal fit
  executors    running the unfinished cases: in turn, in processes, on dask
  options      what the studies' command lines share: common options, a parameter's option, the checks
  size_effect  the size-effect study: runs, tables, fractal.json, report
  damping      the damping study
  mesh_tables  the mesh study's laws (laws.csv), its tables beside the fine lattice, and the verdict
  mesh_report  its figures and report.md
  mesh         coarse modules with the study's criterion against the fine lattice (laws, cases)
  refinement   the same cubes with finer modules
  concrete     the virtual prism and the calibration from a laboratory's properties (`calibration`)
  fracture_energy  the lattice's own G_F on the virtual RILEM beam (`fracture-energy`)
  ablation     one factor at a time on a cube, stopped past the peak
  beams        the Gregoire et al. (2013) beams: specimens, calibration, runs, predictions.csv
  beam_tables  their size effect (Bazant's law fitted per notch) and curve tables
  beam_comparison  the prediction against the measurements
  beam_diagnosis  one factor at a time against the prediction
  beam_report  their figures
  beam_command  `ldem study beams`: calibrate, predict, uniform, curves, compare, size-effect, diagnose, calibrated
  validation   blind predictions of specimen files with the calibrated concrete
  command      the `ldem study` command line, from the registry
"""
from ..io import read_table as read_csv, write_table as write_csv  # noqa: F401
from .cases import (Named, case_dir, case_name, is_finished, load_case, load_curve,  # noqa: F401
                    load_curves, load_summary, run_case)
from .settings import damping_tests, size_effect_tests, study_settings  # noqa: F401
from .executors import run_cases  # noqa: F401
from .size_effect import STUDY_SIZES, run_size_effect  # noqa: F401
from .damping import run_damping  # noqa: F401
from . import mesh, mesh_tables, refinement  # noqa: F401
# Each study registers itself as its module is imported (size_effect, damping, mesh, refinement above):
# this order is `ldem study`'s.
from . import concrete, fracture_energy, beam_command, ablation, validation, seed_settings  # noqa: F401
from .tables import (B0, CASE_COLUMNS, REFERENCE_UNIFORM, SUMMARY_COLUMNS, aggregate, case_row,  # noqa: F401
                     fit_fractal, fractal_fits, mean_cv)
from ..curves import mean_curve, mean_curve_peak  # noqa: F401
from .command import add_parser  # noqa: F401
