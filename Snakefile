# contactlib parametric studies: `snakemake --cores 2` regenerates every dataset and figure.
from snakemake.utils import min_version

min_version("9.0")


configfile: "workflow/config.yaml"


report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"
include: "workflow/rules/surfaces.smk"
include: "workflow/rules/sweep.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/measured.smk"


onstart:
    record_run()
    start_cluster()


onsuccess:
    stop_cluster()


onerror:
    stop_cluster()


rule all:
    input:
        expand("results/{study}.nc", study=STUDIES),
        expand("results/figures/{study}.png", study=STUDIES),
        TABLES,
        MEASURED_TARGETS,
