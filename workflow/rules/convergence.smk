# Work-precision study: every solver on a ladder of steps/tolerances, one job per material.


rule convergence_case:
    input:
        materials=get_material_files,
        kernels=get_all_kernels,
    output:
        vpaths.CONVERGENCE_CASE,
    log:
        vpaths.log(vpaths.SCENE_DIR, "convergence/{material_case}"),
    benchmark:
        vpaths.benchmark(vpaths.SCENE_DIR, "convergence/{material_case}")
    # long chains first (a fit feeds a shard; cases feed the study): a shorter -j2 schedule
    priority: 10
    params:
        code=CODE,
        material="{material_case}",
        v0=get_convergence_v0s,
        catalogue=lambda wildcards: catalogue_spec(
            [wildcards.material_case], PROJECT.scene_catalogue(wildcards.scene)
        ),
    script:
        "../scripts/convergence_case.py"


rule convergence:
    input:
        get_convergence_cases,
    output:
        nc=vpaths.fmt(vpaths.DATASET, scene="{scene}", dataset="convergence"),
        orders=vpaths.ORDERS,
    log:
        vpaths.log(vpaths.SCENE_DIR, "convergence"),
    # the work-precision figure (~4 s) follows: not the last job of a -j2 run
    priority: 10
    params:
        code=CODE,
        spec=get_convergence_spec,
    script:
        "../scripts/convergence.py"
