"""``analysis.solve`` against its stated contract on diagonal and small pencils whose
eigenvalues are known exactly: dense and sparse condensation of massless DOFs, the refusals
(no mass, no energy, a failing dense solve, a mode below the round-off floor, a mesh too fine),
and ``lowest_elastic`` making room for mechanism modes and naming how many elastic modes a
model has."""

import logging
import math

import numpy as np
import pytest
import scipy.sparse as sp

from flexlink.analysis import solve as sv
from flexlink.analysis.eigensolver import EigenSolver, Method, lowest_pairs
from flexlink.errors import InputError, NumericalError

DENSE = EigenSolver("dense")
# two unit masses on springs 1 and 4 to ground, DOF 2 massless between DOF 0 and ground
K3 = np.array([[2.0, 0.0, -1.0], [0.0, 4.0, 0.0], [-1.0, 0.0, 1.0]])
M3 = np.diag([1.0, 1.0, 0.0])


@pytest.mark.parametrize("kind", ["dense", "sparse"])
def test_massless_dof_condensed_exactly(kind):
    K, M = (K3, M3) if kind == "dense" else (sp.csr_matrix(K3), sp.csr_matrix(M3))
    p = sv.prepare(K, M)
    assert (p.n, p.n_solved) == (3, 2)
    assert sp.issparse(p.Ks) == (kind == "sparse")  # dense stays dense
    Ks = p.Ks.toarray() if kind == "sparse" else p.Ks
    # K_c = K_mm - K_ms K_ss^-1 K_sm = [[2 - 1, 0], [0, 4]]; DOF 2 follows DOF 0 one to one
    np.testing.assert_allclose(Ks, [[1.0, 0.0], [0.0, 4.0]], atol=1e-15)
    np.testing.assert_allclose(p.expand(np.eye(2)), [[1, 0], [0, 1], [1, 0]], atol=1e-15)
    result = sv.solve_modes(K, M, 2, lambda_ref=1.0, solver=DENSE)
    np.testing.assert_allclose(result.eigenvalues, [1.0, 4.0], rtol=1e-14)
    assert result.condensed == 1 and result.n_dofs == 3


@pytest.mark.parametrize("kind", ["dense", "sparse"])
def test_a_dof_without_mass_or_stiffness_is_refused_by_name(kind):
    K = np.diag([1.0, 2.0, 0.0, 0.0])  # DOFs 2 and 3: no mass, no spring
    M = np.diag([1.0, 1.0, 0.0, 0.0])
    if kind == "sparse":
        K, M = sp.csr_matrix(K), sp.csr_matrix(M)
    with pytest.raises(NumericalError, match=r"^2 DOF\(s\) have neither mass nor stiffness "
                       r"\(first: reduced DOF 2\)"):
        sv.prepare(K, M)


def test_a_model_without_mass_is_refused():
    with pytest.raises(NumericalError, match="no DOF has mass"):
        sv.prepare(np.eye(2), np.zeros((2, 2)))


def test_a_failing_eigen_solve_says_why():
    # K - shift M = diag(-5, 1) + 1 I is indefinite: LAPACK's Cholesky of it fails
    with pytest.raises(NumericalError, match=r"dense eigen solve failed: .*not positive "
                       r"definite \(K indefinite\?\)"):
        lowest_pairs(Method.DENSE, np.diag([-5.0, 1.0]), np.eye(2), 1, shift=-1.0)
    # shift-invert about an eigenvalue: K - shift M is exactly singular, its LU fails
    K = sp.diags(np.arange(1.0, 13.0)).tocsr()
    with pytest.raises(NumericalError, match="^sparse eigen solve failed: .*singular"):
        lowest_pairs(Method.SPARSE, K, sp.identity(12, format="csr"), 2, shift=1.0)


def test_a_mode_under_the_round_off_floor_is_refused_with_its_frequency():
    # lambda_max = 1e6: floor 100 eps 1e6 = 2.2e-8; 1e-9 lies above 1e-6 lambda_ref = 1e-12
    floor = sv.roundoff_floor(1e6)
    vals = np.array([0.0, 1e-9, 1.0])
    with pytest.raises(NumericalError) as err:
        sv.label(vals, floor, 1e-6, 1e-6, refined=False, lambda_max=1e6)
    text = str(err.value)
    hz = math.sqrt(1e-9) / (2 * math.pi)
    assert text.startswith(f"mode 2 ({hz:.4g} Hz) lies below the round-off floor of this mesh "
                           f"({math.sqrt(floor) / (2 * math.pi):.4g} Hz")
    # refined eigenvalues are energy quotients, free of that floor: labelled, not refused
    kinds = sv.label(vals, 1e-12, 1e-6, 1e-6, refined=True, lambda_max=1e6)
    assert kinds == (sv.MECHANISM, sv.ELASTIC, sv.ELASTIC)


