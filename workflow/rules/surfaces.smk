rule generate_surfaces:
    output:
        "results/surfaces/{study}.nc",
    params:
        spec=study_spec,
    log:
        "logs/generate_surfaces/{study}.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/generate_surfaces.py"
