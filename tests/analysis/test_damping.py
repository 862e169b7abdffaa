"""Modal damping from material loss factors (``analysis/damping.py``): the closed form for one
material, a complex-modulus eigen solve for a mixed linkage, the input's defaults and its
range errors."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import scipy.linalg as la
from click.testing import CliRunner
from conftest import CASES_DIR

from flexlink.analysis.damping import damping_ratios
from flexlink.analysis.modal import analyze
from flexlink.cli import main
from flexlink.errors import InputError
from flexlink.fe.assembly import assemble, rigid_elimination
from flexlink.fe.model import build_model
from flexlink.scene import load_scene

CASE = CASES_DIR / "case1.toml"
ELEMENTS = 8  # per link: enough for a 100-DOF dense complex eigen solve, cheap
N_MODES = 4


def _zeta(scene, n_modes=N_MODES):
    result = analyze(scene, n_modes, ELEMENTS)
    shapes = result.modes.shapes[:, result.modes.elastic[:n_modes]]
    return result, damping_ratios(result.model, shapes, scene.loss_factors)


def test_one_material_without_spring_energy_gives_half_the_loss_factor():
    """Every mode's strain energy sits in links of one material (rigid pins, free Kr, rigid
    drive: the springs hold none), so zeta = eta / 2 exactly; round-off only (1e-13)."""
    eta = 0.004
    scene = load_scene(CASE, {"material.loss_factor": eta, "joints.Kt": "rigid"})
    _, zeta = _zeta(scene)
    assert np.allclose(zeta, eta / 2, rtol=1e-13, atol=0)


def test_joint_springs_carry_no_loss():
    """With compliant pins (Kt 1e6 N/m, no loss) every mode damps less than eta / 2, more so the
    more energy the springs hold."""
    eta = 0.004
    scene = load_scene(CASE, {"material.loss_factor": eta})
    result, zeta = _zeta(scene)
    identity = _identity(result)
    in_links = np.array([sum(v for k, v in zip(identity.parts, row) if k in scene.loss_factors)
                         for row in identity.strain])
    assert np.all(in_links < 1) and np.allclose(zeta, eta / 2 * in_links, rtol=1e-12)


def _identity(result):
    from flexlink.analysis.identity import mode_identity
    return mode_identity(result.model, result.modes.shapes[:, result.modes.elastic[:N_MODES]])


def _complex_modulus_zeta(scene, frequencies):
    """Damping ratios of the modes nearest ``frequencies`` [Hz] from the dense complex
    eigenproblem (K + i sum_p eta_p K_p) u = lambda M u, K_p each link's own stiffness (the
    model's K is linear in E and G: doubling link p's moduli adds K_p once). Exact for a
    hysteretic mode: s^2 = -lambda, zeta = -Re(s) / |s| = sin(arg(lambda) / 2)."""
    pose = scene.rigid_pose()
    topology = scene.topology(ELEMENTS)
    model = build_model(topology, pose.joints)
    K, M = (m.toarray() for m in assemble(model))
    lossy = np.zeros_like(K)
    for i, link in enumerate(topology.links):
        stiffer = dataclasses.replace(link.section, E=2 * link.section.E, G=2 * link.section.G)
        links = list(topology.links)
        links[i] = dataclasses.replace(link, section=stiffer)
        K2 = assemble(build_model(dataclasses.replace(topology, links=tuple(links)),
                                  pose.joints))[0].toarray()
        lossy += scene.loss_factors[link.name] * (K2 - K)
    T = rigid_elimination(model)
    T = np.eye(K.shape[0]) if T is None else T.toarray()
    lam = la.eigvals(T.T @ (K + 1j * lossy) @ T, T.T @ M @ T)
    lam = lam[np.isfinite(lam)]
    out = []
    for f in frequencies:
        nearest = lam[np.argmin(abs(lam.real - (2 * np.pi * f) ** 2))]
        out.append(np.sin(np.angle(nearest) / 2))
    return np.array(out)


@pytest.mark.parametrize("eta", [(0.04, 0.002), (0.002, 0.049)])
def test_mixed_linkage_matches_a_complex_modulus_solve(eta):
    """A steel-like coupler with another loss factor than the composite crank and rocker,
    compliant pins (no loss): the strain-energy zeta is within 1 % of the complex-modulus
    eigenvalue's (the difference is second order in eta and in the shape change)."""
    composite, metal = eta
    scene = load_scene(CASE, {"material.loss_factor": composite,
                              "links.coupler.material": {"E": "210 GPa", "density": "7850 kg/m^3",
                                                         "loss_factor": metal}})
    assert scene.loss_factors == {"crank": composite, "coupler": metal, "rocker": composite}
    result, zeta = _zeta(scene)
    exact = _complex_modulus_zeta(scene, result.elastic_frequencies(N_MODES))
    spread = np.ptp(zeta) / zeta.max()
    assert spread > 0.1  # the modes really mix the two loss factors
    assert np.allclose(zeta, exact, rtol=0.01, atol=0)