def test_label_warns_where_round_off_reaches_the_frequency_tolerance(caplog):
    # eps lambda_max / lambda_1 = 2.2e-16 * 1e12 / 1 = 2.2e-4 > 1e-6
    with caplog.at_level(logging.WARNING, logger="flexlink.analysis.solve"):
        sv.label(np.array([1.0, 2.0]), 1e-6, 1.0, 1e-6, refined=False, lambda_max=1e12)
    assert caplog.messages == [
        "eigenvalues carry about 0.0002 relative round-off (eps lambda_max / lambda_1): the "
        "mesh is finer than double precision supports without the energy refinement"]
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="flexlink.analysis.solve"):
        sv.label(np.array([1.0, 2.0]), 1e-6, 1.0, 1e-6, refined=False, lambda_max=1e6)
    assert caplog.text == ""


def test_refined_eigenvalues_refuse_lost_vectors_and_sort(caplog):
    shapes = np.eye(3)

    def energy(s):
        return np.array([4.0, 1.0, 1e-3])  # a mechanism's quotient last

    # lambda_ref = 1e4: modes below 1e-6 lambda_ref = 1e-2 are mechanisms
    vals, order = sv.refined_eigenvalues(None, shapes, energy, 1e4, 1e6, 1e-6)
    np.testing.assert_array_equal(vals[order], [1e-3, 1.0, 4.0])  # the quotients, sorted
    # eps lambda_max / lambda_1 over the elastic modes (1.0, not the mechanism's 1e-3)
    eps = np.finfo(float).eps
    with caplog.at_level(logging.WARNING, logger="flexlink.analysis.solve"):
        sv.refined_eigenvalues(None, shapes, energy, 1e4, 0.05 / eps, 1e-6)  # 0.05: warned
    assert "eps lambda_max / lambda_1 = 0.05" in caplog.text
    with pytest.raises(NumericalError, match="too fine for double precision.* = 11,"):
        sv.refined_eigenvalues(None, shapes, energy, 1e4, 11 / eps, 1e-6)
    sv.refined_eigenvalues(None, shapes, energy, 1e4, 9 / eps, 1e-6)  # below 10: warned only


def spectrum(mechanisms, elastic):
    """Diagonal K, M = I: ``mechanisms`` zero modes, then eigenvalues 1 .. ``elastic``."""
    K = np.diag(np.concatenate([np.zeros(mechanisms), np.arange(1.0, elastic + 1)]))
    return K, np.eye(len(K))


def test_lowest_elastic_makes_room_for_unexpected_mechanisms():
    K, M = spectrum(mechanisms=7, elastic=6)
    asked = []

    def solve(k):
        asked.append(k)
        return sv.solve_modes(K, M, k, lambda_ref=1.0, solver=DENSE)

    result = sv.lowest_elastic(solve, 2)
    # first 2 + 0 + 4 = 6 modes, all mechanisms; then room for the 6 found, 2 and 4 spare
    assert asked == [6, 12]
    np.testing.assert_allclose(result.eigenvalues[result.elastic][:2], [1.0, 2.0], rtol=1e-12)
    assert result.kinds.count(sv.MECHANISM) == 7


def test_more_elastic_modes_than_the_model_has_are_refused_with_the_count():
    K, M = spectrum(mechanisms=6, elastic=6)

    def solve(k):
        # the highest modes of a stiff, light frame fail the backward-error check: a solve for
        # more than 10 of these 12 modes stands in for that
        if k > 10:
            raise NumericalError("eigen backward error 1e-9 exceeds 1e-10")
        return sv.solve_modes(K, M, k, lambda_ref=1.0, solver=DENSE)

    with pytest.raises(InputError, match=r": 7 elastic modes asked for, but the model has only 6 "
                       r"\(12 DOFs, 6 of them rigid-body/mechanism modes\)") as err:
        sv.lowest_elastic(solve, 7)
    assert err.value.field == "number of modes (-n)" and err.value.expected.startswith("at most 6")
    # within what the model has, the solver's own failure stands
    with pytest.raises(NumericalError, match="backward error"):
        sv.lowest_elastic(solve, 6)
    # every mode solved and still too few: require_elastic names the same count
    few = sv.lowest_elastic(lambda k: sv.solve_modes(K, M, k, lambda_ref=1.0, solver=DENSE), 7)
    assert len(few.elastic) == 6
    with pytest.raises(InputError, match="7 elastic modes asked for, but the model has only 6"):
        sv.require_elastic(few, 7)
    assert sv.require_elastic(few, 6) is few


@pytest.mark.parametrize("refined", [False, True])
def test_mechanism_threshold_is_zero_tol_times_the_model_scale(refined):
    # lambda_ref = 1e4, zero_tol 1e-6: modes below 1e-2 (rad/s)^2 are mechanisms, on the plain
    # and on the energy-refined path alike (the refined quotients carry no round-off floor,
    # but the physical threshold stays); 5e-3 below it, 2e-2 above it
    K = np.diag([5e-3, 2e-2, 1e4])

    def energy(shapes):
        return np.einsum("ij,ij->j", shapes, K @ shapes)  # exact: K is diagonal

    result = sv.solve_modes(K, np.eye(3), 3, lambda_ref=1e4, solver=DENSE,
                            energy=energy if refined else None)
    assert result.refined == refined
    # unrefined, each eigenvalue carries about eps lambda_max = 2e-12 absolute
    np.testing.assert_allclose(result.eigenvalues, [5e-3, 2e-2, 1e4], rtol=1e-12, atol=1e-10)
    assert result.kinds == (sv.MECHANISM, sv.ELASTIC, sv.ELASTIC)
