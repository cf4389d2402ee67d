rule plot_validation:
    input:
        data="results/validation.nc",
    output:
        report(
            "results/figures/validation.png",
            caption="../report/validation.rst",
            category="Validation",
        ),
    log:
        "logs/plot/validation.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/plot_validation.py"


rule plot_area_load:
    input:
        data="results/area_load.nc",
        surfaces=surfaces_of("area_load"),
    output:
        report(
            "results/figures/area_load.png",
            caption="../report/area_load.rst",
            category="Rough contact",
        ),
    log:
        "logs/plot/area_load.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/plot_area_load.py"


rule plot_anisotropy:
    input:
        data="results/anisotropy.nc",
        surfaces=surfaces_of("anisotropy"),
    output:
        report(
            "results/figures/anisotropy.png",
            caption="../report/anisotropy.rst",
            category="Rough contact",
        ),
    log:
        "logs/plot/anisotropy.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/plot_anisotropy.py"


rule plot_speed_vs_error:
    input:
        data="results/speed_vs_error.nc",
    output:
        report(
            "results/figures/speed_vs_error.png",
            caption="../report/speed_vs_error.rst",
            category="Accuracy",
        ),
    log:
        "logs/plot/speed_vs_error.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/plot_speed_vs_error.py"


rule tabulate_speed_vs_error:
    input:
        data="results/speed_vs_error.nc",
    output:
        "results/speed_vs_error_table.md",
    params:
        targets=lookup(dpath="tables/speed_vs_error/targets", within=config),
    log:
        "logs/tabulate/speed_vs_error.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/tabulate_speed_vs_error.py"


rule plot_fig5_friction_area:
    input:
        data="results/fig5_friction_area.nc",
    output:
        report(
            "results/figures/fig5_friction_area.png",
            caption="../report/fig5_friction_area.rst",
            category="Friction on thin layers",
        ),
    params:
        panels=lookup(dpath="figures/fig5_friction_area", within=config),
    log:
        "logs/plot/fig5_friction_area.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/plot_fig5_friction_area.py"


rule plot_fig6a_interlocking:
    input:
        data="results/fig6a_interlocking.nc",
    output:
        report(
            "results/figures/fig6a_interlocking.png",
            caption="../report/fig6a_interlocking.rst",
            category="Friction on thin layers",
        ),
    log:
        "logs/plot/fig6a_interlocking.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/plot_fig6a_interlocking.py"


rule plot_fig2_viscoelastic_map:
    input:
        data="results/fig2_viscoelastic_map.nc",
    output:
        report(
            "results/figures/fig2_viscoelastic_map.png",
            caption="../report/fig2_viscoelastic_map.rst",
            category="Viscoelastic sliding",
        ),
    log:
        "logs/plot/fig2_viscoelastic_map.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/plot_fig2_viscoelastic_map.py"


rule plot_fig3_anisotropy_polar:
    input:
        data="results/fig3_anisotropy_polar.nc",
    output:
        report(
            "results/figures/fig3_anisotropy_polar.png",
            caption="../report/fig3_anisotropy_polar.rst",
            category="Viscoelastic sliding",
        ),
    log:
        "logs/plot/fig3_anisotropy_polar.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/plot_fig3_anisotropy_polar.py"


rule plot_fig6b_viscoelastic_layer:
    input:
        data="results/fig6b_viscoelastic_layer.nc",
    output:
        report(
            "results/figures/fig6b_viscoelastic_layer.png",
            caption="../report/fig6b_viscoelastic_layer.rst",
            category="Viscoelastic sliding",
        ),
    log:
        "logs/plot/fig6b_viscoelastic_layer.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/plot_fig6b_viscoelastic_layer.py"


rule plot_friction_speed:
    input:
        data="results/friction_speed.nc",
    output:
        report(
            "results/figures/friction_speed.png",
            caption="../report/friction_speed.rst",
            category="Viscoelastic sliding",
        ),
    log:
        "logs/plot/friction_speed.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/plot_friction_speed.py"
rule plot_two_scale:
    input:
        data="results/two_scale.nc",
    output:
        report(
            "results/figures/two_scale.png",
            caption="../report/two_scale.rst",
            category="Two-scale method",
        ),
    log:
        "logs/plot/two_scale.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/plot_two_scale.py"
rule plot_two_scale_transient:
    input:
        data="results/two_scale_transient.nc",
    output:
        report(
            "results/figures/two_scale_transient.png",
            caption="../report/two_scale_transient.rst",
            category="Two-scale method",
        ),
    log:
        "logs/plot/two_scale_transient.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/plot_two_scale_transient.py"
rule plot_fig4_adhesive_layers:
    input:
        data="results/fig4_adhesive_layers.nc",
    output:
        report(
            "results/figures/fig4_adhesive_layers.png",
            caption="../report/fig4_adhesive_layers.rst",
            category="Adhesion on thin layers",
        ),
    log:
        "logs/plot/fig4_adhesive_layers.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/plot_fig4_adhesive_layers.py"


rule plot_adhesive_rough:
    input:
        data="results/adhesive_rough.nc",
    output:
        report(
            "results/figures/adhesive_rough.png",
            caption="../report/adhesive_rough.rst",
            category="Adhesion on rough surfaces",
        ),
    log:
        "logs/plot/adhesive_rough.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/plot_adhesive_rough.py"


rule plot_viscoelastic_transient:
    input:
        data="results/viscoelastic_transient.nc",
    output:
        report(
            "results/figures/viscoelastic_transient.png",
            caption="../report/viscoelastic_transient.rst",
            category="Viscoelastic time stepping",
        ),
    log:
        "logs/plot/viscoelastic_transient.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/plot_viscoelastic_transient.py"
rule plot_reciprocating:
    input:
        data="results/reciprocating.nc",
    output:
        report(
            "results/figures/reciprocating.png",
            caption="../report/reciprocating.rst",
            category="Viscoelastic time stepping",
        ),
    log:
        "logs/plot/reciprocating.log",
    conda:
        "../envs/contactlib.yaml"
    script:
        "../scripts/plot_reciprocating.py"
