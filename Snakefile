# vcor: viscoelastic coefficient of restitution, parameter-study workflow.
# Table of contents only; rules live in workflow/rules, configuration in config.yaml.
from snakemake.utils import min_version

min_version("9.0")


# config.yaml unless the command line names config files (`--configfile my.yaml` runs my.yaml alone)
if not workflow.overwrite_configfiles:

    configfile: "config.yaml"


report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"
include: "workflow/rules/kernels.smk"
include: "workflow/rules/fit.smk"
include: "workflow/rules/sweep.smk"
include: "workflow/rules/spheres.smk"
include: "workflow/rules/convergence.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/calibrate.smk"
include: "workflow/rules/dem.smk"


rule all:
    default_target: True
    input:
        get_all_targets(),


# at the end of a run, successful or not: what each scene's sweep holds and where (vcor.study.summary);
# then the process ends at once (vcor.study.run_end)
onsuccess:
    from snakemake.logging import logger
    import vcor.study.run_end as vrun_end
    import vcor.study.summary as vsummary

    for _line in vsummary.run_summary(PROJECT):
        logger.info(_line)
    vrun_end.cancel_rescheduling_timers()


onerror:
    from snakemake.logging import logger
    import vcor.study.run_end as vrun_end
    import vcor.study.summary as vsummary

    for _line in vsummary.run_summary(PROJECT):
        logger.info(_line)
    vrun_end.cancel_rescheduling_timers()
