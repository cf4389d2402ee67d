"""Fan one study's grid over Dask (contactlib.pipeline.sweep.run_grid) and write results/{study}.nc."""

import functools
import json
import os
import sys

from contactlib.pipeline import cluster, lifeline, sweep

from contactlib import studies


def main(sm):
    # not one second longer than Snakemake: killed, it must not leave this sweep and its workers running
    tie = lifeline.exit_with_parent()
    spec, material, solver, dask = sm.params.spec, sm.params.material, sm.params.solver, dict(sm.params.dask)
    log_file = open(sm.log[0], "w")

    def emit(line):
        for stream in (log_file, sys.stderr):
            print(f"{spec['name']}: {line}", file=stream, flush=True)

    emit(f"process {os.getpid()} exits with its parent {os.getppid()} ({tie})")
    study = studies.STUDIES[spec["name"]]
    solver = dict(solver)
    path_dim = study.get("path_dim") if solver.pop("warm_start") else None
    constants = {**material, **solver, **spec["constants"]}
    if study.get("ladder_dim"):  # e.g. every tol of the grid, so one solve serves them all
        constants[f"{study['ladder_dim']}_ladder"] = sorted(spec["grid"][study["ladder_dim"]])
    shared = dask.pop("shared")
    if not dask["scheduler_address"] and not shared:  # a LocalCluster sized to the cores Snakemake gave this job
        dask["n_workers"] = max(1, min(dask["n_workers"], sm.threads // dask["threads_per_worker"]))
    config = {"study": spec, "material": material, "solver": {**solver, "warm_start": path_dim is not None},
              "dask": dask}
    # a swept nu is a coordinate, not a global attribute
    scene = {} if "nu" in spec["grid"] else {"nu": material["nu"], "E_star": material["E"] / (1 - material["nu"] ** 2)}
    inputs = study["dataset_attrs"](constants) if "dataset_attrs" in study else {}  # e.g. a measured file's checksum
    # the run's shared cluster (started by the Snakefile's onstart), else one of this job's own
    scheduler_file = sm.params.scheduler_file or None
    with cluster.open_client(**dask, scheduler_file=scheduler_file, log=emit) as client:
        ds = sweep.run_grid(
            functools.partial(study["point"], **constants),
            spec["grid"],
            client=client,
            checkpoint_dir=sm.params.checkpoints,
            fingerprint=json.dumps({**constants, **inputs}, sort_keys=True),
            fft_shapes=study["fft_shapes"](spec["grid"], constants),
            labels=studies.STUDY_VARIABLES,
            attrs={"title": spec["title"], "source": f"contactlib.studies.{study['point'].__name__}",
                   "study": spec["name"], "scale": spec["scale"], "config": json.dumps(config, sort_keys=True),
                   "length_scale": "1 m", "E": material["E"], **scene, **inputs},
            progress=emit,
            path_dim=path_dim,
            group_dims=study.get("group_dims", ()),
        )
    ds = studies.add_error_estimate(ds, spec["name"], constants)
    sweep.write_netcdf(ds, sm.output[0], sweep_dims=spec["grid"])
    emit(f"wrote {sm.output[0]}: {dict(ds.sizes)}, {int((ds.status != 0).sum())} failed points")


if __name__ == "__main__":  # Dask's spawned workers re-import this file as __mp_main__
    main(snakemake)  # noqa: F821 (injected by Snakemake)
