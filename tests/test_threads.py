"""scipy's factorisations run with one BLAS thread (vcor.threads): the numbers do not depend on the
machine's cores or on whether the process is a Snakemake job (one thread) or a notebook."""

import os
import subprocess
import sys


def test_the_first_two_body_fit_of_a_process_is_the_same_as_a_later_one():
    """The two-body modulus is fitted with one BLAS thread from the first call on (scipy's BLAS is loaded
    before the thread limit is set): the same digits whether or not scipy.linalg was loaded before."""
    code = ("import vcor; print(repr(vcor.simulate('sls', 2.0, target={'plate': {'material': 'butyl-prony3', "
            "'h': 0.01}}).cor))")
    runs = [subprocess.run([sys.executable, "-c", pre + code], capture_output=True, text=True, check=True).stdout
            for pre in ("", "import scipy.linalg; ")]
    assert runs[0] == runs[1] and runs[0].strip(), runs


def test_ive_gives_the_same_digits_with_any_number_of_blas_threads():
    """scipy's Radau factorises with one BLAS thread (vcor.threads): a Snakemake job (one thread) and a
    notebook (every core) get the same number; with the machine's threads it differed by 2.7e-12."""
    code = ("import vcor; m = vcor.materials.Prony(2e6, [8e6, 3e6], [5e3, 2e2]); "
            "print(repr(vcor.simulate(m, 3.0, method='ive', ive_method='Radau', rtol=1e-4).cor))")
    runs = [subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                           env={**os.environ, "OPENBLAS_NUM_THREADS": n}).stdout for n in ("1", "2")]
    assert runs[0] == runs[1] and runs[0].strip(), runs
