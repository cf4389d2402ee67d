"""The plumbing of a parametric study, apart from the numerics: fan a point function over a parameter grid with
checkpoints (:mod:`.sweep`), one Dask cluster shared by a workflow's studies (:mod:`.cluster`) and the processes'
lifeline to Snakemake (:mod:`.lifeline`). Calls the library through its public API only."""
