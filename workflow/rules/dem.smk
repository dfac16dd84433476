# DEM bridge (vcor.dem): one collision's COR, each DEM law fitted to it, the COR table, the parameters
# file, the LAMMPS deck, the Yade script and the figure, per entry of the config's dem: block;
# results/dem/<name>/MANIFEST.txt requires them all (the one target that builds an entry).


def get_dem_targets(wildcards):
    """Every output of a dem: entry (the manifest's inputs)."""
    return PROJECT.dem_targets(wildcards.dem)



rule dem:
    input:
        get_dem_material_files,
    output:
        nc="results/dem/{dem}.nc",
        table="results/dem/{dem}/table.csv",
        parameters="results/dem/{dem}/parameters.csv",
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


rule dem_yade:
    input:
        "results/dem/{dem}.nc",
    output:
        "results/dem/{dem}/yade/collision.py",
    log:
        "results/dem/logs/{dem}.yade.log",
    wildcard_constraints:
        dem="|".join(re.escape(d) for d in sorted(PROJECT.dem)) or "no-dem",
    params:
        code=CODE,
    script:
        "../scripts/dem_yade.py"


rule dem_manifest:
    input:
        get_dem_targets,
    output:
        "results/dem/{dem}/MANIFEST.txt",
    log:
        "results/dem/logs/{dem}.manifest.log",
    wildcard_constraints:
        dem="|".join(re.escape(d) for d in sorted(PROJECT.dem)) or "no-dem",
    script:
        "../scripts/dem_manifest.py"


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
