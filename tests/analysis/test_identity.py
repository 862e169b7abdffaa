"""Mode identity: energy fractions, labels and effective modal masses (analysis/identity.py)."""

import dataclasses

import numpy as np
import pytest

from flexlink.analysis.identity import (effective_masses, energy_parts, mode_identity,
                                        mode_labels, participating_mass, total_mass)
import scipy.linalg as la

from flexlink.fe.assembly import assemble, rigid_elimination
from flexlink.fe.model import JointSpec, LinkSpec, Topology, build_model
from flexlink.output.pose.scene_summary import identity_json
from flexlink.scene import load_scene

from helpers import SECTION, modes_of, single_beam


def _case1(elements=4, joint_mass=0.0):
    scene = load_scene("cases/case1.toml")
    topo = scene.topology(elements)
    if joint_mass:
        joints = tuple(dataclasses.replace(j, mass=joint_mass) if j.name == "B" else j
                       for j in topo.joints)
        topo = dataclasses.replace(topo, joints=joints)
    return build_model(topo, scene.rigid_pose().joints)


@dataclasses.dataclass(frozen=True)
class _Modes:
    eigenvalues: np.ndarray
    shapes: np.ndarray

    @property
    def elastic(self):
        return np.flatnonzero(self.eigenvalues > 1e-6 * self.eigenvalues.max())


def _all_modes(model):
    """Every mode of a small model by plain LAPACK eigh (mass-normalised), independent of
    solve.py: the sums over all modes need the highest ones too."""
    K, M = assemble(model)
    T = rigid_elimination(model)
    if T is not None:
        K, M = T.T @ K @ T, T.T @ M @ T
    vals, vecs = la.eigh(K.toarray(), M.toarray())
    return _Modes(vals, vecs if T is None else np.asarray(T @ vecs))


def test_energy_parts_add_up_to_the_assembled_energies_and_fractions_to_one():
    model = _case1(joint_mass=0.01)
    modes = _all_modes(model)
    K, M = assemble(model)
    U = modes.shapes
    parts = energy_parts(model, U)
    # the parts are u^T K u and u^T M u split link by link and joint by joint: round-off only
    assert np.allclose(parts.strain.sum(axis=0), np.einsum("ik,ik->k", U, K @ U),
                       rtol=1e-9, atol=1e-9 * modes.eigenvalues.max())
    assert np.allclose(parts.kinetic.sum(axis=0), 1.0, rtol=1e-9)  # mass-normalised shapes
    assert parts.kinetic[parts.names.index("B")].max() > 0  # the joint mass takes its part
    strain, kinetic = parts.fractions()
    elastic = modes.elastic
    assert np.allclose(strain[:, elastic].sum(axis=0), 1.0, atol=1e-12)
    assert np.allclose(kinetic.sum(axis=0), 1.0, atol=1e-12)
    assert (strain[:, elastic] >= -1e-12).all() and (kinetic >= -1e-12).all()


def test_effective_masses_of_all_modes_sum_to_the_total_mass():
    model = _case1(joint_mass=0.01)
    modes = _all_modes(model)
    masses = effective_masses(model, modes.shapes)
    expected = sum(l.section.mass_per_length * l.length for l in model.links) + 0.01
    assert total_mass(model) == pytest.approx(expected, rel=1e-14)
    # no joint of case 1 is grounded rigidly in translation: the whole mass takes part
    assert masses.sum(axis=0) == pytest.approx([expected, expected], rel=1e-10)
    assert participating_mass(model) == pytest.approx([expected, expected], rel=1e-12)


def test_free_beam_puts_its_whole_mass_in_the_rigid_body_modes():
    model = single_beam("free-free", 8, angle=0.3)
    modes = _all_modes(model)
    masses = effective_masses(model, modes.shapes)
    mass = SECTION.mass_per_length
    assert masses.sum(axis=0) == pytest.approx([mass, mass], rel=1e-10)
    # elastic modes of a free body carry no net momentum
    assert masses[modes.elastic].max() < 1e-10 * mass


def test_rigidly_grounded_mass_does_not_take_part():
    model = single_beam("cantilever", 8)
    modes = _all_modes(model)
    masses = effective_masses(model, modes.shapes)
    part = participating_mass(model)
    assert masses.sum(axis=0) == pytest.approx(part, rel=1e-10)
    assert (part < total_mass(model)).all()  # the clamped node's share stays with the ground


def test_labels_name_the_bending_link_and_the_soft_joint_springs():
    modes = modes_of(single_beam("cantilever", 16), 3)
    labels = mode_labels(energy_parts(single_beam("cantilever", 16), modes.shapes))
    assert labels[:2] == ["beam bending 1", "beam bending 2"]
    # a stiff bar on soft translational springs at both ends: it bounces on the springs
    soft = Topology(links=(LinkSpec("bar", "S", "E", SECTION, 8),),
                    joints=(JointSpec("S", ground=True, Kt=100.0, Kr=0.0),
                            JointSpec("E", ground=True, Kt=100.0, Kr=0.0)))
    model = build_model(soft, {"S": (0.0, 0.0), "E": (1.0, 0.0)})
    identity = mode_identity(model, modes_of(model, 2).shapes)
    assert identity.labels[0] == "joint springs S, E (axial)" or \
        identity.labels[0] == "joint springs E, S (axial)"
    assert identity.effective_mass.shape == (2, 2)  # per mode, in x and y


