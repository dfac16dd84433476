# Viscoelastic spheres (Ramirez et al. 1999): eps(b), series, Pade approximants, hereditary variant.


rule spheres:
    output:
        vpaths.fmt(vpaths.DATASET, scene="{scene}", dataset="spheres"),
    log:
        vpaths.log(vpaths.SCENE_DIR, "spheres"),
    benchmark:
        vpaths.benchmark(vpaths.SCENE_DIR, "spheres")
    # heads a chain (figures, manifest), like the shards
    priority: 5
    params:
        code=CODE,
        spec=get_spheres_spec,
    script:
        "../scripts/spheres.py"
