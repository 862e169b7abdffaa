"""Claims of the fe stage that the mutation runs found unguarded (docs/testing.md, fourth
round): scaling laws and the conventions the docstrings state, each against an independent
value."""

import math

import pytest

from flexlink.errors import InputError
from flexlink.fe.model import JointSpec, LinkSpec, Section, Topology, build_model
from flexlink.fe.strip import out_of_plane_eigen_scale


def _strip_model(scale: float):
    """A 0.5 m strip of 20 x 2 mm, every length multiplied by ``scale``."""
    strip = Section.rectangle(E=70e9, G=26e9, density=2700.0, width=0.02 * scale,
                              thickness=0.002 * scale)
    joints = (JointSpec("S", True, math.inf, 0.0), JointSpec("E", False, 0.0, 0.0))
    topology = Topology(links=(LinkSpec("strip", "S", "E", strip, 4),), joints=joints)
    return build_model(topology, {"S": (0.0, 0.0), "E": (0.5 * scale, 0.0)})


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
