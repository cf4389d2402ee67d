# Measured topography files: each listed file is read once into a labelled surface, swept, and plotted.


rule write_example_topography:
    output:
        "results/example_topographies/{example}.txt",
    params:
        example=lambda wildcards: config["example_topographies"][wildcards.example],
    log:
        "logs/write_example_topography/{example}.log",
    wildcard_constraints:
        example="|".join(EXAMPLES) or "(?!)",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/write_example_topography.py"


rule read_measured_surface:
    input:
        lambda wildcards: measured_entry(wildcards)["path"],
    output:
        "results/surfaces/{study}/{surface}.nc",
    params:
        surface=measured_entry,
    log:
        "logs/read_measured_surface/{study}/{surface}.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/read_surface.py"


rule run_measured_study:
    input:
        surface="results/surfaces/{study}/{surface}.nc",
    output:
        "results/{study}/{surface}.nc",
    params:
        spec=measured_spec,
        material=lookup(dpath="material", within=config),
        solver=lookup(dpath="solver", within=config),
        dask=lookup(dpath="dask", within=config),
        scheduler_file=shared_scheduler_file,
        checkpoints="results/checkpoints/{study}/{surface}",
    threads: sweep_threads
    log:
        "logs/run_study/{study}/{surface}.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/run_study.py"


rule plot_measured_area_load:
    input:
        data="results/measured_area_load/{surface}.nc",
        surface="results/surfaces/measured_area_load/{surface}.nc",
    output:
        report(
            "results/figures/measured_area_load/{surface}.png",
            caption="../report/measured_area_load.rst",
            category="Measured surfaces",
        ),
    log:
        "logs/plot/measured_area_load/{surface}.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/plot_measured_area_load.py"
