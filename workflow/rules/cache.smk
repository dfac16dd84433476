# Compile the numba kernels once, before the solving jobs: with -j2 the first jobs would otherwise
# each compile the same kernels (an empty numba cache costs ~7 s of compiling per process).


rule numba_cache:
    output:
        temp(touch("results/.numba-cache")),
    log:
        "results/logs/numba_cache.log",
    benchmark:
        "results/benchmarks/numba_cache.tsv"
    priority: 20
    script:
        "../scripts/numba_cache.py"
