"""The eigen solver passed in: which of dense and sparse takes a problem, one rule for AUTO
(dense up to the solver's own ``dense_max``), and the refusal of a dense solve too large."""

from __future__ import annotations

import numpy as np
import pytest

from flexlink.analysis.eigensolver import (AUTO_DENSE_MAX, DENSE_REFUSE, DEFAULT_SOLVER,
                                           EigenSolver, Method)
from flexlink.analysis.solve import solve_modes
from flexlink.analysis.sweep import SWEEP_SOLVER
from flexlink.errors import InputError, NumericalError


@pytest.mark.parametrize("solver", [DEFAULT_SOLVER, SWEEP_SOLVER, EigenSolver(dense_max=10)])
def test_auto_is_dense_up_to_the_solvers_own_limit_and_sparse_above(solver):
    assert solver.method is Method.AUTO
    assert solver.pick(solver.dense_max, 4) is Method.DENSE
    assert solver.pick(solver.dense_max + 1, 4) is Method.SPARSE
    assert solver.assembles_dense(solver.dense_max) and not solver.assembles_dense(solver.dense_max + 1)


def test_the_single_solve_and_the_sweep_differ_only_in_their_limit():
    assert DEFAULT_SOLVER.dense_max == AUTO_DENSE_MAX < SWEEP_SOLVER.dense_max


def test_arpack_cannot_take_nearly_every_mode_so_dense_does():
    # ARPACK needs k < n - 1
    assert EigenSolver(Method.SPARSE).pick(10, 9) is Method.DENSE
    assert EigenSolver(Method.SPARSE).pick(10, 8) is Method.SPARSE
    assert not EigenSolver(Method.SPARSE).assembles_dense(2)


def test_a_dense_solve_too_large_is_refused():
    with pytest.raises(NumericalError, match="dense solve refused"):
        EigenSolver(Method.DENSE).pick(DENSE_REFUSE + 1, 4)
    assert EigenSolver(Method.DENSE).pick(DENSE_REFUSE, 4) is Method.DENSE


def test_the_result_names_the_solver_that_ran_and_an_unknown_one_is_refused():
    K, M = np.diag([1.0, 4.0, 9.0, 16.0]), np.eye(4)
    assert solve_modes(K, M, 2, lambda_ref=1.0).solver is Method.DENSE
    with pytest.raises(InputError, match=r"^method: 'fast' is not a choice \(expected auto, dense or sparse\)$"):
        EigenSolver("fast")
