"""Claims of the scene stage that the mutation runs found unguarded (notes/history.md, fourth
round): the messages' stated contents and the scene's conventions."""

import math
import types

import numpy as np
import pytest
from conftest import CASES_DIR, SCENES_DIR

from flexlink.errors import InputError
from flexlink.fe.model import Section
from flexlink.scene import load_scene
from flexlink.scene.plausibility import exact_timoshenko_drop, pose_warnings, timoshenko_drop
from flexlink.scene.source import read_scene_source


def _refusal(tmp_path, text: str) -> InputError:
    path = tmp_path / "scene.toml"
    path.write_text(text)
    with pytest.raises(InputError) as refusal:
        load_scene(path)
    return refusal.value


def test_a_key_of_another_synthesis_method_says_which_method_declares_it(tmp_path):
    """The tagged table here is two levels down ([linkage] type = "general", then
    [linkage.synthesis] method = ...): the key must be looked up among the synthesis methods,
    not among the linkage kinds."""
    text = (SCENES_DIR / "extended_rocker.toml").read_text()
    assert "k = 1.0\n" in text
    error = _refusal(tmp_path, text.replace("k = 1.0\n", 'k = 1.0\ntheta4i = "30 deg"\n', 1))
    assert error.field == "linkage.synthesis.theta4i"
    assert ("unknown key for method = 'extended-rocker': 'theta4i' belongs to "
            "method = 'minimax'") in str(error)


def test_a_table_the_scene_replaces_whole_takes_its_origin_from_the_scene(tmp_path):
    """A [material] table replaces the base's whole (source.merge), so none of the base's
    material keys is left, and the table's file, for messages, is the scene's own."""
    path = tmp_path / "steel.toml"
    path.write_text(f'base = "{(CASES_DIR / "case1.toml").as_posix()}"\n'
                    '[material]\nisotropic = "steel"\n')
    src = read_scene_source(path)
    material = {k: v for k, v in src.origin.items() if k.split(".")[0] == "material"}
    assert material == {"material.isotropic": str(path)}
    assert src.file_of("material") == str(path)
    assert src.file_of("linkage.R2") == str(CASES_DIR / "case1.toml")  # the rest keeps its file


@pytest.mark.parametrize("crank", [0.3, 2.0])
def test_a_crossed_four_bar_poses_on_its_own_branch(crank):
    """The two assembly branches of a four-bar share O2, A and O4; B of the crossed one is B
    of the open one mirrored in the line A O4 (both lie at the coupler's length from A and
    the rocker's from O4). The scene's branch, not a default, must pick it."""
    case1 = CASES_DIR / "case1.toml"
    open_ = load_scene(case1).rigid_pose(crank).joints
    crossed = load_scene(case1, overrides={"pose.branch": "crossed"}).rigid_pose(crank).joints
    a, o4, b = (np.array(open_[j]) for j in ("A", "O4", "B"))
    along = (o4 - a) / np.linalg.norm(o4 - a)
    mirrored = a + 2 * ((b - a) @ along) * along - (b - a)
    np.testing.assert_allclose(crossed["B"], mirrored, rtol=0, atol=1e-12)  # metres, round-off
    for joint in ("O2", "A", "O4"):
        np.testing.assert_allclose(crossed[joint], open_[joint], rtol=0, atol=1e-15)


def test_a_four_bar_takes_its_own_link_tables_but_not_their_ends_or_mesh(tmp_path):
    """A four-bar's [links.NAME] may give a link its own section, never its joints or
    elements (fixed by the kind; the mesh is [mesh] elements_per_link)."""
    base = f'base = "{(CASES_DIR / "case1.toml").as_posix()}"\n'
    path = tmp_path / "thicker.toml"
    path.write_text(base + '[links.coupler.section]\nthickness = "3 mm"\n')
    assert load_scene(path).sections["coupler"].depth == pytest.approx(3e-3, rel=1e-15)
    error = _refusal(tmp_path, base + "[links.coupler]\nelements = 4\n")
    assert error.field == "links.coupler.elements"
    assert "elements_per_link" in str(error)


def test_an_unknown_body_in_a_transmission_pair_names_the_pair(tmp_path):
    """The refusal of a [linkage] transmission pair naming no body says which pair (its
    index in the list) and which name, as every unknown-name refusal does."""
    text = (SCENES_DIR / "wiper.toml").read_text()
    pairs = 'transmission = [["link1", "rocker1"], ["link2", "rocker2"]]'
    assert pairs in text
    error = _refusal(tmp_path, text.replace(pairs, pairs.replace('"rocker2"', '"rocker9"')))
    assert error.field == "linkage.transmission[1]"
    assert error.source == str(tmp_path / "scene.toml")
    assert "unknown body 'rocker9'" in str(error)


