rule run_study:
    output:
        "results/{study}.nc",
    params:
        spec=study_spec,
        material=lookup(dpath="material", within=config),
        solver=lookup(dpath="solver", within=config),
        dask=lookup(dpath="dask", within=config),
        scheduler_file=shared_scheduler_file,
        checkpoints="results/checkpoints/{study}",
    threads: sweep_threads
    log:
        "logs/run_study/{study}.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/run_study.py"
