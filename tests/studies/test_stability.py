"""The fast stability checks (``flexlink stability``, flexlink/studies/verification/self_checks.py) judged here
against closed forms and tolerances of the tests' own: each check reports the numbers it
measured (``Check.details``), and these tests compare them with what physics demands. The
product's own PASS/FAIL is for users; it is asserted only where the command's exit code is.

Adding a check to the suite: a function in ``stability.FAST`` returning Check(s) with a
descriptive id and its numbers in ``details``, and a test here judging those numbers."""

import dataclasses
import json
import math

import numpy as np
import pytest
from click.testing import CliRunner
from conftest import CASES_DIR
from scipy.optimize import brentq

from flexlink import load_scene
from flexlink.analysis.eigensolver import EigenSolver, Method
from flexlink.analysis.modal import pose_modes
from flexlink.cli import main
from flexlink.scene.plausibility import SHEAR_WARN, SLENDER_LIMIT
from flexlink.studies.verification import self_checks as st

CASE1 = CASES_DIR / "case1.toml"
EPS = np.finfo(float).eps


@pytest.fixture(scope="module")
def scene():
    return load_scene(CASE1)


@pytest.fixture(scope="module")
def checks(scene):
    """Every fast check, run once, by id."""
    results = st.run_checks(scene)
    found = {c.id: c for c in results}
    assert len(found) == len(results), "two checks share an id"
    return found


def test_ids_are_descriptive_names(checks):
    """No issue-list numbers: every id is lower-case words joined by hyphens."""
    for key in checks:
        assert key.replace("-", "").isalpha() and key == key.lower(), key


def test_every_check_says_in_words_what_it_expected_and_got(checks):
    """The command prints name, expected and got for people: each must be text, not empty."""
    for key, check in checks.items():
        for text in (check.name, check.expected, check.got):
            assert isinstance(text, str) and text.strip(), (key, text)


def test_bearing_sweep(scene, checks):
    """Kt = Kr = k from 0 to 1e30. At k = 0 only the drive holds anything: each of the three
    links moves as a rigid body in the plane (3 DOFs each) except the crank's rotation, held by
    the rigid drive: 3 x 3 - 1 = 8 zero modes. Adding stiffness never lowers an eigenvalue
    (Rayleigh's monotonicity), up to the eigenvalues' round-off (1e-9 of the largest compared).
    The rigid-joint limit is the exact constraint: the same matrices, so equal to round-off
    (1e-12); the stiffest penalty spring is within its own error (element stiffness / k, below
    1e-6 once k is at least 1e6 times the element)."""
    d = checks["bearing-sweep"].details
    links = scene.topology(st.ELEMENTS).links
    assert d["sweep"][0]["zero_modes"] == 3 * len(links) - 1
    lams = np.array(d["eigenvalues"])
    scale = max(np.max(d["exact_eigenvalues"]), 1.0)
    assert np.all(np.diff(lams, axis=0) >= -1e-9 * scale)
    assert np.all(np.isfinite(lams)) and lams.min() >= -1e-9 * scale
    assert d["rigid_vs_exact"] < 1e-12
    assert d["penalty_vs_exact"] < 1e-6
    assert d["backward_error_max"] < 1e-10
    assert d["warnings_logged"] > 0  # the switch from penalty to constraint is logged


def test_free_crank(checks):
    """All Kr = 0 and no drive: one mechanism mode (the four-bar's one degree of freedom),
    listed first and M-orthogonal to the elastic modes (1e-8: the eigen solver's orthogonality).
    A vanishing drive spring k_d then raises each elastic eigenvalue by k_d phi_d^2 (phi_d the
    mode's drive rotation, mass-normalised): first-order perturbation, so d ln f = k_d phi_d^2
    / (2 lambda), within 1 % (the second order is the square of the first)."""
    d = checks["free-crank"].details
    assert d["mechanism_modes"] == 1 and d["kinds"][0] == "rigid-body/mechanism"
    assert d["frequencies_Hz"][0] < 1e-3 * d["elastic_Hz"][0]
    assert d["m_coupling"] < 1e-8
    first_order = (0.5 * d["drive_stiffness"] * np.square(d["drive_rotation"])
                   / np.array(d["eigenvalues"]))
    assert np.all(np.abs(np.array(d["shift"]) - first_order)
                  <= 0.01 * np.abs(first_order) + 1e3 * EPS)


def test_sparse_solver_on_a_mechanism(checks):
    """Shift-invert below zero keeps K - sigma M definite, and the sparse solver finds what the
    dense one does: the same kinds, frequencies within the eigenvalues' round-off,
    100 eps lambda_max / lambda_1 (100: a few ulps per operation over the solve)."""
    d = checks["sparse-mechanism"].details
    assert d["shift"] < 0 and d["kinds_equal"] and d["mechanism_modes"] == 1
    assert d["max_difference"] < max(1e-10, 100 * EPS * d["lambda_max"] / d["lambda_1"])


