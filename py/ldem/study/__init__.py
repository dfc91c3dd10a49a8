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

A study is one folder, named as it is registered (a hyphen becomes an
underscore: size-effect is size_effect/): its __init__ holds its options
(add_arguments), its run from them with the lines it prints, and
register(Study(name, line, add_arguments, run)) (registry); its cases, tables
and report sit beside it in the folder when they outgrow it. `ldem study NAME`
is each registered one (command). Options of a parameter (--strain-rate,
--size, the loads' choices, ...) come from the parameter table (options).

What the studies share are the modules here, each importing only those listed
before it, never a study:
  registry     the studies by name (Study, register)
  cases        case names and folders, what is finished, one case (any test object) run into its folder
  settings     what the size-effect study sets beside the cubes' defaults (stops, tail, pace), its cases
  tables       one row per case, aggregation per (load, size), the fractal fit
  executors    running the unfinished cases: in turn, in processes, on dask
  options      what the studies' command lines share: common options, a parameter's option, the checks
  located      a case finished here, in a reference study, or as a row of an earlier run's cases.csv
  mc2010       fib Model Code 2010's properties of a concrete from its compressive strength
  concrete     the virtual direct tension prism and the calibration of a concrete on it
  curve_quantities, curve_report   what is read off a curve past its peak, its table and figure
  command      the `ldem study` command line, from the registry

The studies, in the order `ldem study` lists them (a study may use an earlier
one's pieces: refinement and seed_settings mesh's laws, seed_settings the
size-effect run, validation the beams' stop):
  size_effect  sizes x seeds x loads: tables, fractal.json, report
  damping      one cube at several damping ratios
  mesh         coarse modules with the study's criterion against the fine lattice (+ tables, report)
  refinement   the same cubes with finer modules
  calibration  the lattice material of a concrete from a laboratory's properties
  fracture_energy  the lattice's own G_F on the virtual RILEM beam
  beams        the Gregoire et al. (2013) beams: cases (specimens, calibration, runs, predictions.csv),
               tables, report, comparison, diagnosis, whole_curves, transfer; __init__: its sub-commands
  ablation     one factor at a time on a cube, stopped past the peak
  validation   blind predictions of specimen files with the calibrated concrete
  criteria     is the load quasi-static: criteria (a)-(c) on five specimens at their rate and a quarter of it
  seed_settings  the settings the reference study does not report, one at a time
"""
from ..io import read_table as read_csv, write_table as write_csv  # noqa: F401
from .cases import (Named, case_dir, case_name, is_finished, load_case, load_curve,  # noqa: F401
                    load_curves, load_summary, run_case)
from .settings import damping_tests, size_effect_tests, study_settings  # noqa: F401
from .executors import run_cases  # noqa: F401
from .size_effect import STUDY_SIZES, run_size_effect  # noqa: F401
from .damping import run_damping  # noqa: F401
from . import mesh, refinement  # noqa: F401
# Each study registers itself as its package is imported (size_effect, damping, mesh, refinement above):
# this order is `ldem study`'s.
from . import concrete, calibration, fracture_energy, beams, ablation, validation, criteria, seed_settings  # noqa: F401
from .tables import (B0, CASE_COLUMNS, REFERENCE_UNIFORM, SUMMARY_COLUMNS, aggregate, case_row,  # noqa: F401
                     fit_fractal, fractal_fits, mean_cv)
from ..curves import mean_curve, mean_curve_peak  # noqa: F401
from .command import add_parser  # noqa: F401
