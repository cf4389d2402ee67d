rule generate_surfaces:
    output:
        "results/surfaces/{study}.nc",
    params:
        spec=study_spec,
    log:
        "logs/generate_surfaces/{study}.log",
    script:
        "../scripts/generate_surfaces.py"
