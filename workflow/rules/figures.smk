# Figures (PNG for the report, PDF for print) and the per-scene manifest.
#
# One job per scene draws all of that scene's figures (starting a process and importing xarray and
# matplotlib costs more than drawing most figures). A rule per scene (named figures_<scene>) lists
# the scene's figures as outputs, so `snakemake results/<scene>/figures/fig1.png` works (it draws the
# scene's figures), each PNG has its own caption in the report, and a change to one figure's options
# re-draws the scene's figures (seconds).

for _scene, _sc in SCENES.items():
    _figs = list(_sc.figures)
    if not _figs:
        continue

    rule:
        name:
            figure_rule_name(_scene)
        input:
            **figure_inputs(_scene),
        output:
            png=[
                report(
                    vpaths.fmt(vpaths.FIGURE, scene=_scene, fig=f, ext="png"),
                    caption=f"../report/figures/{f}.rst",
                    category=_scene,
                )
                for f in _figs
            ],
            pdf=[
                vpaths.fmt(vpaths.FIGURE, scene=_scene, fig=f, ext="pdf")
                for f in _figs
            ],
        log:
            vpaths.log(vpaths.fmt(vpaths.SCENE_DIR, scene=_scene), "figures"),
        params:
            scene=_scene,
            figures=_figs,
            plots_code=PLOTS_CODE,
            options=figure_options(_scene),
        script:
            "../scripts/figure.py"


rule manifest:
    input:
        get_scene_targets,
    output:
        vpaths.MANIFEST,
    log:
        vpaths.log(vpaths.SCENE_DIR, "manifest"),
    script:
        "../scripts/manifest.py"
