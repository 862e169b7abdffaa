"""The joint springs, the drive and the joint masses a scene declares reach the model with
their values: a link far stiffer than its springs moves as a rigid body on them, whose
frequency is known in closed form.

- Pendulum on the drive: one link O -> P turning about its ground bearing O (Kt rigid,
  Kr = 0) held by a drive of stiffness k, a joint mass m at the free end P:
      omega^2 = k / J_O,  J_O = rho A L^3 / 3 + m L^2 (+ rho I L for Timoshenko links).
- Mass on the bearing: the same link with its rotation held (Kr rigid) on a bearing of
  translational stiffness Kt: two translation modes (x and y) at
      omega^2 = Kt / (rho A L + m).
The link's own flexibility shifts these, to first order, by c x ratio where ratio = k L / EI
or Kt L^3 / EI (or Kt L / EA, whichever is larger); c was measured at most 0.16 over 60 drawn
links, and the test allows c = 1. The springs are drawn with ratio 1e-5 to 1e-4: softer
ones would put the spring mode below the solver's mechanism threshold (1e-6 of the link's
own bending eigenvalue scale, about ratio / 3 here), where it is rightly labelled a
mechanism. Relations (scaling, invariance) cannot see a value read wrong by a constant
factor; these can.
"""

import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from strategies import log_uniform, write_scene

from flexlink.analysis.modal import analyze
from flexlink.scene import load_scene


def single_link(length, angle, E, density, depth, across, beam, Kt, Kr, drive, tip_mass):
    """Scene text of one link O -> P, ground bearing O (Kt [N/m], Kr [N m/rad], "rigid" as
    text), a drive of stiffness ``drive`` at O (or none), a joint mass [kg] at P."""
    tip = (length * math.cos(angle), length * math.sin(angle))

    def stiff(value, unit):
        return f'"{value}"' if isinstance(value, str) else f'"{value!r} {unit}"'

    lines = [
        'name = "one link"', "[linkage]", 'type = "general"', 'driver = "arm"',
        f'start = "{angle!r} rad"', "[linkage.ground]", 'O = ["0 m", "0 m"]',
        "[linkage.bodies.arm]", 'joints = ["O", "P"]', f'length = "{length!r} m"',
        "[linkage.guess]", f'P = ["{tip[0]!r} m", "{tip[1]!r} m"]',
        "[material]", f'E = "{E!r} Pa"', f'density = "{density!r} kg/m^3"',
        "[links.arm]", 'start = "O"', 'end = "P"',
        f'section = {{ width = "{depth!r} m", thickness = "{across!r} m", bending = "edgewise" }}',
        "[joints.O]", f"Kt = {stiff(Kt, 'N/m')}", f"Kr = {stiff(Kr, 'N*m/rad')}",
        "[joints.P]", 'Kt = "rigid"', 'Kr = "rigid"', f'mass = "{tip_mass!r} kg"',
        "[mesh]", "elements_per_link = 4", "[model]", f'beam = "{beam}"']
    if drive is not None:
        lines += ["[drive]", 'link = "arm"', 'joint = "O"', f"stiffness = {stiff(drive, 'N*m/rad')}"]
    return "\n".join(lines) + "\n"


@st.composite
def links(draw):
    length = draw(log_uniform(0.05, 2.0))
    depth = length * draw(st.floats(0.01, 0.05))
    return {"length": length, "angle": draw(st.floats(-math.pi, math.pi)),
            "E": draw(log_uniform(1e9, 4e11)), "density": draw(st.floats(1000.0, 20000.0)),
            "depth": depth, "across": depth * draw(st.floats(0.2, 5.0)),
            "beam": draw(st.sampled_from(("euler-bernoulli", "timoshenko")))}


@given(links(), log_uniform(1e-5, 1e-4), st.floats(0.0, 2.0))
def test_a_stiff_link_on_its_drive_swings_at_the_pendulum_frequency(link, ratio, tip_ratio):
    A, I = link["depth"] * link["across"], link["across"] * link["depth"] ** 3 / 12
    rhoA = link["density"] * A
    L = link["length"]
    k = ratio * link["E"] * I / L
    tip_mass = tip_ratio * rhoA * L
    text = single_link(**link, Kt="rigid", Kr=0.0, drive=k, tip_mass=tip_mass)
    f = analyze(load_scene(write_scene(text)), 1).elastic_frequencies(1)[0]
    J = rhoA * L**3 / 3 + tip_mass * L**2
    if link["beam"] == "timoshenko":
        J += link["density"] * I * L
    assert math.isclose(f, math.sqrt(k / J) / (2 * math.pi), rel_tol=ratio)


@given(links(), log_uniform(1e-5, 1e-4), st.floats(0.0, 2.0))
def test_a_stiff_link_on_a_soft_bearing_translates_at_the_spring_mass_frequency(
        link, ratio, tip_ratio):
    A, I = link["depth"] * link["across"], link["across"] * link["depth"] ** 3 / 12
    rhoA = link["density"] * A
    L = link["length"]
    Kt = ratio * min(link["E"] * I / L**3, link["E"] * A / L)
    tip_mass = tip_ratio * rhoA * L
    text = single_link(**link, Kt=Kt, Kr="rigid", drive=None, tip_mass=tip_mass)
    f = analyze(load_scene(write_scene(text)), 2).elastic_frequencies(2)
    expected = math.sqrt(Kt / (rhoA * L + tip_mass)) / (2 * math.pi)
    np.testing.assert_allclose(f, expected, rtol=ratio)