def test_default_loss_factor_comes_from_the_material_file_and_is_listed(tmp_path):
    material = tmp_path / "alloy.toml"
    material.write_text('name = "alloy"\nE = { mean = "70 GPa" }\nG = { mean = "26 GPa" }\n'
                        'density = { mean = "2700 kg/m^3" }\npoisson = { mean = 0.33 }\n'
                        'loss_factor = { mean = 3e-4, low = 1e-4, high = 1e-3, source = "test" }\n')
    scene = load_scene(CASE, {"material": {"isotropic": str(material)}})
    assert set(scene.loss_factors.values()) == {3e-4}
    listed = [a for a in scene.assumptions if a.field == "material.loss_factor"]
    assert len(listed) == 1 and "material file" in listed[0].note and "1e-4" not in listed[0].value
    default = load_scene(CASE)
    assert set(default.loss_factors.values()) == {0.01}  # woven composite default
    assert any(a.field == "material.loss_factor" for a in default.assumptions)
    given = load_scene(CASE, {"material.loss_factor": 0.02})
    assert not any(a.field.endswith("loss_factor") for a in given.assumptions)


@pytest.mark.parametrize("value", [-0.01, 1.0, 2.5])
def test_loss_factor_outside_range_is_one_line(tmp_path, value):
    scene = tmp_path / "lossy.toml"
    scene.write_text(f'base = "{CASE.as_posix()}"\n[material]\nloss_factor = {value}\n')
    result = CliRunner().invoke(main, ["modes", str(scene), "--out", str(tmp_path / "o")])
    assert result.exit_code == 2
    assert "lossy.toml" in result.output and "material.loss_factor" in result.output
    assert "[0, 1)" in result.output and "Traceback" not in result.output


def test_material_file_loss_factor_outside_range(tmp_path):
    material = tmp_path / "bad.toml"
    material.write_text('E = { mean = "70 GPa" }\nG = { mean = "26 GPa" }\n'
                        'density = { mean = "2700 kg/m^3" }\npoisson = { mean = 0.33 }\n'
                        'loss_factor = { mean = 1.5 }\n')
    with pytest.raises(InputError, match=r"bad\.toml: loss_factor\.mean: got 1\.5 .*\[0, 1\)"):
        load_scene(CASE, {"material": {"isotropic": str(material)}})


def test_modes_command_shows_zeta_and_its_assumption(tmp_path):
    """The JSON case carries damping_ratio per mode (eta / 2 weighted by the links' strain share, so below
    the composite default's 0.005 with compliant pins); the text shows a zeta % line and the
    assumed loss factor."""
    import json

    args = ["modes", str(CASE), "-e", str(ELEMENTS), "--out", str(tmp_path)]
    document = json.loads(CliRunner().invoke(main, args + ["--json"]).output)
    case = document["cases"][0]
    zeta = case["damping_ratio"]
    assert len(zeta) == len(case["modes"])
    assert all(0.004 < z < 0.005 for z in zeta)
    assert any(a["field"] == "material.loss_factor" for a in case["assumptions"])
    text = CliRunner().invoke(main, args).output
    assert "damping ratio zeta %" in text and "damping: material.loss_factor = 0.01" in text


