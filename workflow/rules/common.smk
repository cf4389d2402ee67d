import json
import os
import subprocess
import sys
from pathlib import Path

from snakemake.utils import validate

from contactlib.pipeline import lifeline

from contactlib import studies


validate(config, schema="../schemas/config.schema.yaml")

# Recovery after a hard kill, with no extra flags: the default profile (profiles/default, beside the Snakefile) sets
# rerun-incomplete, and a lock left by a run that is gone is released here, before Snakemake locks.
RUN_RECORD = Path(".snakemake/contactlib_run.pid")


def _recorded_pid():
    try:
        return int(RUN_RECORD.read_text().split()[0])
    except (OSError, ValueError, IndexError):
        return None


def record_run():
    """Note this run's snakemake pid, unless a live run holds the record."""
    owner = _recorded_pid()
    if owner is None or owner == os.getpid() or not lifeline.running(owner, "snakemake"):
        RUN_RECORD.parent.mkdir(exist_ok=True)
        RUN_RECORD.write_text(f"{os.getpid()}\n")


def release_stale_lock():
    """Remove Snakemake's locks when the run that took them (its recorded pid) is dead."""
    locks = sorted(Path(".snakemake/locks").glob("*.lock"))
    owner = _recorded_pid()
    if not locks or owner is None or lifeline.running(owner, "snakemake"):
        return
    for lock in locks:
        lock.unlink(missing_ok=True)
    RUN_RECORD.unlink(missing_ok=True)
    print(f"contactlib: released the lock of snakemake run {owner}, which is gone (killed?); finished points "
          "resume from results/checkpoints", file=sys.stderr)


release_stale_lock()

# one dataset per study, except the studies of measured files: one dataset per file (rules/measured.smk)
STUDIES = [s for s in config["studies"] if not studies.STUDIES[s].get("per_surface")]
MEASURED_STUDIES = [s for s in config["studies"] if studies.STUDIES[s].get("per_surface")]
SURFACE_STUDIES = [s for s in STUDIES if "surface_keys" in studies.STUDIES[s]]
TABLES = [f"results/{s}_table.md" for s in STUDIES if s in config.get("tables", {})]


wildcard_constraints:
    study="|".join(STUDIES + MEASURED_STUDIES) or "(?!)",


def study_spec(wildcards):
    """The study's title, constants (study level, then scale level) and grid at config['scale']."""
    study = config["studies"][wildcards.study]
    block = study[config["scale"]]
    return {
        "name": wildcards.study,
        "title": study["title"],
        "scale": config["scale"],
        "constants": {**study["constants"], **block["constants"]},
        "grid": block["grid"],
    }


# One Dask LocalCluster for every sweep of the run (config dask.shared): started by onstart when the run has
# sweeps to do, stopped by onsuccess/onerror, ended with Snakemake if Snakemake is killed (contactlib.pipeline.cluster).
SHARED_CLUSTER_FILE = Path(".snakemake/contactlib_dask.json")
SWEEP_RULES = {"run_study", "run_measured_study"}
_cluster_process = []


def shared_cluster():
    return bool(config["dask"]["shared"]) and not config["dask"]["scheduler_address"]


def shared_scheduler_file(wildcards):
    return str(SHARED_CLUSTER_FILE) if shared_cluster() else ""


def sweep_threads(wildcards):
    """Cores the study's own Dask cluster occupies (one when its sweep goes to a shared or existing one)."""
    dask = config["dask"]
    return 1 if (dask["scheduler_address"] or shared_cluster()) else dask["n_workers"] * dask["threads_per_worker"]


def start_cluster():
    """Start the run's shared cluster if a sweep will run (its workers take the run's cores)."""
    if not shared_cluster() or not any(job.rule.name in SWEEP_RULES for job in workflow.dag.needrun_jobs()):
        return
    dask = config["dask"]
    workers = max(1, min(dask["n_workers"], workflow.cores // dask["threads_per_worker"]))
    SHARED_CLUSTER_FILE.unlink(missing_ok=True)
    Path("logs").mkdir(exist_ok=True)
    with open("logs/dask_cluster.log", "w") as log:
        _cluster_process.append(subprocess.Popen(
            [sys.executable, "-m", "contactlib.pipeline.cluster", "--scheduler-file", str(SHARED_CLUSTER_FILE),
             "--n-workers", str(workers), "--threads-per-worker", str(dask["threads_per_worker"])],
            stdout=log, stderr=subprocess.STDOUT))


def stop_cluster():
    for process in _cluster_process:
        process.terminate()
        try:
            process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            process.kill()
    _cluster_process.clear()


def surfaces_of(study):
    return f"results/surfaces/{study}.nc" if study in SURFACE_STUDIES else []


def measured_entries(study):
    """The study's surface entries by name (names must be unique: each names a dataset and a figure)."""
    entries = config["studies"][study]["surfaces"]
    names = [e["name"] for e in entries]
    if len(set(names)) != len(names):
        raise ValueError(f"studies/{study}/surfaces: names must be unique, got {names}")
    return {e["name"]: e for e in entries}


MEASURED = {study: measured_entries(study) for study in MEASURED_STUDIES}
MEASURED_TARGETS = [
    target
    for study, entries in MEASURED.items()
    for surface in entries
    for target in (f"results/{study}/{surface}.nc", f"results/figures/{study}/{surface}.png")
]
EXAMPLES = list(config.get("example_topographies", {}))


def measured_entry(wildcards):
    return MEASURED[wildcards.study][wildcards.surface]


def measured_spec(wildcards):
    """study_spec plus the prepared surface file the points read."""
    spec = study_spec(wildcards)
    spec["constants"]["surface_file"] = f"results/surfaces/{wildcards.study}/{wildcards.surface}.nc"
    spec["surface"] = wildcards.surface
    return spec
