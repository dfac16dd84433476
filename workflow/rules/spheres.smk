# Viscoelastic spheres (Ramirez et al. 1999): eps(b), series, Pade approximants, hereditary variant.


rule spheres:
    output:
        vpaths.fmt(vpaths.DATASET, scene="{scene}", dataset="spheres"),
    log:
        "results/{scene}/logs/spheres.log",
    benchmark:
        "results/{scene}/benchmarks/spheres.tsv"
    # heads a chain (figures, manifest), like the shards
    priority: 5
    params:
        code=CODE,
        spec=get_spheres_spec,
    script:
        "../scripts/spheres.py"
