"""The stages of ``solve.solve_modes`` one by one: prepare, eigen_solve, check, label."""

import numpy as np
import pytest
import scipy.sparse as sp

from flexlink.analysis.eigensolver import EigenSolver
from flexlink.analysis import solve as sv
from flexlink.errors import NumericalError

# two unit masses on springs k = 1 and 4 to ground, and a massless DOF between them (spring 1)
K = sp.csr_matrix(np.array([[2.0, 0.0, -1.0], [0.0, 4.0, 0.0], [-1.0, 0.0, 1.0]]))
M = sp.csr_matrix(np.diag([1.0, 1.0, 0.0]))


def test_prepare_condenses_the_massless_dof_exactly():
    p = sv.prepare(K, M)
    assert (p.n, p.n_solved) == (3, 2)
    # statically: DOF 2 follows DOF 0, so DOF 0 sees 2 - 1 = 1
    np.testing.assert_allclose(p.Ks.toarray(), [[1.0, 0.0], [0.0, 4.0]], atol=1e-15)
    np.testing.assert_allclose(p.expand(np.eye(2))[2], [1.0, 0.0], atol=1e-15)


def test_the_stages_compose_to_solve_modes():
    p = sv.prepare(K, M)
    vals, vecs = sv.eigen_solve(p, 2, "dense", lambda_ref=1.0)
    np.testing.assert_allclose(vals, [1.0, 4.0], rtol=1e-14)  # omega^2 = k / m
    evidence = sv.check(p, vals, vecs, zero=1e-6, method="dense")
    kinds = sv.label(vals, 1e-6, 1.0, 1e-6, refined=False, lambda_max=p.lambda_max)
    whole = sv.solve_modes(K, M, 2, lambda_ref=1.0, solver=EigenSolver("dense"))
    np.testing.assert_allclose(whole.eigenvalues, vals, rtol=1e-14)  # the same solve again
    np.testing.assert_allclose(np.abs(whole.shapes), np.abs(evidence.vectors), atol=1e-15)
    assert whole.kinds == kinds == (sv.ELASTIC, sv.ELASTIC) and whole.condensed == 1


def test_check_refuses_nan_and_negative_eigenvalues():
    p = sv.prepare(K, M)
    vals, vecs = sv.eigen_solve(p, 2, "dense", lambda_ref=1.0)
    with pytest.raises(NumericalError, match="NaN"):
        sv.check(p, np.array([np.nan, 4.0]), vecs, zero=1e-6, method="dense")
    with pytest.raises(NumericalError) as err:
        sv.check(p, np.array([-1.0, 4.0]), vecs, zero=1e-6, method="dense")
    # the whole sentence: the value with its unit, and which inputs to look at
    assert str(err.value) == ("negative eigenvalue -1 rad^2/s^2: K is not positive "
                              "semi-definite (check spring and section inputs)")
    with pytest.raises(NumericalError, match="backward error"):
        sv.check(p, vals * 1.01, vecs, zero=1e-6, method="dense")


def test_label_splits_mechanism_from_elastic():
    kinds = sv.label(np.array([1e-12, 1.0]), zero=1e-6, lambda_ref=1.0, zero_tol=1e-6,
                     refined=True, lambda_max=4.0)
    assert kinds == (sv.MECHANISM, sv.ELASTIC)
