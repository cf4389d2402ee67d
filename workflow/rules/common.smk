import json
import os
import sys
from pathlib import Path

from snakemake.utils import validate

from contactlib import studies


validate(config, schema="../schemas/config.schema.yaml")

# Recovery after a hard kill, with no extra flags: the default profile (workflow/profiles/default) sets
# rerun-incomplete, and a lock left by a run that is gone is released here, before Snakemake locks.
RUN_RECORD = Path(".snakemake/contactlib_run.pid")


def _snakemake_alive(pid):
    """Whether ``pid`` is a live snakemake process (a recycled pid running something else is not)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    cmdline = Path(f"/proc/{pid}/cmdline")
    return not cmdline.exists() or b"snakemake" in cmdline.read_bytes()


def _recorded_pid():
    try:
        return int(RUN_RECORD.read_text().split()[0])
    except (OSError, ValueError, IndexError):
        return None


def record_run():
    """Note this run's snakemake pid, unless a live run holds the record."""
    owner = _recorded_pid()
    if owner is None or owner == os.getpid() or not _snakemake_alive(owner):
        RUN_RECORD.parent.mkdir(exist_ok=True)
        RUN_RECORD.write_text(f"{os.getpid()}\n")


def release_stale_lock():
    """Remove Snakemake's locks when the run that took them (its recorded pid) is dead."""
    locks = sorted(Path(".snakemake/locks").glob("*.lock"))
    owner = _recorded_pid()
    if not locks or owner is None or _snakemake_alive(owner):
        return
    for lock in locks:
        lock.unlink(missing_ok=True)
    RUN_RECORD.unlink(missing_ok=True)
    print(f"contactlib: released the lock of snakemake run {owner}, which is gone (killed?); finished points "
          "resume from results/checkpoints", file=sys.stderr)


release_stale_lock()

STUDIES = list(config["studies"])
SURFACE_STUDIES = [s for s in STUDIES if "surface_keys" in studies.STUDIES[s]]
TABLES = [f"results/{s}_table.md" for s in STUDIES if s in config.get("tables", {})]


wildcard_constraints:
    study="|".join(STUDIES),


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


def sweep_threads(wildcards):
    """Cores the local Dask cluster occupies (one when the sweep goes to an existing scheduler)."""
    dask = config["dask"]
    return 1 if dask["scheduler_address"] else dask["n_workers"] * dask["threads_per_worker"]


def surfaces_of(study):
    return f"results/surfaces/{study}.nc" if study in SURFACE_STUDIES else []
