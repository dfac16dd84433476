# Figures (PNG for the report, PDF for print) and the per-scene manifest.


rule figure:
    input:
        unpack(get_figure_inputs),
    output:
        png=report(
            "results/{scene}/figures/{fig}.png",
            caption="../report/figure.rst",
            category="{scene}",
        ),
        pdf="results/{scene}/figures/{fig}.pdf",
    log:
        "results/{scene}/logs/figures/{fig}.log",
    params:
        plots_code=PLOTS_CODE,
        options=get_figure_options,
    script:
        "../scripts/figure.py"


rule manifest:
    input:
        get_scene_targets,
    output:
        "results/{scene}/MANIFEST.txt",
    log:
        "results/{scene}/logs/manifest.log",
    script:
        "../scripts/manifest.py"
