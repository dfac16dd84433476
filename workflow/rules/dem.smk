# DEM bridge (vcor.dem): one collision's COR, each DEM law fitted to it, the COR table, the LAMMPS
# deck and the figure, per entry of the config's dem: block.


rule dem:
    input:
        get_dem_material_files,
    output:
        nc="results/dem/{dem}.nc",
        table="results/dem/{dem}/table.csv",
    log:
        "results/dem/logs/{dem}.log",
    benchmark:
        "results/dem/benchmarks/{dem}.tsv"
    wildcard_constraints:
        dem="|".join(re.escape(d) for d in sorted(PROJECT.dem)) or "no-dem",
    params:
        code=CODE,
        spec=get_dem_spec,
        catalogue=CATALOGUE_SPEC,
    script:
        "../scripts/dem.py"


rule dem_deck:
    input:
        "results/dem/{dem}.nc",
    output:
        "results/dem/{dem}/lammps/in.{kind}",
    log:
        "results/dem/logs/{dem}.{kind}.log",
    wildcard_constraints:
        dem="|".join(re.escape(d) for d in sorted(PROJECT.dem)) or "no-dem",
        kind="pair|wall",
    params:
        code=CODE,
    script:
        "../scripts/dem_deck.py"


rule dem_figure:
    input:
        "results/dem/{dem}.nc",
    output:
        png=report(
            "results/dem/{dem}.png",
            caption="../report/dem.rst",
            category="DEM",
        ),
        pdf="results/dem/{dem}.pdf",
    log:
        "results/dem/logs/{dem}.figure.log",
    wildcard_constraints:
        dem="|".join(re.escape(d) for d in sorted(PROJECT.dem)) or "no-dem",
    params:
        plots_code=PLOTS_CODE,
    script:
        "../scripts/dem_figure.py"
