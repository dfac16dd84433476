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


# a local rule run inside the Snakemake process: hashing a few files is not worth a process start-up
localrules:
    manifest,


rule manifest:
    input:
        get_scene_targets,
    output:
        "results/{scene}/MANIFEST.txt",
    log:
        "results/{scene}/logs/manifest.log",
    run:
        from vcor.io import write_manifest

        open(log[0], "w").close()
        write_manifest(wildcards.scene, input, output[0])