def _timoshenko_over_euler(E, G, depth, length):
    """f_Timoshenko / f_Euler-Bernoulli of a pinned-pinned rectangular beam's first bending
    mode (shear factor 5/6): the lower root of
    (kGA a^2 - rhoA w^2)(EI a^2 + kGA - rhoI w^2) = (kGA a)^2, a = pi / L, per unit rhoA."""
    a = math.pi / length
    r2 = depth**2 / 12  # I / A
    kG = 5 / 6 * G
    c2, c1, c0 = r2, -(E * r2 * a**2 + kG + r2 * kG * a**2), kG * a**2 * E * r2 * a**2
    w2 = 2 * c0 / (-c1 + math.sqrt(c1 * c1 - 4 * c2 * c0))  # the lower root, no cancellation
    return math.sqrt(w2 / (E * r2 * a**4))


def test_slenderness_warnings(scene, checks):
    """A link gets a warning exactly where Euler-Bernoulli theory stops holding: L/h below
    the slenderness limit, or shear and rotary inertia lowering its first bending frequency
    (pinned-pinned Timoshenko, computed here) by more than the warning's share."""
    rows = checks["slenderness"].details["rows"]
    pose, topology = scene.rigid_pose(), scene.topology(st.ELEMENTS)
    for row in rows:
        assert np.all(np.isfinite(row["f_Hz"])) and min(row["f_Hz"]) > 0
        drops = []
        for spec in topology.links:
            length = math.dist(pose.joints[spec.start], pose.joints[spec.end])
            E, G = ((spec.section.E, spec.section.G) if row["material"] == "scene"
                    else (210e9, 81e9))
            drops.append(1 - _timoshenko_over_euler(E, G, length / row["L_over_h"], length))
        expected = row["L_over_h"] < SLENDER_LIMIT or max(drops) > SHEAR_WARN
        assert bool(row["warnings"]) == expected, row
        assert all("L/h" in w for w in row["warnings"])


def test_kinematic_refusals(checks):
    """R = (0.2, 1.2, 0.9): cos mu = (R4^2 + R3^2 - R2^2 - 1 + 2 R2 cos theta2) / (2 R3 R4)
    spans [41.809, 67.976] deg over the cycle, so mu = 90 deg is refused naming that range."""
    R2, R3, R4 = 0.2, 1.2, 0.9
    mu = [math.degrees(math.acos((R4**2 + R3**2 - R2**2 - 1 + 2 * R2 * c) / (2 * R3 * R4)))
          for c in (1.0, -1.0)]
    got = checks["unreachable-mu"].got
    assert "not reachable" in got and f"[{mu[0]:.3f}, {mu[1]:.3f}]" in got
    assert "cannot close" in checks["non-grashof"].got
    assert "dead centre" in checks["dead-centre"].got


@pytest.mark.parametrize("cid", ["stiffness-contrast", "mass-contrast"])
def test_contrast(checks, cid):
    """A 1e6 stiffness or mass contrast: dense and sparse agree within 1e-8 (the refined
    eigenvalues are accurate to about the square of the vectors' error)."""
    assert checks[cid].details["max_difference"] < 1e-8


STEEL = {"E": 210e9, "G": 81e9, "density": 7850.0}  # [Pa, Pa, kg/m^3]: the checks' steel


@pytest.mark.parametrize("cid, field", [("stiffness-contrast", "E"), ("mass-contrast", "density")])
def test_contrast_models_are_the_ones_described(scene, checks, cid, field):
    """The contrast checks solve the model their text names: a steel crank, the coupler steel
    with its stiffness (E and G) or its density divided by 1e6, the rocker as in the scene.
    Rebuilt here from that description and solved on the same dense path, the frequencies
    agree to round-off (1e-12: one computation, the same operations)."""
    softened = {"E": ("E", "G"), "density": ("density",)}[field]
    coupler = {k: v / 1e6 if k in softened else v for k, v in STEEL.items()}
    topology = scene.topology(st.ELEMENTS)
    links = tuple(dataclasses.replace(spec, section=dataclasses.replace(
        spec.section, **{"crank": STEEL, "coupler": coupler}.get(spec.name, {})))
        for spec in topology.links)
    expected = pose_modes(dataclasses.replace(topology, links=links), scene.rigid_pose().joints, 8,
                          EigenSolver(Method.DENSE))[1].frequencies
    np.testing.assert_allclose(checks[cid].details["dense_Hz"], expected, rtol=1e-12)


def test_dense_refused(checks):
    assert "refused" in checks["dense-refused"].got


def cantilever_frequency(section, length: float) -> float:
    """First bending frequency [Hz] of a clamped-free Euler-Bernoulli beam: beta L the lowest
    root of cos(x) cosh(x) + 1 = 0, f = (beta L)^2 sqrt(EI / (rhoA L^4)) / (2 pi)."""
    beta = brentq(lambda x: math.cos(x) * math.cosh(x) + 1, 1.0, 3.0, xtol=1e-15)
    return beta**2 * math.sqrt(section.EI / (section.mass_per_length * length**4)) / (2 * math.pi)


