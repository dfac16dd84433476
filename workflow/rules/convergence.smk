# Work-precision study: every solver on a ladder of steps/tolerances, one job per (material, v0).


rule convergence_case:
    input:
        materials=get_fitted_inputs,
    output:
        "results/{scene}/convergence/{material_case}-v{vi}.nc",
    log:
        "results/{scene}/logs/convergence/{material_case}-v{vi}.log",
    benchmark:
        "results/{scene}/benchmarks/convergence/{material_case}-v{vi}.tsv"
    conda:
        "../envs/vcor.yaml"
    params:
        material="{material_case}",
        v0=get_convergence_v0,
        material_dir=MATERIAL_DIR,
    script:
        "../scripts/convergence_case.py"


rule convergence:
    input:
        get_convergence_cases,
    output:
        nc="results/{scene}/convergence.nc",
        orders="results/{scene}/orders.txt",
    log:
        "results/{scene}/logs/convergence.log",
    conda:
        "../envs/vcor.yaml"
    params:
        spec=get_convergence_spec,
    script:
        "../scripts/convergence.py"