def _declared_case(tmp_path, damping: str):
    scene = tmp_path / "declared.toml"
    scene.write_text(f'base = "{CASE.as_posix()}"\n[damping]\n{damping}\n')
    return scene


def _modes_json(scene, tmp_path):
    import json

    args = ["modes", str(scene), "-e", str(ELEMENTS), "-n", str(N_MODES), "--json",
            "--out", str(tmp_path / "out")]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    return json.loads(result.output)["cases"][0]


def test_rayleigh_damping_matches_the_damped_eigenvalues(tmp_path):
    """C = alpha M + beta K: the printed ratios equal those of the damped quadratic eigenproblem
    (s^2 M + s C + K) u = 0 solved densely here in first-order form (zeta = -Re s / |s|), to
    1e-7: Rayleigh damping leaves the undamped modes uncoupled, so the two agree exactly up to
    the eigen solvers' round-off."""
    alpha, beta = 3.0, 2e-5  # both terms matter: alpha/(2w) and beta w/2 are each ~1e-3..1e-2
    case = _modes_json(_declared_case(tmp_path, f"rayleigh_alpha = {alpha}\n"
                                                f"rayleigh_beta = {beta}"), tmp_path)
    scene = load_scene(CASE)
    pose = scene.rigid_pose()
    model = build_model(scene.topology(ELEMENTS), pose.joints)
    K, M = (m.toarray() for m in assemble(model))
    T = rigid_elimination(model)
    T = np.eye(K.shape[0]) if T is None else T.toarray()
    K, M = T.T @ K @ T, T.T @ M @ T
    n = K.shape[0]
    C = alpha * M + beta * K
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-la.solve(M, K), -la.solve(M, C)]])
    s = la.eigvals(A)
    s = s[(s.imag > 1.0)]  # one of each conjugate pair; the mechanism modes are overdamped
    computed = np.array([row["computed_Hz"] for row in case["modes"]])
    zeta = []
    for f in computed:
        nearest = s[np.argmin(abs(abs(s) - 2 * np.pi * f))]
        zeta.append(-nearest.real / abs(nearest))
    assert np.allclose(case["damping_ratio"], zeta, rtol=1e-7, atol=0)
    assert "Rayleigh" in case["damping_source"]


def test_declared_ratios_apply_per_mode_and_replace_the_loss_factors(tmp_path):
    """ratios = [a, b]: mode 1 gets a, every later mode b; no loss factor is then assumed."""
    case = _modes_json(_declared_case(tmp_path, "ratios = [0.03, 0.012]"), tmp_path)
    assert case["damping_ratio"] == [0.03] + [0.012] * (N_MODES - 1)
    assert not any(a["field"].endswith("loss_factor") for a in case["assumptions"])
    one = _modes_json(_declared_case(tmp_path, "ratio = 0.02"), tmp_path)
    assert one["damping_ratio"] == [0.02] * N_MODES


@pytest.mark.parametrize("damping, field, expected", [
    ("ratio = 1.2", "damping.ratio", "[0, 1)"),
    ("ratio = -0.1", "damping.ratio", "[0, 1)"),
    ("ratios = [0.01, 1.0]", "damping.ratios", "[0, 1)"),
    ("rayleigh_alpha = -1", "damping.rayleigh_alpha", "[0, 1e+06]"),
    ("ratio = 0.01\nrayleigh_beta = 1e-5", "damping", "exactly one of"),
    ("ratios = []", "damping", "empty"),
])
def test_declared_damping_out_of_range_is_one_line(tmp_path, damping, field, expected):
    scene = _declared_case(tmp_path, damping)
    result = CliRunner().invoke(main, ["modes", str(scene), "--out", str(tmp_path / "o")])
    assert result.exit_code == 2, result.output
    line = result.output.strip()
    assert "\n" not in line and "declared.toml" in line and field in line and expected in line
