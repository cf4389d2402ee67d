import json

from snakemake.utils import validate

from contactlib import studies


validate(config, schema="../schemas/config.schema.yaml")

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
