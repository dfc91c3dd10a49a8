"""The files of runs and studies, and the registry of writers by name.

    files        the output folder, whole-or-absent files (atomic), text
    registry     register_writer / open_writers: a run is given writer names
    tables       curve.csv ("curve"), summary.json ("summary"), study tables
    vtk          bars.vtu, crack.vtu, their series and .pvd/.pvtu ("vtk")
    checkpoints  checkpoint.npz ("checkpoint"), restarts; final_state.npz ("final_state"), extensions
    figures      curve/energies/cracks pictures ("figures"), slice.npz ("slice")

A new writer is a module here that ends with register_writer(name, ...) and
is imported below; no runner changes. Writers take data; nothing here
computes physics."""
from .files import atomic, prepare_dir, write_text  # noqa: F401
from .registry import Run, check_writers, describe_writers, open_writers, register_writer, writer_names  # noqa: F401
from .tables import (CurveCsv, cut_curve_after, read_curve, read_summary, read_table, write_summary,  # noqa: F401
                     write_table)
from .vtk import (VTU_POINT_ARRAYS, Snapshots, bar_arrays, vtu_cell_arrays, write_bars, write_pvd, write_pvtu,  # noqa: F401
                  write_vtu)
from .checkpoints import (CHECKPOINT, FINAL_STATE, Checkpoints, case_checkpoint, saved_step,  # noqa: F401
                          discard_checkpoint, read_checkpoint, restore, write_checkpoint)
from .figures import read_slice, write_slice  # noqa: F401
