# DEM bridge (vcor.dem): one collision's COR, each DEM law fitted to it, the COR table, the parameters
# file, the LAMMPS deck, the Yade script and the figure, per entry of the config's dem: block;
# results/dem/<name>/MANIFEST.txt requires them all (the one target that builds an entry).


# One job per entry solves its collisions, fits the laws and writes the dataset, the tables, the LAMMPS
# deck and the Yade script (a rule per entry: the deck's name and whether there is one depend on the
# entry); the figure and the manifest follow.
for _dem in PROJECT.dem:

    rule:
        name:
            dem_rule_name(_dem)
        input:
            materials=PROJECT.dem_material_files(_dem),
            kernels=kernels_of([vdem.solver_method(PROJECT.dem[_dem])]),
        output:
            **PROJECT.dem_files(_dem),
        log:
            vpaths.log(vpaths.DEM_DIR, _dem),
        benchmark:
            vpaths.benchmark(vpaths.DEM_DIR, _dem)
        params:
            code=CODE,
            name=_dem,
            spec=PROJECT.dem[_dem],
            catalogue=catalogue_spec(
                PROJECT.dem_materials(_dem), PROJECT.dem_catalogue(_dem)
            ),
        script:
            "../scripts/dem.py"


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
