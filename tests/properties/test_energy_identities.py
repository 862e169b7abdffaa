"""Energy identities of every returned mode, against K and M assembled from the scene.

- The strain and kinetic energy fractions the tool prints per link and joint are
  non-negative and sum to 1, and their totals are u^T K u and u^T M u.
- The Rayleigh quotient of each returned shape equals its eigenvalue (in either mass model).
- A rigid motion of the whole linkage strains no link.
- The fractions are the derivatives of the frequencies (Hellmann-Feynman: for a simple
  eigenvalue, d lambda / d p = u^T (dK/dp - lambda dM/dp) u with u^T M u = 1). Hence, with
  the joint springs and masses held fixed,
      d ln f / d ln E   = (link strain fraction) / 2            (G scaled with E)
      d ln f / d ln rho = -(link kinetic fraction) / 2
  and for Euler-Bernoulli links (mapping u' = s u on translations, rotations kept):
      d ln f / d ln L     = (e_axial - e_bending + 2 e_Kt - 3 k_links - 2 k_joints) / 2
                            (every length times s, sections fixed)
      d ln f / d ln depth = (e_axial + 3 e_bending - k_links) / 2
                            (the in-plane depth times s: A times s, I times s^3)
  where e are strain fractions (links' axial and bending parts, joints' Kt part) and k
  kinetic fractions. A wrong fraction, a wrong split between axial and bending, or a wrong
  kinetic share breaks one of these.
- Effective masses: over every mode of a small model, the effective masses for ground motion
  in x (and in y) sum to the participating mass r^T M r, which is the whole mass of links and
  joints when no joint is rigidly grounded; and each printed effective mass equals
  (u^T M r)^2 recomputed from M, the shape and the rigid translation r.
"""

import dataclasses
import math

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
from hypothesis import assume, given
from hypothesis import strategies as st
from strategies import JointValues, linkages, load, scaled

from flexlink.analysis.identity import effective_masses, energy_parts
from flexlink.analysis.modal import Mass, analyze
from flexlink.fe.assembly import assemble, rigid_elimination
from flexlink.fe.energy import lumped_mass
from flexlink.analysis.mesh import COMMAND_LINE, MeshRule
from flexlink.output.pose.scene_summary import comparison_rows
from flexlink.studies.pose.scene_summary import summary_of

N_MODES = 3
# Fractions are ratios of energies that each carry round-off of about eps times the largest
# element energy they sum; 1e-10 is far above that for meshes of a few elements.
FRACTION_TOL = 1e-10
# A Rayleigh quotient with the assembled K against the returned eigenvalue (an energy
# Rayleigh quotient without K's cancellation): u^T K u summed from entries of the size of the
# stiffest element carries round-off of about eps lambda_max / lambda relative (lambda_max the
# largest diagonal ratio K_ii / M_ii). ``rq_rtol`` allows 100 times that, plus 1e-9.
RQ_RTOL = 1e-9


def rq_rtol(K, M, lam):
    """Relative tolerance [-] of u^T K u for modes of eigenvalue ``lam`` (see RQ_RTOL)."""
    k, m = K.diagonal(), M.diagonal()
    lam_max = np.max(k[m > 0] / m[m > 0])
    return RQ_RTOL + 100 * np.finfo(float).eps * lam_max / np.abs(lam)
STEP = 1e-4  # relative step of the central differences
# Central differences of ln f with STEP: truncation ~STEP^2 (1e-8), round-off ~1e-13 / STEP
# (1e-9); 1e-6 is well above both and far below any wrong fraction.
SLOPE_TOL = 1e-6
GAP = 1e-2  # modes closer than this (relative) may swap under the steps: left out


def reduced_pair(model, mass="consistent"):
    """(K, M, T) assembled from the model, M in the mass model ``mass``; T the identity when
    nothing is rigid."""
    K, M = assemble(model)
    if mass == "lumped":
        M = lumped_mass(model)
    T = rigid_elimination(model)
    return K, M, sp.identity(model.n_dofs, format="csr") if T is None else T


def elastic_shapes(result):
    modes = result.modes
    return modes.eigenvalues[modes.elastic], modes.shapes[:, modes.elastic]