def test_repeated_eigenvalues(scene, checks):
    """Two identical uncoupled cantilevers: every frequency twice (1e-10: round-off of the
    refined eigenvalues), sparse = dense (1e-10), M-orthonormal (1e-10), no mechanism mode,
    and the first pair at the closed form within 1e-6 (16 cubic elements: the first mode's
    discretisation error is below 1e-8)."""
    d = checks["repeated-eigenvalues"].details
    f, dense = np.array(d["sparse_Hz"]), np.array(d["dense_Hz"])
    assert np.max(np.abs(f[0::2] - f[1::2]) / f[1::2]) < 1e-10
    assert np.max(np.abs(f - dense) / dense) < 1e-10
    assert d["orthogonality"] < 1e-10 and d["mechanism_modes"] == 0
    section = next(iter(scene.sections.values()))
    assert abs(f[0] / cantilever_frequency(section, d["length"]) - 1) < 1e-6


def test_massless_dofs(checks):
    """Rotations without rotary inertia change the frequencies by an O(h^2) amount (below 1e-3
    at 64 elements per link); a massless node on springs is condensed and changes nothing
    (1e-10); a node with neither mass nor stiffness is refused with a reason."""
    rot, node = checks["massless-rotations"].details, checks["massless-node"].details
    assert rot["condensed"] > 0 and rot["max_difference"] < 1e-3
    assert node["condensed"] == 3 and node["max_difference"] < 1e-10
    assert "neither mass nor stiffness" in checks["empty-node"].got


@pytest.mark.parametrize("cid, needle", [("unit-mm-as-m", "did you mean 300 mm"),
                                         ("unit-gpa-as-pa", "did you mean 53 GPa"),
                                         ("unit-section-mm-as-m", "did you mean 20 mm"),
                                         ("unit-bare-number", "without a unit")])
def test_unit_slips(checks, cid, needle):
    assert needle in checks[cid].got


def test_a_wrong_answer_fails_the_judge(scene, monkeypatch):
    """The judge above can fail: with two elements per cantilever the first frequency misses
    the closed form by more than 1e-6, and the product's own verdict says FAIL too."""
    monkeypatch.setattr(st, "ELEMENTS", 2)
    check = st.repeated(scene)
    f = check.details["sparse_Hz"][0]
    section = next(iter(scene.sections.values()))
    assert abs(f / cantilever_frequency(section, check.details["length"]) - 1) > 1e-6
    assert not check.passed


def test_penalty_switch_is_logged_and_exact(scene, caplog):
    from flexlink.fe.model import build_model
    from flexlink.fe.rigid import rigid_threshold, rigidified
    topo = scene.topology(8)
    model = build_model(dataclasses.replace(topo, joints=tuple(
        dataclasses.replace(j, Kt=1e30) for j in topo.joints)), scene.rigid_pose().joints)
    with caplog.at_level("WARNING", logger="flexlink.fe.rigid"):
        stiff = rigidified(model)
    assert "treated as rigid" in caplog.text
    translational = model.springs.dof_a % 3 != 2
    assert all(map(lambda k: k == float("inf"), stiff.springs.stiffness[translational]))
    assert (rigid_threshold(model)[translational] < 1e30).all()


def test_verify_command(tmp_path, monkeypatch):
    """The command's output and exit code (the checks are judged above)."""
    monkeypatch.setattr(st, "FAST", (st.repeated, st.units))
    result = CliRunner().invoke(main, ["verify", str(CASE1), "--json", "--out", str(tmp_path)])
    doc = json.loads(result.stdout)
    assert result.exit_code == 0 and doc["passed"] == doc["total"] == 5
    assert [c["id"] for c in doc["checks"]] == [
        "repeated-eigenvalues", "unit-mm-as-m", "unit-gpa-as-pa", "unit-section-mm-as-m",
        "unit-bare-number"]
    written = json.loads((tmp_path / "case1" / "verify.json").read_text())
    assert written["checks"] == doc["checks"] and written["command"] == "verify"
    monkeypatch.setattr(st, "ELEMENTS", 2)  # makes the repeated-eigenvalue check fail
    result = CliRunner().invoke(main, ["verify", str(CASE1), "--out", str(tmp_path)])
    assert result.exit_code == 1 and "[FAIL] repeated-eigenvalues:" in result.stdout


def test_the_old_command_name_still_runs_the_checks_and_says_it_is_renamed(tmp_path, monkeypatch):
    """``flexlink stability`` is kept for one release as the old name of ``verify``: the same
    document on stdout, and a note on stderr naming the new command and ``stability-map``."""
    monkeypatch.setattr(st, "FAST", (st.units,))
    old = CliRunner().invoke(main, ["stability", str(CASE1), "--json", "--out", str(tmp_path)])
    new = CliRunner().invoke(main, ["verify", str(CASE1), "--json", "--out", str(tmp_path)])
    assert old.exit_code == new.exit_code == 0
    verdicts = [[(c["id"], c["passed"], c["got"]) for c in json.loads(run.stdout)["checks"]]
                for run in (old, new)]
    assert verdicts[0] == verdicts[1] and verdicts[0]
    assert "`flexlink verify`" in old.stderr and "stability-map" in old.stderr
    assert "stability" not in new.stderr
