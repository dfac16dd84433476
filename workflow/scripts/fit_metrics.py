"""Error metrics of a scene's fitted materials beside the paper's own sets (thin)."""

from vcor.fitting import fits
from vcor.io import receipts
from vcor.io.joblog import count, job_log

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    for path in smk.input:
        receipts.verified(path)
    receipts.atomic_text(smk.output[0], fits.scene_metrics_table(smk.params.names, smk.params.material_dir))
    log.note(f"tabulated the error metrics of {count(len(smk.params.names), 'fitted material')}: {smk.output[0]}")
