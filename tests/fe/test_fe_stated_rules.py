"""Claims of the fe stage that the mutation runs found unguarded (notes/history.md, fourth
round): scaling laws and the conventions the docstrings state, each against an independent
value."""

import math

import numpy as np
import pytest

from flexlink.errors import InputError
from flexlink.fe.energy import lumped_mass
from flexlink.fe.link import link_matrices
from flexlink.fe.modeshape import sample_shapes
from flexlink.fe.model import JointSpec, LinkSpec, Section, Topology, build_model
from flexlink.fe.strip import out_of_plane_eigen_scale


def _strip_model(scale: float, elements: int = 4, angle: float = 0.0):
    """A 0.5 m strip of 20 x 2 mm, every length multiplied by ``scale``."""
    strip = Section.rectangle(E=70e9, G=26e9, density=2700.0, width=0.02 * scale,
                              thickness=0.002 * scale)
    joints = (JointSpec("S", True, math.inf, 0.0), JointSpec("E", False, 0.0, 0.0))
    topology = Topology(links=(LinkSpec("strip", "S", "E", strip, elements),), joints=joints)
    end = 0.5 * scale * np.array([math.cos(angle), math.sin(angle)])
    return build_model(topology, {"S": (0.0, 0.0), "E": tuple(end)})


@pytest.mark.parametrize("scale", [0.5, 3.0])
def test_the_out_of_plane_eigenvalue_scale_follows_geometric_similarity(scale):
    """Scaling every length of a linkage by s scales every eigenvalue by s^-2 (omega^2 ~
    E / (rho L^2)): so must the scale [rad^2/s^2] the rigid-body threshold is measured against,
    or the same linkage in other units would sort its modes differently. The strip's bending
    term (EI / rhoA L^4) is the smaller one here, torsion's (GJ / rhoIp L^2) ten thousand times
    larger."""
    ratio = out_of_plane_eigen_scale(_strip_model(scale)) / out_of_plane_eigen_scale(
        _strip_model(1.0))
    assert ratio == pytest.approx(scale**-2, rel=1e-12)  # rounding of the section products


def test_an_unnamed_tube_is_as_unnamed_as_any_section():
    """A section built without a name has the name "" and its refusals name no file; the tube's
    constructor keeps that convention of ``Section`` and ``Section.rectangle``."""
    tube = Section.tube(70e9, 26e9, 2700.0, 0.01, 0.008)
    assert tube.name == Section.rectangle(70e9, 26e9, 2700.0, 0.02, 0.002).name == ""
    with pytest.raises(InputError) as refusal:
        Section.tube(70e9, 26e9, 2700.0, 0.01, 0.012)
    assert refusal.value.source is None
    assert refusal.value.field == "tube"


def test_the_lumped_mass_is_positive_with_the_hrz_rotary_share():
    """HRZ lumping (Hinton, Rock and Zienkiewicz 1976) scales the consistent matrix's diagonal
    to the element mass: an element end gets m / 2 in x and y and, from the consistent
    diagonal's ratio 4 h^2 / 156, m h^2 / 78 in rotation; so at every node of a link the
    rotary entry is h^2 / 39 times the translational one, and every entry is positive (a mass
    matrix: kinetic energy > 0 for any velocity)."""
    model = _strip_model(1.0, elements=5, angle=0.7)
    h = 0.5 / 5
    diag = lumped_mass(model).diagonal().reshape(-1, 3)
    assert (diag > 0).all()
    np.testing.assert_allclose(diag[:, 0], diag[:, 1], rtol=1e-15)  # rotation invariant
    np.testing.assert_allclose(diag[:, 2] / diag[:, 0], h**2 / 39, rtol=1e-13)  # rounding
    assert diag[:, 0].sum() == pytest.approx(2700.0 * 0.02 * 0.002 * 0.5, rel=1e-13)


SECTION = dict(E=70e9, G=26e9, density=2700.0, area=4e-5, second_moment=1.3e-11, depth=0.002)


@pytest.mark.parametrize("field", [*SECTION, "shear_factor"])
@pytest.mark.parametrize("bad", [0.0, -1.0, math.inf, math.nan])
def test_a_section_refuses_a_non_positive_or_non_finite_value_naming_it(field, bad):
    with pytest.raises(InputError) as refusal:
        Section(**{**SECTION, field: bad}, name="strip")
    assert (refusal.value.field, refusal.value.source) == (field, "strip")


def test_a_bending_that_is_not_a_choice_is_refused_naming_the_field():
    with pytest.raises(InputError) as refusal:
        Section(**SECTION, bending="sideways")
    assert refusal.value.field == "section.bending"
    assert "edgewise" in refusal.value.expected and "flatwise" in refusal.value.expected
    with pytest.raises(InputError) as refusal:
        Section.rectangle(70e9, 26e9, 2700.0, 0.02, 0.002, bending="sideways")
    assert refusal.value.field == "section.bending"
    assert "unknown bending 'sideways'" in str(refusal.value)
    assert refusal.value.expected == "edgewise or flatwise"  # the choices, as a user types them


