"""Rule of mixtures for the Table I constituents."""

import math
from pathlib import Path

import pytest

from flexlink.errors import InputError
from flexlink.materials.mixtures import load_constituent, rule_of_mixtures, woven_beam_modulus, woven_composite


@pytest.fixture(scope="module")
def ply():
    return rule_of_mixtures(load_constituent("carbon_fiber"), load_constituent("polyester"), 0.5)


def test_table1_values_read_in_si():
    cf = load_constituent("carbon_fiber")
    assert (cf.E, cf.G, cf.density, cf.poisson) == (201e9, 1526e6, 1730.0, 0.21)
    assert cf.spread == {"E": 20e9, "G": 643e6, "density": 10.0}


def test_rule_of_mixtures_at_half_fraction(ply):
    assert math.isclose(ply.E1, 0.5 * 201e9 + 0.5 * 2.4e9)
    assert math.isclose(ply.E2, 1 / (0.5 / 201e9 + 0.5 / 2.4e9))
    assert math.isclose(ply.density, 1490.0)
    assert math.isclose(ply.nu12, 0.28)
    assert ply.E2 < ply.E1  # Reuss below Voigt


def test_woven_beam_modulus_reference_value(ply):
    E = woven_beam_modulus(ply)
    # documented reference: 53.4 GPa, within 0.5 % of (E1 + E2)/2
    assert abs(E / 53.4e9 - 1) < 1e-3
    assert abs(E / (0.5 * (ply.E1 + ply.E2)) - 1) < 5e-3


def test_isotropic_limit_gives_back_the_modulus():
    """Fibre = matrix: every mixture rule must return that material's own modulus."""
    m = load_constituent("polyester")
    same = rule_of_mixtures(m, m, 0.3)
    assert math.isclose(same.E1, m.E) and math.isclose(same.E2, m.E)
    # an isotropic 'fabric' narrow strip has modulus E exactly (no Poisson stiffening)
    assert math.isclose(woven_beam_modulus(same), m.E, rel_tol=1e-12)
    assert woven_composite(m, m, 0.3).density == m.density


def test_shipped_materials_are_the_repository_files():
    """Installed or not, the shipped folder holds exactly the files of materials/."""
    from flexlink.materials.mixtures import shipped_materials

    repo = Path(__file__).resolve().parents[2] / "materials"
    shipped = {p.name: p.read_bytes() for p in shipped_materials().iterdir()
               if p.name.endswith(".toml")}
    assert shipped == {p.name: p.read_bytes() for p in repo.glob("*.toml")}


def test_unknown_material_names_the_shipped_ones():
    from flexlink.materials.mixtures import load_constituent

    with pytest.raises(InputError) as info:
        load_constituent("unobtainium")
    message = str(info.value)
    # the shipped names as a user writes them, and no install path to puzzle over
    assert message.startswith("unknown material 'unobtainium'; shipped materials: "
                              "aisi_1020_cd, aisi_1080, carbon_fiber, polyester, steel"), message
    assert "/" not in message.split("(expected")[0], message


def test_rule_of_mixtures_away_from_half_fraction():
    """At Vf = 0.5 the fibre and matrix fractions are equal, so swapping them goes unseen;
    Vf = 0.3 against the formulas written out with Table I values."""
    ply = rule_of_mixtures(load_constituent("carbon_fiber"), load_constituent("polyester"), 0.3)
    assert math.isclose(ply.E1, 0.3 * 201e9 + 0.7 * 2.4e9, rel_tol=1e-14)  # 61.98 GPa
    assert math.isclose(ply.E2, 1 / (0.3 / 201e9 + 0.7 / 2.4e9), rel_tol=1e-14)
    assert math.isclose(ply.G12, 1 / (0.3 / 1526e6 + 0.7 / 50e6), rel_tol=1e-14)
    assert math.isclose(ply.nu12, 0.3 * 0.21 + 0.7 * 0.35, rel_tol=1e-14)
    assert math.isclose(ply.density, 0.3 * 1730 + 0.7 * 1250, rel_tol=1e-14)  # 1394 kg/m^3


def test_woven_modulus_by_hand_at_vf_0_3():
    """Balanced 0/90 strip: E = A11 - A12^2 / A11 with A11 = (Q11 + Q22)/2, written out."""
    E1, E2, nu12 = 0.3 * 201e9 + 0.7 * 2.4e9, 1 / (0.3 / 201e9 + 0.7 / 2.4e9), 0.3 * 0.21 + 0.7 * 0.35
    d = 1 - nu12 * nu12 * E2 / E1
    a11, a12 = 0.5 * (E1 + E2) / d, nu12 * E2 / d
    beam = woven_composite(load_constituent("carbon_fiber"), load_constituent("polyester"), 0.3)
    assert math.isclose(beam.E, a11 - a12**2 / a11, rel_tol=1e-13)
    assert math.isclose(beam.G, 1 / (0.3 / 1526e6 + 0.7 / 50e6), rel_tol=1e-14)


@pytest.mark.parametrize("vf", [0.0, 1.0, -0.1, 1.2])
def test_fibre_fraction_outside_open_unit_interval_is_refused(vf):
    m = load_constituent("polyester")
    with pytest.raises(InputError, match="fiber_volume_fraction"):
        rule_of_mixtures(m, m, vf)


def test_a_constituent_file_is_read_again_when_it_changes_and_a_folder_is_no_file(tmp_path):
    import os

    from flexlink.errors import InputError
    from flexlink.materials.mixtures import shipped_materials
    path = tmp_path / "resin.toml"
    text = (shipped_materials() / "polyester.toml").read_text()
    path.write_text(text)
    first = load_constituent(str(path))
    assert load_constituent(str(path)) is first  # kept while the file is unchanged
    path.write_text(text.replace('mean = "1.25 g/cm^3"', 'mean = "1.35 g/cm^3"'))
    os.utime(path, ns=(0, path.stat().st_mtime_ns + 10**9))  # a new mtime even on coarse clocks
    assert load_constituent(str(path)).density == pytest.approx(1350.0)
    (tmp_path / "folder.toml").mkdir()
    with pytest.raises(InputError, match="no material file"):
        load_constituent(str(tmp_path / "folder.toml"))
