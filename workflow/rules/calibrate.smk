# Calibrations from measured COR (vcor.fitting.calibrate): the full record and the calibrated material.


rule calibrate:
    input:
        get_calibration_inputs,
    output:
        record="results/calibrations/{cal}.nc",
        material=f"{MATERIAL_DIR}/{{cal}}.nc",
    log:
        "results/calibrations/logs/{cal}.log",
    benchmark:
        "results/calibrations/benchmarks/{cal}.tsv"
    wildcard_constraints:
        cal="|".join(re.escape(c) for c in sorted(CATALOGUE.calibrations))
        or "no-calibration",
    params:
        code=CODE,
        spec=get_calibration_spec,
        identity=get_material_identity,
        catalogue=CATALOGUE_SPEC,
    script:
        "../scripts/calibrate.py"


rule calibration_figure:
    input:
        "results/calibrations/{cal}.nc",
    output:
        png=report(
            "results/calibrations/{cal}.png",
            caption="../report/calibration.rst",
            category="calibrations",
        ),
        pdf="results/calibrations/{cal}.pdf",
    log:
        "results/calibrations/logs/{cal}.figure.log",
    wildcard_constraints:
        cal="|".join(re.escape(c) for c in sorted(CATALOGUE.calibrations))
        or "no-calibration",
    params:
        plots_code=PLOTS_CODE,
    script:
        "../scripts/calibration_figure.py"
