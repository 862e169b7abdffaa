"""Section properties against formulas written out by hand."""

import pytest

from flexlink.fe.model import Section


def test_tube_second_moment_is_the_bending_one_not_the_polar_one():
    """ro = 10 mm, ri = 8 mm: I = pi (1e-8 - 4.096e-9) / 4 = 4.6370e-9 m^4 (the polar moment
    J = 2 I would be 9.274e-9) and A = pi (1e-4 - 6.4e-5) = 1.1310e-4 m^2."""
    s = Section.tube(E=70e9, G=26e9, density=2700.0, outer_radius=0.010, inner_radius=0.008)
    assert s.second_moment == pytest.approx(4.63699e-9, rel=1e-5)
    assert s.area == pytest.approx(1.13097e-4, rel=1e-5)
    assert s.depth == 0.020


def test_rectangle_bends_about_its_in_plane_depth():
    """width 20 mm (in plane), thickness 1.5 mm: I = 1.5e-3 * 0.02^3 / 12 = 1.0e-9 m^4."""
    s = Section.rectangle(E=53e9, G=1e9, density=1400.0, width=0.020, thickness=1.5e-3)
    assert s.second_moment == pytest.approx(1.0e-9, rel=1e-12)
    assert s.area == pytest.approx(3.0e-5, rel=1e-12) and s.depth == 0.020
    assert s.mass_per_length == pytest.approx(0.042, rel=1e-12)