def test_an_unknown_beam_theory_is_refused_naming_it_and_the_theories():
    with pytest.raises(InputError) as refusal:
        Section(**SECTION, beam="bernoulli", name="strip")
    assert (refusal.value.field, refusal.value.source) == ("model.beam", "strip")
    assert "unknown beam theory 'bernoulli'" in str(refusal.value)
    assert refusal.value.expected == "euler-bernoulli or timoshenko"


@pytest.mark.parametrize("argument", ["length", "EA", "EI", "mass_per_length"])
def test_link_matrices_refuse_a_non_positive_input_naming_it(argument):
    """A link 1 mm long with EA = EI = mass per length = 1e-3 (small, all valid) is accepted;
    each input set to 0 is refused naming it."""
    good = dict(length=1e-3, EA=1e-3, EI=1e-3, mass_per_length=1e-3)
    link_matrices(good["length"], 2, good["EA"], good["EI"], good["mass_per_length"])
    bad = {**good, argument: 0.0}
    with pytest.raises(InputError) as refusal:
        link_matrices(bad["length"], 2, bad["EA"], bad["EI"], bad["mass_per_length"])
    assert refusal.value.field == argument
    assert "positive and finite, got 0.0" in str(refusal.value)


def test_a_pose_without_a_joint_or_with_a_zero_length_link_is_refused():
    strip = Section.rectangle(E=70e9, G=26e9, density=2700.0, width=0.02, thickness=0.002)
    joints = (JointSpec("S", True, math.inf, 0.0), JointSpec("E", False, 0.0, 0.0))
    topology = Topology(links=(LinkSpec("strip", "S", "E", strip, 2),), joints=joints)
    with pytest.raises(InputError) as refusal:
        build_model(topology, {"S": (0.0, 0.0)})
    assert refusal.value.field == "pose" and "'E'" in str(refusal.value)
    with pytest.raises(InputError) as refusal:
        build_model(topology, {"S": (0.1, 0.2), "E": (0.1, 0.2)})
    assert refusal.value.field == "links.strip" and "zero length" in str(refusal.value)


def test_one_subdivision_samples_the_nodes_only():
    """``sample_shapes``' stated range: subdivisions >= 1, and 1 gives the nodes only, so the
    samples are the model's own nodes and nodal values (any shape vector); 0 is refused."""
    model = _strip_model(1.0, elements=3, angle=0.4)
    shapes = np.random.default_rng(5).normal(size=(model.n_dofs, 2))
    sampled = sample_shapes(model, shapes, subdivisions=1)
    np.testing.assert_array_equal(sampled.point_node, np.arange(len(model.nodes)))
    np.testing.assert_allclose(sampled.points, model.nodes, rtol=0, atol=1e-15)  # metres
    nodal = shapes.reshape(-1, 3, 2)
    np.testing.assert_allclose(sampled.displacement, nodal[:, :2], rtol=1e-14, atol=1e-15)
    np.testing.assert_allclose(sampled.rotation, nodal[:, 2], rtol=1e-14, atol=1e-15)
    with pytest.raises(ValueError, match="subdivisions must be >= 1"):
        sample_shapes(model, shapes, subdivisions=0)


def test_a_spring_is_made_rigid_from_a_million_times_the_stiffest_element_of_its_kind():
    """fe/rigid.py: a spring at least 1e6 times the stiffest element of its kind becomes an
    exact constraint; translational: the larger of EA/h and 12 EI/h^3 over all elements,
    rotational: 4 EI/h. Two links of other sections and meshes; the maxima are b's, EA/h =
    3.4e8 N/m (its 12 EI/h^3 is 8.6e6 N/m) and 4 EI/h = 1.8e3 N m/rad."""
    from flexlink.fe.rigid import rigid_threshold

    a = Section.rectangle(E=70e9, G=26e9, density=2700.0, width=0.02, thickness=0.002)
    b = Section.rectangle(E=210e9, G=81e9, density=7850.0, width=0.01, thickness=0.004,
                          bending="flatwise")
    joints = (JointSpec("S", True, 1e5, 10.0), JointSpec("M", False, 1e5, 10.0),
              JointSpec("E", True, 1e5, 10.0))
    links = (LinkSpec("a", "S", "M", a, 2), LinkSpec("b", "M", "E", b, 8))
    model = build_model(Topology(links=links, joints=joints),
                        {"S": (0.0, 0.0), "M": (0.7, 0.0), "E": (0.7, 0.2)})
    h = {"a": 0.35, "b": 0.025}  # element lengths [m]
    trans = max(max(s.E * s.area / h[n], 12 * s.E * s.second_moment / h[n] ** 3)
                for n, s in (("a", a), ("b", b)))
    rot = max(4 * s.E * s.second_moment / h[n] for n, s in (("a", a), ("b", b)))
    rotational = model.springs.dof_a % 3 == 2
    assert rotational.any() and not rotational.all()
    expected = 1e6 * np.where(rotational, rot, trans)
    np.testing.assert_allclose(rigid_threshold(model), expected, rtol=1e-13)  # round-off
