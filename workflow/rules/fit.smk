# Material fits: built only when a scene names a fitted material; config materials likewise.


rule config_material:
    # a material of the config's materials block, written like a fit
    input:
        get_material_table,
    output:
        vpaths.material(MATERIAL_DIR),
    log:
        vpaths.log(MATERIAL_DIR, "{name}"),
    wildcard_constraints:
        name=_names(CATALOGUE.specs, "no-config-material"),
    params:
        code=CODE,
        spec=get_material_spec,
        identity=get_material_identity,
    script:
        "../scripts/config_material.py"


rule fit_material:
    input:
        get_fit_data_files,
    output:
        nc=vpaths.material(MATERIAL_DIR, "{material}"),
        table=vpaths.material_table(MATERIAL_DIR, "{material}"),
    log:
        vpaths.log(MATERIAL_DIR, "{material}"),
    benchmark:
        vpaths.benchmark(MATERIAL_DIR, "{material}")
    wildcard_constraints:
        material=_names(set(CATALOGUE.fits) - GROUPED_FITS, "no-fitted-material"),
    # long chains first (a fit feeds a shard; cases feed the study): a shorter -j2 schedule
    priority: 10
    params:
        code=CODE,
        names=lambda wildcards: [wildcards.material],
        specs=lambda wildcards: [get_fit_spec(wildcards)],
        identities=lambda wildcards: [get_material_identity(wildcards)],
    script:
        "../scripts/fit_material.py"


# A fit family of which the project builds a member, fitted whole in one job (Project.fit_groups says why).
for _family, _members in FIT_GROUPS.items():

    rule:
        name:
            FIT_FAMILY_RULES[_family]
        input:
            fit_data_files(_members),
        output:
            nc=[vpaths.material(MATERIAL_DIR, m) for m in _members],
            table=[vpaths.material_table(MATERIAL_DIR, m) for m in _members],
        log:
            vpaths.log(
                MATERIAL_DIR, f"{vpaths.FAMILY_LOGS}{vpaths.family_slug(_family)}"
            ),
        benchmark:
            vpaths.benchmark(
                MATERIAL_DIR, f"{vpaths.FAMILY_LOGS}{vpaths.family_slug(_family)}"
            )
        priority: 10
        params:
            code=CODE,
            names=_members,
            specs=[CATALOGUE.fits[m] for m in _members],
            identities=[CATALOGUE.identity(m) for m in _members],
        script:
            "../scripts/fit_material.py"


rule fit_samples:
    # one job's share of the bootstrap samples of a fit to measured data, refitted from the fit itself
    # (vcor.fitting.resample); the shares run side by side (vcor.study.uncertainty.SAMPLE_JOBS)
    input:
        data=get_fit_data_files,
        fit=vpaths.material(MATERIAL_DIR, "{material}"),
    output:
        vpaths.samples_part(MATERIAL_DIR),
    log:
        vpaths.log(MATERIAL_DIR, "samples/{material}-b{n}-s{seed}-p{part}of{parts}"),
    benchmark:
        vpaths.benchmark(
            MATERIAL_DIR, "samples/{material}-b{n}-s{seed}-p{part}of{parts}"
        )
    wildcard_constraints:
        n="[0-9]+",
        seed="[0-9]+",
        part="[0-9]+",
        parts="[0-9]+",
    priority: 10
    params:
        code=CODE,
        spec=get_fit_spec,
        identity=get_samples_identity,
    script:
        "../scripts/fit_samples.py"


rule merge_samples:
    # every bootstrap sample of a fit in one file, for the scenes with uncertainty (vcor.study.uncertainty)
    input:
        vpaths.samples_parts(MATERIAL_DIR, vuncertainty.SAMPLE_JOBS),
    output:
        vpaths.samples(MATERIAL_DIR),
    log:
        vpaths.log(MATERIAL_DIR, "samples/{material}-b{n}-s{seed}"),
    benchmark:
        vpaths.benchmark(MATERIAL_DIR, "samples/{material}-b{n}-s{seed}")
    wildcard_constraints:
        n="[0-9]+",
        seed="[0-9]+",
    priority: 10
    params:
        code=CODE,
        identity=get_samples_identity,
    script:
        "../scripts/merge_samples.py"


rule fit_metrics:
    input:
        get_scene_fit_files,
    output:
        vpaths.FIT_METRICS,
    log:
        vpaths.log(vpaths.SCENE_DIR, "fit_metrics"),
    params:
        code=CODE,
        names=get_scene_fitted_names,
        material_dir=MATERIAL_DIR,
    script:
        "../scripts/fit_metrics.py"