@pytest.mark.parametrize("scene", [CASES_DIR / "case1.toml", SCENES_DIR / "wiper.toml"])
def test_every_kind_keeps_its_reference_frequencies(tmp_path, scene):
    """[reference] is part of the schema for every linkage kind: a general scene's published
    frequencies reach the scene (and so the reports' comparison) as a four-bar's do."""
    path = tmp_path / "referenced.toml"
    path.write_text(f'base = "{scene.as_posix()}"\n'
                    '[reference]\nsource = "a hammer test"\nEx_Hz = [12.5, 40.0]\n')
    reference = load_scene(path).reference
    assert reference.source == "a hammer test"
    assert reference.columns["Ex"] == (12.5, 40.0)  # exact: both are binary fractions


def test_a_drive_on_an_unknown_link_names_the_link_meant(tmp_path):
    """As every unknown name: the file, the key and the nearest name the scene has."""
    text = (SCENES_DIR / "wiper.toml").read_text()
    written = 'link = "crank"\njoint = "O1"'
    error = _refusal(tmp_path, text.replace(written, written.replace('"crank"', '"crnk"')))
    assert str(error) == (f"{tmp_path / 'scene.toml'}: drive.link: unknown link 'crnk'; "
                          "did you mean crank?")


@pytest.mark.parametrize(("drive", "expected"), [
    ('link = "crank"\njoint = "a"', "'O1'"),  # the crank's ground end
    ('link = "link1"\njoint = "a"', "a link with a ground end"),  # a coupler has none
])
def test_a_drive_off_the_ground_says_where_it_may_sit(tmp_path, drive, expected):
    """The drive holds a link's rotation at one of its ground joints: elsewhere the refusal
    names the joint and the link and offers that link's ground ends, or says none exist."""
    text = (SCENES_DIR / "wiper.toml").read_text()
    written = 'link = "crank"\njoint = "O1"'
    assert written in text
    error = _refusal(tmp_path, text.replace(written, drive))
    assert error.field == "drive.joint"
    assert error.source == str(tmp_path / "scene.toml")
    assert "'a' is not a ground joint of link" in str(error)
    assert error.expected == expected


NOTED = 'value = "20 mm", note = "assumed: a strip"'


@pytest.mark.parametrize(("noted", "field", "message", "expected"), [
    (NOTED + ', why = "x"', "section.width",
     "a noted value holds only ['note', 'range', 'reason', 'value'], not ['why']", None),
    (NOTED + ', range = ["12 mm"], reason = "x"', "section.width.range", "got ['12 mm']",
     "[low, high], each written like the value"),
    (NOTED + ', range = ["12 mm", "30 mm"]', "section.width.reason", "a range needs its reason",
     "a text saying why the range is plausible"),
    (NOTED + ', reason = "x"', "section.width.reason", "a reason without a range",
     "range = [low, high] with it"),
    ('value = "20 mm", note = 3', "section.width.note", "got 3", "a text"),
    ('value = "20 mm", note = "measured", range = ["12 mm", "30 mm"], reason = "x"',
     "section.width.range", "a range belongs to an assumed value", 'a note starting "assumed"'),
])
def test_a_malformed_noted_value_names_its_file_and_part(tmp_path, noted, field, message,
                                                         expected):
    """A noted value is { value, note[, range, reason] }: each way of breaking that form is
    refused naming the file, the part of the value at fault, and what would be accepted."""
    path = tmp_path / "scene.toml"
    path.write_text(f'base = "{(CASES_DIR / "case1.toml").as_posix()}"\n'
                    f'[section]\nwidth = {{ {noted} }}\n')
    with pytest.raises(InputError) as refusal:
        read_scene_source(path)
    error = refusal.value
    assert (error.source, error.field, error.expected) == (str(path), field, expected)
    assert str(error).startswith(f"{path}: {field}: {message}")


def test_a_noted_value_without_a_note_is_its_value(tmp_path):
    """The editor schema requires only `value` in a noted value (docs/scene.schema.json): the
    note may be left out, and the value then reads as if written plainly, with no assumption."""
    path = tmp_path / "scene.toml"
    path.write_text(f'base = "{(CASES_DIR / "case1.toml").as_posix()}"\n'
                    '[section]\nwidth = { value = "21 mm" }\n')
    src = read_scene_source(path)
    assert src.data["section"]["width"] == "21 mm"
    assert "section.width" not in {a.field for a in src.assumptions}


