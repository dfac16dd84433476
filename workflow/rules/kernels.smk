# Numba kernels: compiled once per machine, each method in a job of its own that runs first
# (vcor.solvers.backend). The jobs that solve wait for the marks of the methods they use; meanwhile
# the other core runs jobs without kernels (fits). Marks: vcor.study.kernels.


rule kernels:
    output:
        vpaths.KERNELS,
    log:
        vpaths.log(vpaths.RESULTS, "kernels/{method}"),
    wildcard_constraints:
        method="|".join(re.escape(m) for m in COMPILED_METHODS),
    priority: 20
    params:
        code=CODE,
    script:
        "../scripts/kernels.py"