@given(linkages(), st.sampled_from(tuple(Mass)))
def test_each_shape_has_its_eigenvalue_as_rayleigh_quotient(spec, mass):
    result = analyze(load(spec), N_MODES, mass=mass)
    K, M, _ = reduced_pair(result.model, mass)
    lam, U = elastic_shapes(result)
    stiffness = np.einsum("ij,ij->j", U, K @ U)
    inertia = np.einsum("ij,ij->j", U, M @ U)
    np.testing.assert_allclose(inertia, 1.0, rtol=RQ_RTOL)  # mass-normalised, as documented
    assert np.all(np.abs(stiffness / inertia - lam) <= rq_rtol(K, M, lam) * lam)
    np.testing.assert_allclose(result.modes.frequencies, np.sqrt(np.clip(
        result.modes.eigenvalues, 0, None)) / (2 * math.pi), rtol=1e-15)


@given(linkages())
def test_printed_energy_fractions_are_non_negative_and_sum_to_one(spec):
    result = analyze(load(spec), N_MODES)
    rows = comparison_rows(summary_of(result, N_MODES,
                                      MeshRule(result.elements_per_link, COMMAND_LINE)))
    K, M, _ = reduced_pair(result.model)
    lam, U = elastic_shapes(result)
    parts = energy_parts(result.model, U[:, :N_MODES])
    strain = np.einsum("ij,ij->j", U, K @ U)[:N_MODES]
    tol = rq_rtol(K, M, lam[:N_MODES])
    assert np.all(np.abs(parts.strain.sum(axis=0) - strain) <= tol * strain)
    np.testing.assert_allclose(parts.kinetic.sum(axis=0),
                               np.einsum("ij,ij->j", U, M @ U)[:N_MODES], rtol=RQ_RTOL)
    for row in rows:
        for key in ("strain_energy", "kinetic_energy"):
            values = np.array(list(row[key].values()))
            assert np.all(values >= -FRACTION_TOL), (key, row[key])
            assert abs(values.sum() - 1) <= FRACTION_TOL, (key, row[key])


@given(linkages(), st.floats(-1.0, 1.0), st.floats(-1.0, 1.0))
def test_a_rigid_motion_strains_no_link(spec, cx, cy):
    model = analyze(load(spec), 1).model
    x, y = model.nodes[:, 0], model.nodes[:, 1]
    rigid = np.zeros((model.n_dofs, 3))
    rigid[0::3, 0] = 1.0
    rigid[1::3, 1] = 1.0
    rigid[0::3, 2], rigid[1::3, 2], rigid[2::3, 2] = -(y - cy), x - cx, 1.0
    parts = energy_parts(model, rigid)
    links = np.array(parts.is_link)
    # scale: the strain energy of the same links stretched by 100 %
    scale = sum(l.section.EA * l.length for l in model.links)
    assert np.all(np.abs(parts.strain[links]) <= 1e-12 * scale * (1 + cx**2 + cy**2))


def _fractions(result, n):
    """Per elastic mode (first n): link strain e_ax, e_b, joint Kt strain e_t, link and joint
    kinetic fractions."""
    _, U = elastic_shapes(result)
    parts = energy_parts(result.model, U[:, :n])
    links = np.array(parts.is_link)
    strain, kinetic = parts.strain.sum(axis=0), parts.kinetic.sum(axis=0)
    e_ax = parts.axial[links].sum(axis=0) / strain
    e_b = (parts.strain[links] - parts.axial[links]).sum(axis=0) / strain
    e_t = parts.axial[~links].sum(axis=0) / strain
    k_links = parts.kinetic[links].sum(axis=0) / kinetic
    return e_ax, e_b, e_t, k_links, 1 - k_links


def _slope(spec, vary, n):
    """d ln f / d ln p of the first n elastic modes by central differences, where
    ``vary(spec, factor)`` scales p by factor."""
    up = analyze(load(vary(spec, 1 + STEP)), n).elastic_frequencies(n)
    down = analyze(load(vary(spec, 1 - STEP)), n).elastic_frequencies(n)
    return (np.log(up) - np.log(down)) / (math.log1p(STEP) - math.log1p(-STEP))