@pytest.mark.parametrize(("content", "message"), [
    (None, "file not found"),
    ("folder", "is a folder, not a scene file"),
    (b"\xff\xfe not text", "not UTF-8 text (byte 0, line 1): is this a scene file?"),
    ("[linkage\nR2 = 0.3\n", "not valid TOML: "),
])
def test_a_file_that_is_no_scene_says_why(tmp_path, content, message):
    """Before any key is read, the refusal says what is wrong with the file itself: missing,
    a folder, not UTF-8, or not TOML (then with the TOML parser's own words and place)."""
    path = tmp_path / "scene.toml"
    if content == "folder":
        path.mkdir()
    elif isinstance(content, bytes):
        path.write_bytes(content)
    elif content is not None:
        path.write_text(content)
    with pytest.raises(InputError) as refusal:
        read_scene_source(path)
    assert refusal.value.source == str(path)
    assert str(refusal.value).startswith(f"{path}: {message}")
    if message == "not valid TOML: ":
        assert "(at line 1, column 9)" in str(refusal.value)  # tomllib's place of the error


def test_an_implausible_value_is_refused_in_one_sentence_with_the_way_out(tmp_path):
    """A unit slip is refused with the range, what it covers, the likely meant value, the
    count of further findings and how to accept the value after all. Case 1's ratios make
    the coupler 240 m and the rocker 200 m as well (out of range), the crank 80 m (in)."""
    path = tmp_path / "scene.toml"
    path.write_text(f'base = "{(CASES_DIR / "case1.toml").as_posix()}"\n'
                    '[linkage]\nground = "300 m"\n')
    with pytest.raises(InputError) as refusal:
        load_scene(path)
    assert str(refusal.value) == (
        f"{path}: linkage.ground: 300 m is outside the plausible range [0.0001, 100] m (a link "
        "of a machine, 0.1 mm to 100 m); did you mean 300 mm? (and 2 more) (expected a value "
        'in the range, or [checks] plausibility = "warn")')


def test_a_scene_without_a_material_is_refused_naming_the_table(tmp_path):
    """No [material] and no link's own: the refusal names the file, the table and its forms."""
    text = (SCENES_DIR / "wiper.toml").read_text()
    table = text[text.index("[material]"):text.index("[links.crank]")]
    assert table.count("\n") == 4  # [material], E, density, blank line
    error = _refusal(tmp_path, text.replace(table, ""))
    assert (error.source, error.field) == (str(tmp_path / "scene.toml"), "material")
    assert str(error).startswith(f"{tmp_path / 'scene.toml'}: material: no material given")
    assert error.expected == "a [material] table: composite, isotropic = 'name', or E and density"


@pytest.mark.parametrize(("scene", "eta", "low", "high"), [
    (CASES_DIR / "case1.toml", 0.01, 0.002, 0.02),  # a woven composite
    (SCENES_DIR / "wiper.toml", 1e-3, 1e-4, 1e-2),  # E and density: taken as a metal
])
def test_an_unstated_loss_factor_is_the_documented_default_and_an_assumption(scene, eta, low,
                                                                             high):
    """docs/damping.md, "Defaults and sources": a [material.composite] defaults to eta = 0.01
    (range 2e-3 to 2e-2), a material given by E and density to 1e-3 (1e-4 to 1e-2); every
    link takes it, and the scene lists it as an assumption with that range."""
    loaded = load_scene(scene)
    assert set(loaded.loss_factors.values()) == {eta}
    noted = [a for a in loaded.assumptions if a.field == "material.loss_factor"]
    assert len(noted) == 1 and noted[0].value == f"{eta:g}"
    assert f"material loss factor {eta:g}, plausible {low:g} to {high:g}" in noted[0].note


CRANK_SECTION = ('section = { width = { value = "15 mm", note = "assumed: 15 mm in-plane depth '
                 'of the flat links; thickness follows from the link mass" }, bending = '
                 '"edgewise", mass = "0.0785 kg" }')


@pytest.mark.parametrize(("section", "field", "message", "expected"), [
    ('section = { width = "15 mm", bending = "edgewise" }', "links.crank.section.width",
     "a flat bar needs thickness, plies with ply_thickness, or mass", None),
    ('section = { width = "15 mm", thickness = "2 mm" }', "links.crank.section.bending",
     "missing", "bending = 'flatwise' (thickness in the plane of motion) or 'edgewise' (width "
     "in the plane) for a flat bar"),
    ("", "links.crank.section", "no section given", "width with thickness (or plies and "
     "ply_thickness, or mass), area with second_moment, or a tube"),
])
def test_an_incomplete_section_says_which_key_is_missing(tmp_path, section, field, message,
                                                         expected):
    """The section forms of the scene reference: a flat bar needs its thickness (or plies, or
    the link's mass) and its bending; a link with no section keys at all is told the forms."""
    text = (SCENES_DIR / "wiper.toml").read_text()
    assert CRANK_SECTION in text
    error = _refusal(tmp_path, text.replace(CRANK_SECTION, section))
    assert (error.source, error.field, error.expected) == (str(tmp_path / "scene.toml"), field,
                                                           expected)
    assert str(error).startswith(f"{tmp_path / 'scene.toml'}: {field}: {message}")