def test_modes_command_prints_and_writes_the_identity(tmp_path):
    import json

    from click.testing import CliRunner

    from flexlink.cli import main

    result = CliRunner().invoke(main, ["modes", "cases/case1.toml", "-e", "8", "--json",
                                       "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    case = json.loads(result.output)["cases"][0]
    for row in case["modes"]:
        assert {"label", "strain_energy", "kinetic_energy", "effective_mass_kg"} <= set(row)
        assert sum(row["strain_energy"].values()) == pytest.approx(1.0, abs=1e-12)
    assert case["mass_kg"]["total"] > 0
    header = (tmp_path / "case1" / "modes.csv").read_text().splitlines()[0].split(",")
    assert {"label", "strain_coupler", "kinetic_coupler", "m_eff_x_kg", "m_eff_y_kg"} <= set(header)
    table = CliRunner().invoke(main, ["modes", "cases/case1.toml", "-e", "8", "--out",
                                      str(tmp_path)]).output
    assert "label" in table and "bending" in table


@pytest.fixture(scope="module")
def case1_identity():
    model = _case1()
    return mode_identity(model, modes_of(model, 3).shapes)


def test_each_modes_energy_fractions_sum_to_one(case1_identity):
    """Strain and kinetic parts each split u^T K u and u^T M u: a row sums to 1 (round-off)."""
    assert len(case1_identity) == 3
    np.testing.assert_allclose(case1_identity.strain.sum(axis=1), 1.0, rtol=0, atol=1e-12)
    np.testing.assert_allclose(case1_identity.kinetic.sum(axis=1), 1.0, rtol=0, atol=1e-12)


@pytest.mark.parametrize("field, cut", [
    ("strain", np.s_[:, 1:]), ("kinetic", np.s_[1:]), ("effective_mass", np.s_[:, :1])])
def test_an_identity_of_the_wrong_shape_is_refused_naming_the_field(case1_identity, field, cut):
    bad = getattr(case1_identity, field)[cut]
    with pytest.raises(ValueError, match=rf"ModeIdentity\.{field} has shape"):
        dataclasses.replace(case1_identity, **{field: bad})


def test_a_joint_mass_kinetic_fraction_is_its_share_of_u_m_u():
    """A lumped mass m at joint B moves with its node: its part of u^T M u is m |u_B|^2."""
    model = _case1(joint_mass=0.01)
    U = modes_of(model, 3).shapes
    M = assemble(model)[1]
    node_part = sum(m * (U[3 * n] ** 2 + U[3 * n + 1] ** 2) for n, m in model.point_masses)
    identity = mode_identity(model, U)
    expected = node_part / np.einsum("ik,ik->k", U, M @ U)
    # fractions of one sum computed two ways: round-off only
    np.testing.assert_allclose(identity.kinetic[:, identity.parts.index("B")], expected,
                               rtol=1e-10)
    # and the JSON fields say the same, with the effective masses in x and y
    masses = effective_masses(model, U)
    for j in range(3):
        row = identity_json(identity, j)
        assert row["kinetic_energy"]["B"] == pytest.approx(expected[j], rel=1e-10)
        assert row["effective_mass_kg"] == {"x": masses[j, 0], "y": masses[j, 1]}


def test_joints_are_named_by_their_share_and_fractions_are_scale_free():
    # a bar on translational springs 100 and 300 N/m: its second mode stores more energy in
    # the stiffer spring. Swapping the springs mirrors the system, so it must swap the names
    def bar(k_start, k_end):
        soft = Topology(links=(LinkSpec("bar", "S", "E", SECTION, 8),),
                        joints=(JointSpec("S", ground=True, Kt=k_start, Kr=0.0),
                                JointSpec("E", ground=True, Kt=k_end, Kr=0.0)))
        return build_model(soft, {"S": (0.0, 0.0), "E": (1.0, 0.0)})

    labels = []
    for model in (bar(100.0, 300.0), bar(300.0, 100.0)):
        shapes = modes_of(model, 3).shapes
        parts = energy_parts(model, shapes)
        j = 1
        share = {name: parts.strain[parts.names.index(name), j] for name in "SE"}
        first, second = sorted(share, key=lambda name: -share[name])
        assert share[second] > 0.2 * share[first]  # both springs carry a named share
        labels.append(mode_labels(parts)[j])
        # fractions do not depend on the shapes' scale; the bar's own strain is a difference
        # of nearly equal nodal terms (it hardly bends), so its share carries ~1e-12 round-off
        for scaled, plain in zip(energy_parts(model, 3.0 * shapes).fractions(), parts.fractions()):
            np.testing.assert_allclose(scaled, plain, rtol=0, atol=1e-10)
    assert labels == ["joint springs E, S (axial)", "joint springs S, E (axial)"]
