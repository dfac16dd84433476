# Sweeps: content-addressed shards of grid points, aggregated into results/<scene>/sweep.nc.


rule sweep_shard:
    input:
        materials=get_shard_material_files,
        kernels=get_scene_kernels,
    output:
        nc=vpaths.SHARD,
        index=vpaths.SHARD_INDEX,
    log:
        vpaths.log(vpaths.SCENE_DIR, "shards/{shard}"),
    benchmark:
        vpaths.benchmark(vpaths.SCENE_DIR, "shards/{shard}")
    # a shard heads a chain (aggregate, figures, manifest): before the figures of other scenes, so
    # that the last minute of -j2 is not one scene's chain on one core
    priority: 5
    params:
        points=get_shard_points,
        settings=get_settings,
        catalogue=get_shard_catalogue,
    script:
        "../scripts/sweep_shard.py"


rule aggregate:
    input:
        shards=get_shard_files,
        materials=get_material_files,
    output:
        vpaths.SWEEP,
    log:
        vpaths.log(vpaths.SCENE_DIR, "aggregate"),
    benchmark:
        vpaths.benchmark(vpaths.SCENE_DIR, "aggregate")
    priority: 5
    params:
        rows=get_shard_rows,
        grid=get_grid,
        code=CODE,
        scene=get_scene,
        catalogue=get_scene_catalogue,
    script:
        "../scripts/aggregate.py"


rule moduli:
    input:
        materials=get_material_files,
    output:
        vpaths.fmt(vpaths.DATASET, scene="{scene}", dataset="moduli"),
    log:
        vpaths.log(vpaths.SCENE_DIR, "moduli"),
    benchmark:
        vpaths.benchmark(vpaths.SCENE_DIR, "moduli")
    params:
        code=CODE,
        materials=get_moduli_materials,
        catalogue=get_scene_catalogue,
    script:
        "../scripts/moduli.py"


rule histories:
    input:
        materials=get_material_files,
        kernels=get_histories_kernels,
    output:
        vpaths.fmt(vpaths.DATASET, scene="{scene}", dataset="histories"),
    log:
        vpaths.log(vpaths.SCENE_DIR, "histories"),
    benchmark:
        vpaths.benchmark(vpaths.SCENE_DIR, "histories")
    # long chains first (a fit feeds a shard; cases feed the study): a shorter -j2 schedule
    priority: 10
    params:
        code=CODE,
        histories=get_histories_spec,
        settings=get_settings,
        catalogue=get_scene_catalogue,
    script:
        "../scripts/histories.py"