def test_a_section_given_by_area_and_second_moment_is_named_by_its_area(tmp_path):
    """Every section is labelled with its link, material and size for the messages that
    concern it; the A-and-I form by its area in m^2 (20 mm^2 = 2e-05 m^2)."""
    path = tmp_path / "scene.toml"
    text = (SCENES_DIR / "wiper.toml").read_text()
    path.write_text(text.replace(CRANK_SECTION, 'section = { area = "20 mm^2", '
                                                'second_moment = "100 mm^4" }'))
    assert load_scene(path).sections["crank"].name == "crank: material, A 2e-05 m^2"


def test_a_base_loop_is_refused_naming_the_file(tmp_path):
    """A scene that is its own base (or any loop) would merge forever: refused past the
    nesting limit, naming the file and its `base` key."""
    path = tmp_path / "scene.toml"
    path.write_text('base = "scene.toml"\nname = "loop"\n')
    with pytest.raises(InputError) as refusal:
        read_scene_source(path)
    assert (refusal.value.source, refusal.value.field) == (str(path), "base")
    assert str(refusal.value) == f"{path}: base: base files nest too deeply (a loop?)"


def test_a_welded_joint_of_a_four_bar_is_refused(tmp_path):
    """Welding joins links into one body: a general scene's option only (a four-bar's joints
    are its four pins)."""
    base = f'base = "{(CASES_DIR / "case1.toml").as_posix()}"\n'
    error = _refusal(tmp_path, base + "[joints.A]\nwelded = true\n")
    assert (error.source, error.field) == (str(tmp_path / "scene.toml"), "joints.A.welded")
    assert str(error).endswith(": welded joints are for general scenes")


@pytest.mark.parametrize("slenderness", [20.0, 50.0, 100.0])
def test_the_estimated_timoshenko_drop_is_exact_to_first_order(slenderness):
    """The estimate that picks the links to warn about, 1 - (1 + u)^-1/2 with
    u = (pi h / (sqrt(12) L))^2 (1 + E / (k G)), k = 5/6, is u/2 - 3u^2/8 + ...: its ratio to
    the leading term u/2 is within 3u/4 of 1, and it meets the exact drop of Timoshenko
    theory (fe.beams, checked against the elements in tests/fe) to second order."""
    steel = Section.rectangle(E=210e9, G=210e9 / 2.6, density=7850.0, width=0.01,
                              thickness=0.002, bending="edgewise")
    length = slenderness * steel.depth
    u = (math.pi * steel.depth / math.sqrt(12) / length) ** 2 * (1 + 2.6 / (5 / 6))
    estimate = timoshenko_drop(steel, length)
    assert abs(estimate / (u / 2) - 1) <= 0.75 * u
    assert abs(estimate - exact_timoshenko_drop(steel, length)) <= 0.5 * estimate**2


def test_a_pose_near_a_dead_centre_is_warned_of_in_one_sentence():
    """Within 10 deg of 0 or 180 deg a transmission angle gets the warning with its angle,
    its distance from the dead centre and why it matters; one 12 deg away gets none."""
    pose = types.SimpleNamespace(transmission={"coupler/rocker": math.radians(174.5),
                                               "link2/rocker2": math.radians(12.0)})
    assert pose_warnings(None, pose) == [
        "transmission angle coupler/rocker 174.500 deg is 5.5 deg from a dead centre (0 or "
        "180 deg): the pose and the joint loads are very sensitive there"]


def test_an_assumed_value_keeps_all_it_was_written_with(tmp_path):
    """An assumed noted value becomes an assumption holding the key, the value, the note,
    the file, and the range with its reason exactly as written (the sensitivity study
    samples the range and quotes the reason)."""
    path = tmp_path / "scene.toml"
    path.write_text(f'base = "{(CASES_DIR / "case1.toml").as_posix()}"\n[section]\n'
                    f'width = {{ {NOTED}, range = ["12 mm", "30 mm"], reason = "strips" }}\n')
    [width] = [a for a in read_scene_source(path).assumptions if a.field == "section.width"]
    assert (width.value, width.note, width.source) == ("20 mm", "assumed: a strip", str(path))
    assert (width.range, width.reason) == (("12 mm", "30 mm"), "strips")