def _separated(freqs):
    f = np.asarray(freqs)
    gaps = np.array([np.min(np.abs(np.delete(f, i) - fi)) / fi if f.size > 1 else np.inf
                     for i, fi in enumerate(f)])
    return gaps > GAP


SENSITIVITIES = {
    # name: (scaling of the spec, beam theories it holds for, slope from the fractions)
    "modulus": (lambda sp, s: scaled(sp, E=s), ("euler-bernoulli", "timoshenko"),
                lambda e_ax, e_b, e_t, k_l, k_j: (e_ax + e_b) / 2),
    "density": (lambda sp, s: scaled(sp, density=s), ("euler-bernoulli", "timoshenko"),
                lambda e_ax, e_b, e_t, k_l, k_j: -k_l / 2),
    "length": (lambda sp, s: scaled(sp, length=s), ("euler-bernoulli",),
               lambda e_ax, e_b, e_t, k_l, k_j: (e_ax - e_b + 2 * e_t - 3 * k_l - 2 * k_j) / 2),
    "depth": (lambda sp, s: scaled(sp, section=s), ("euler-bernoulli",),
              lambda e_ax, e_b, e_t, k_l, k_j: (e_ax + 3 * e_b - k_l) / 2),
}


@given(st.sampled_from(sorted(SENSITIVITIES)), st.data())
def test_energy_fractions_are_the_frequency_sensitivities(name, data):
    vary, theories, law = SENSITIVITIES[name]
    spec = data.draw(linkages(beam=data.draw(st.sampled_from(theories))))
    n = 2
    result = analyze(load(spec), n)
    f = result.elastic_frequencies(n)
    keep = _separated(result.modes.elastic_frequencies[: n + 1])[:n]
    assume(keep.any())
    expected = law(*_fractions(result, n))
    measured = _slope(spec, vary, n)
    np.testing.assert_allclose(measured[keep], expected[keep], atol=SLOPE_TOL, err_msg=str(f))


def _complete_modes(model):
    """Every mode of the model (an independent dense solve): mass-normalised full shapes."""
    K, M, T = reduced_pair(model)
    Kr, Mr = (T.T @ K @ T).toarray(), (T.T @ M @ T).toarray()
    _, Q = la.eigh(Kr, Mr)
    return np.asarray(T @ Q), M, T


def _translation(model, T):
    """(n, 2) rigid translation in x and y of every DOF that is not fixed to the ground."""
    r = np.zeros((model.n_dofs, 2))
    r[0::3, 0], r[1::3, 1] = 1.0, 1.0
    grounded = np.asarray(abs(T).sum(axis=1)).ravel() == 0
    r[grounded] = 0.0
    return r


@given(linkages(elements=st.just(2)), st.booleans())
def test_effective_masses_of_all_modes_sum_to_the_participating_mass(spec, float_ground):
    if float_ground:  # no rigid ground bearing: every kilogram takes part in ground motion
        joints = {n: JointValues(j.Kt if math.isfinite(j.Kt) else spec.E * 1e-3, j.Kr, j.mass)
                  for n, j in spec.joints.items()}
        spec = dataclasses.replace(spec, joints=joints)
    model = analyze(load(spec), 1).model
    U, M, T = _complete_modes(model)
    r = _translation(model, T)
    total = effective_masses(model, U).sum(axis=0)
    participating = np.einsum("ij,ij->j", r, M @ r)
    np.testing.assert_allclose(total, participating, rtol=1e-9)
    if float_ground:
        np.testing.assert_allclose(total, spec.total_mass, rtol=1e-9)


@given(linkages())
def test_printed_effective_masses_match_a_recomputation_from_m_and_the_shape(spec):
    result = analyze(load(spec), N_MODES)
    rows = comparison_rows(summary_of(result, N_MODES,
                                      MeshRule(result.elements_per_link, COMMAND_LINE)))
    _, M, T = reduced_pair(result.model)
    _, U = elastic_shapes(result)
    r = _translation(result.model, T)
    gamma = U[:, :N_MODES].T @ (M @ r)
    printed = np.array([[row["effective_mass_kg"]["x"], row["effective_mass_kg"]["y"]]
                        for row in rows])
    np.testing.assert_allclose(printed, gamma**2, rtol=1e-9, atol=1e-12 * spec.total_mass)
