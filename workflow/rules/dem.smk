# DEM bridge (vcor.dem): one collision's COR, each DEM law fitted to it, the COR table, the parameters
# file, the LAMMPS deck, the Yade script and the figure, per entry of the config's dem: block;
# results/dem/<name>/MANIFEST.txt requires them all (the one target that builds an entry).


rule dem:
    input:
        materials=get_dem_material_files,
        kernels=get_dem_kernels,
    output:
        nc=vpaths.DEM,
        table=vpaths.DEM_TABLE,
        parameters=vpaths.DEM_PARAMETERS,
    log:
        vpaths.log(vpaths.DEM_DIR, "{dem}"),
    benchmark:
        vpaths.benchmark(vpaths.DEM_DIR, "{dem}")
    wildcard_constraints:
        dem=_names(PROJECT.dem, "no-dem"),
    params:
        code=CODE,
        spec=get_dem_spec,
        catalogue=CATALOGUE_SPEC,
    script:
        "../scripts/dem.py"


rule dem_deck:
    input:
        vpaths.DEM,
    output:
        vpaths.DEM_DECK,
    log:
        vpaths.log(vpaths.DEM_DIR, "{dem}.{kind}"),
    wildcard_constraints:
        dem=_names(PROJECT.dem, "no-dem"),
        kind="pair|wall",
    params:
        code=CODE,
    script:
        "../scripts/dem_deck.py"


rule dem_yade:
    input:
        vpaths.DEM,
    output:
        vpaths.DEM_YADE,
    log:
        vpaths.log(vpaths.DEM_DIR, "{dem}.yade"),
    wildcard_constraints:
        dem=_names(PROJECT.dem, "no-dem"),
    params:
        code=CODE,
    script:
        "../scripts/dem_yade.py"


rule dem_manifest:
    input:
        get_dem_targets,
    output:
        vpaths.DEM_MANIFEST,
    log:
        vpaths.log(vpaths.DEM_DIR, "{dem}.manifest"),
    wildcard_constraints:
        dem=_names(PROJECT.dem, "no-dem"),
    script:
        "../scripts/dem_manifest.py"


rule dem_figure:
    input:
        vpaths.DEM,
    output:
        png=report(
            vpaths.fmt(vpaths.DEM_FIGURE, dem="{dem}", ext="png"),
            caption="../report/dem.rst",
            category="DEM",
        ),
        pdf=vpaths.fmt(vpaths.DEM_FIGURE, dem="{dem}", ext="pdf"),
    log:
        vpaths.log(vpaths.DEM_DIR, "{dem}.figure"),
    wildcard_constraints:
        dem=_names(PROJECT.dem, "no-dem"),
    params:
        plots_code=PLOTS_CODE,
    script:
        "../scripts/dem_figure.py"
