# Calibrations from measured COR (vcor.fitting.calibrate): the full record and the calibrated material.


rule calibrate:
    input:
        get_calibration_inputs,
    output:
        record=vpaths.CALIBRATION,
        material=vpaths.material(MATERIAL_DIR, "{cal}"),
    log:
        vpaths.log(vpaths.CALIBRATIONS_DIR, "{cal}"),
    benchmark:
        vpaths.benchmark(vpaths.CALIBRATIONS_DIR, "{cal}")
    wildcard_constraints:
        cal=_names(CATALOGUE.calibrations, "no-calibration"),
    params:
        code=CODE,
        spec=get_calibration_spec,
        identity=get_material_identity,
        catalogue=lambda wildcards: catalogue_spec([wildcards.cal]),
    script:
        "../scripts/calibrate.py"


rule calibration_figure:
    input:
        vpaths.CALIBRATION,
    output:
        png=report(
            vpaths.fmt(vpaths.CALIBRATION_FIGURE, cal="{cal}", ext="png"),
            caption="../report/calibration.rst",
            category="calibrations",
        ),
        pdf=vpaths.fmt(vpaths.CALIBRATION_FIGURE, cal="{cal}", ext="pdf"),
    log:
        vpaths.log(vpaths.CALIBRATIONS_DIR, "{cal}.figure"),
    wildcard_constraints:
        cal=_names(CATALOGUE.calibrations, "no-calibration"),
    params:
        plots_code=PLOTS_CODE,
    script:
        "../scripts/calibration_figure.py"
