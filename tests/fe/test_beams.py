"""Single beams against closed-form Euler-Bernoulli frequencies, and the convergence order."""

import math

import numpy as np
import pytest

from helpers import BETA_L, beam_scale, bending_frequencies, modes_of, single_beam


@pytest.mark.parametrize("support", list(BETA_L))
def test_first_four_modes_within_0_01_percent_at_32_elements(support):
    result = modes_of(single_beam(support, 32), 10)
    exact = np.array(BETA_L[support]) ** 2 * beam_scale()
    computed = bending_frequencies(result, 4)
    np.testing.assert_allclose(computed, exact, rtol=1e-4)
    # the rigid-body modes of the free-free beam are found and labelled, not reported as elastic
    expected_rigid = 3 if support == "free-free" else 0
    assert sum(k != "elastic" for k in result.kinds) == expected_rigid


def test_convergence_order_is_about_four():
    """Consistent-mass Hermite elements: frequency error ~ h^4 (eigenvalue error ~ h^4 too)."""
    exact = BETA_L["cantilever"][2] ** 2 * beam_scale()
    meshes = [8, 16, 32]  # asymptotic range for mode 3; coarser pairs give 3.67
    errors = [abs(bending_frequencies(modes_of(single_beam("cantilever", n), 6), 3)[2] - exact)
              / exact for n in meshes]
    orders = [math.log2(errors[i] / errors[i + 1]) for i in range(len(errors) - 1)]
    assert all(3.7 < p < 4.3 for p in orders), orders
    # frequencies approach from above (consistent mass: upper bounds, Rayleigh-Ritz)
    assert all(e > 0 for e in errors)


@pytest.mark.parametrize("method", ["dense", "sparse"])
def test_dense_and_sparse_agree_with_rigid_body_modes(method):
    result = modes_of(single_beam("free-free", 24), 8, method=method)
    assert result.kinds[:3] == ("rigid-body/mechanism",) * 3
    exact = np.array(BETA_L["free-free"][:4]) ** 2 * beam_scale()
    np.testing.assert_allclose(bending_frequencies(result, 4), exact, rtol=1e-4)
    assert result.orthogonality_error < 1e-8


def test_mesh_too_fine_for_double_precision_is_reported_not_returned():
    """Without the energy refinement, a 10 000-element beam puts the round-off floor
    (100 eps lambda_max, ~700 Hz here) above its first bending mode (334 Hz): that mode
    cannot be told from a rigid-body mode, so the solver must say so, not label or return it."""
    from flexlink.errors import NumericalError

    with pytest.raises(NumericalError, match="round-off floor"):
        modes_of(single_beam("free-free", 10000), 6, method="sparse")


def test_refined_path_also_refuses_a_mesh_beyond_double_precision():
    """With the energy refinement the eigenvalue is a Rayleigh quotient of the computed vector;
    on a 30 000-element link the vector itself is lost, and the quotient departs from the
    solver's eigenvalue: that must be an error, not a frequency."""
    from flexlink.fe.model_at_pose import in_plane_eigen_scale
    from flexlink.fe.assembly import assemble, rigid_elimination
    from flexlink.fe.energy import twice_strain_energy
    from flexlink.errors import NumericalError
    from flexlink.analysis.eigensolver import EigenSolver
    from flexlink.analysis.solve import solve_modes

    model = single_beam("cantilever", 30000)
    K, M = assemble(model)
    with pytest.raises(NumericalError, match="too fine for double precision"):
        solve_modes(K, M, 4, T=rigid_elimination(model), lambda_ref=in_plane_eigen_scale(model), solver=EigenSolver("sparse"),
                    energy=lambda U: twice_strain_energy(model, U))
