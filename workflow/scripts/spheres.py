"""eps(b) of viscoelastic spheres: numerics, series, Pade (thin: vcor.study.datasets does the work)."""

from vcor.io import netcdf
from vcor.io.joblog import count, job_log
from vcor.study import datasets, scene, summary

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    spec = smk.params.spec
    ds = datasets.spheres_dataset(scene.axis_values(spec["b"]), rules=spec["rules"], tau_ratios=spec["tau_ratio"],
                                  steps_per_contact=spec["steps_per_contact"], ice=spec.get("ice"))
    netcdf.write_dataset(ds, smk.output[0], title=f"vcor viscoelastic spheres, scene {smk.wildcards.scene}",
                         extra_attrs={"spheres_config": spec}, command="snakemake rule spheres")
    log.note(f"solved eps(b) of scene {smk.wildcards.scene} at {ds.sizes['b']} values of b with "
             f"{count(len(spec['rules']), 'separation rule')}: {summary.outcome_of(ds).text()}; {smk.output[0]}")
