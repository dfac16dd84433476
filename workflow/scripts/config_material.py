"""Write a material of the config's materials block to the material folder (thin: vcor.materials.files)."""

from vcor.io.joblog import job_log
from vcor.io.netcdf import write_dataset
from vcor.materials.files import material_dataset

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    name = smk.wildcards.name
    ds, attrs = material_dataset(name, smk.params.spec)
    write_dataset(ds, smk.output[0], title=f"vcor material {name} (config materials block)", extra_attrs=attrs,
                  command="vcor.materials.files.material_dataset (deterministic: no time stamp)", timestamp=False,
                  identity=smk.params.identity)
    log.note(f"wrote material {name} (model {smk.params.spec['model']}): {smk.output[0]}")
