"""The study's proposal for coarse meshes, tested at a point of settings (the
fitted one): the mesh study's "criterion" law (ldem.study.mesh_tables.criterion_law:
eps_p = mean peak / E, CV(G_f) = CV(U_num/U_min), c_a = 0.1385 E[U_num/U_min]
of fine uniform cubes of side L at those settings) on a coarse cube of modules
L, against the fine cubes of the same size in a study run at the same point
(`ldem study seed-settings --study`). The coarse cube is driven at the fine
one's rate and keeps the study's tail (settings.tail_settings); both run to
separation."""
from __future__ import annotations

import dataclasses
import json
import os
from typing import List, Sequence

from ... import io
from ...cube import CubeTest
from ..executors import run_cases
from ..mesh import UNIFORM_FINAL_STRAIN, law_tests
from ..mesh.tables import criterion_law, variant_law
from ..settings import tail_settings
from ..tables import case_row, mean_cv
from .fit import fit_variant

BOUNDS = {"peak": 0.10, "U_num": 0.20}  # the mesh study's verdict: peak within 10 %, U_num within 20 %


def proposal_tests(point: dict, module: float, size: float, seeds: int, law: dict, threads: int = 1) -> List[CubeTest]:
    """The coarse uniform cubes: modules of side `module`, the criterion's law, the point's settings at `size`."""
    base = CubeTest()
    over = fit_variant(point).overrides(size)
    return [CubeTest(size=size, L0=module, load="uniform", seed=k, threads=threads, final_strain=UNIFORM_FINAL_STRAIN,
                     **{**over, **tail_settings(size), **variant_law("criterion", law, base)})
            for k in range(1, seeds + 1)]


def run_proposal(point: dict, fine_study: str, out: str, module: float = 0.06, size: float = 0.96, seeds: int = 6,
                 jobs: int = 1, threads: int = 1) -> dict:
    """Runs the law cubes and the coarse cubes into out; writes proposal.md and
    proposal.json; returns the law, the coarse and fine means and their errors."""
    over = fit_variant(point).overrides
    laws = [dataclasses.replace(t, threads=threads, **over(t.size)) for t in law_tests([module], seeds)]
    law = criterion_law([case_row(s) for s in run_cases(laws, os.path.join(out, "law"), jobs=jobs)], CubeTest())
    coarse = [case_row(s) for s in run_cases(proposal_tests(point, module, size, seeds, law, threads),
                                             os.path.join(out, "coarse"), jobs=jobs)]
    fine = [r for r in io.read_table(os.path.join(fine_study, "cases.csv"))
            if r["load"] == "uniform" and r["size_m"] == size]
    if not fine:
        raise ValueError(f"{fine_study}/cases.csv has no uniform {size:g} m cube")
    result = {"point": point, "module_m": module, "size_m": size, "law": law,
              "coarse": _means(coarse), "fine": _means(fine)}
    result["errors"] = {k: result["coarse"][k] / result["fine"][k] - 1 for k in ("peak", "U_num")}
    io.write_text(os.path.join(out, "proposal.json"), json.dumps(result, indent=2))
    io.write_text(os.path.join(out, "proposal.md"), proposal_table(result))
    return result


def _means(rows: Sequence[dict]) -> dict:
    sep = [r for r in rows if r["separated"] in (True, "True")]
    return {"seeds": len(rows), "separated": len(sep), "peak": mean_cv([r["peak_stress_MPa"] for r in rows])[0],
            "U_num": mean_cv([r["U_num_J"] for r in sep])[0] if sep else float("nan"),
            "U_ratio": mean_cv([r["U_ratio"] for r in sep])[0] if sep else float("nan")}


def proposal_table(r: dict) -> str:
    law, c, f, e = r["law"], r["coarse"], r["fine"], r["errors"]
    lines = [f"Coarse modules of {r['module_m']:g} m on the {r['size_m']:g} m cube, the criterion's law from "
             f"{law['seeds']} fine cubes of side {r['module_m']:g} m: eps_p {law['eps_p']:.4g}, CV(G_f) "
             f"{law['Gf_cv']:.4g}, c_a {law['c_a']:.4g} (E[U_num/U_min] {law['U_ratio_mean']:.4f}).", "",
             "| | seeds (separated) | peak [MPa] | U_num [J] | U_num/U_min |", "|---|---|---|---|---|"]
    for name, m in (("fine lattice", f), ("coarse, criterion", c)):
        lines.append(f"| {name} | {m['seeds']} ({m['separated']}) | {m['peak']:.4f} | {m['U_num']:.4g} | "
                     f"{m['U_ratio']:.4f} |")
    verdict = ", ".join(f"{k} {100 * e[k]:+.1f} % ({'within' if abs(e[k]) <= BOUNDS[k] else 'beyond'} "
                        f"{100 * BOUNDS[k]:g} %)" for k in ("peak", "U_num"))
    return "\n".join(lines + ["", f"Coarse against fine: {verdict}."]) + "\n"
