"""Dimensional synthesis of crank-rockers: link proportions from design targets.

Both return a ``kinematics.FourBar``; its own methods (transmission limits, rocker swing,
toggle angles) check the targets, which is what the tests do.

Mini-max transmission angle (FACTS.md): mu stays in 90 +- delta, with mu_min + mu_max = 180 deg
(R3^2 + R4^2 - R2^2 = 1); theta4i is the rocker angle at mu_min (crank along the ground line).

Brodell and Soni: unit time ratio (the two toggle positions 180 deg of crank apart) and the
best transmission angle for a rocker swing Theta:
    (a3/a1)^2 = (1 - cos Theta) / (2 cos^2 gamma_min)
    (a4/a1)^2 = (1 - (a3/a1)^2) / (1 - (a3/a1)^2 cos^2 gamma_min)
    (a2/a1)^2 = (a3/a1)^2 + (a4/a1)^2 - 1          (a2 crank, a3 coupler, a4 rocker)

Extended-rocker design (unit time ratio by construction): for swing Theta and rocker L4, the
crank pivot lies on the chord through the rocker's two extreme pin positions, so
    L2 = L4 sin(Theta/2),  L3 = c L2,  L1 = sqrt(L3^2 + (L4 cos(Theta/2))^2);
the built rocker is then k L4 (k = 1 keeps the design; k != 1 moves the pin along the rocker).
Scaled as the extended-rocker paper scales its family instead (``extended_rocker_tip``): the
extended arm L41 (to the tip that carries the load) and the swing stay fixed, and k = L41/L4
sets the rocker L4 = L41/k, every other link following from it by the design above. All links
then scale by one factor, so the angular motion (swing, time ratio, K, L, and so omega and
alpha at a crank speed) is the same for every k, and so is the tip's stroke L41 Theta.
"""

from __future__ import annotations

import math

from flexlink.errors import InputError
from flexlink.kinematics.fourbar import FourBar


def minimax(theta4i: float, delta: float, ground: float = 1.0) -> FourBar:
    """Mini-max crank-rocker from the rocker angle ``theta4i`` [rad] at mu_min and the band
    half-width ``delta`` [rad] (mu = 90 deg +- delta); ``ground`` L1 [m]."""
    if not 0 < delta < math.pi / 2:
        raise InputError(f"delta = {math.degrees(delta):g} deg outside (0, 90) deg", field="delta")
    mu_min = math.pi / 2 - delta
    M = math.sin(theta4i) / math.sin(mu_min)
    N = math.sin(theta4i - mu_min) / math.sin(mu_min)
    s = M * M + N * N
    if s <= 1.0:
        raise InputError(f"theta4i = {math.degrees(theta4i):g} deg and delta = "
                         f"{math.degrees(delta):g} deg give M^2 + N^2 = {s:.4g} <= 1: "
                         "no crank-rocker",
                         field="theta4i")
    R2 = s / (s - 1) - math.sqrt(2 * s - 1) / (s - 1)
    return FourBar.from_ratios(R2, M * (1 - R2), N * (1 - R2), ground=ground)


def brodell_soni(gamma_min: float, swing: float, ground: float = 1.0) -> FourBar:
    """Unit-time-ratio crank-rocker with minimum transmission angle ``gamma_min`` [rad] and
    rocker swing ``swing`` [rad]; ``ground`` a1 [m]."""
    if not 0 < gamma_min < math.pi / 2 or not 0 < swing < math.pi:
        raise InputError("need 0 < gamma_min < 90 deg and 0 < swing < 180 deg",
                         field="gamma_min/swing")
    c2 = math.cos(gamma_min) ** 2
    r3sq = (1 - math.cos(swing)) / (2 * c2)
    r4sq = (1 - r3sq) / (1 - r3sq * c2)
    r2sq = r3sq + r4sq - 1
    if not (0 < r3sq < 1 and r2sq > 0):
        raise InputError(f"gamma_min = {math.degrees(gamma_min):g} deg with swing "
                         f"{math.degrees(swing):g} deg has no crank-rocker", field="gamma_min")
    return FourBar.from_ratios(math.sqrt(r2sq), math.sqrt(r3sq), math.sqrt(r4sq), ground=ground)


def extended_rocker(rocker: float, swing: float, coupler_ratio: float, k: float = 1.0) -> FourBar:
    """Crank-rocker designed for unit time ratio with rocker ``rocker`` L4 [m], swing [rad],
    coupler L3 = ``coupler_ratio`` L2, built with rocker k L4 (see the module docstring)."""
    if not coupler_ratio > 1 or not k > 0:
        raise InputError("need coupler_ratio > 1 and k > 0", field="coupler_ratio/k")
    crank = rocker * math.sin(swing / 2)
    coupler = coupler_ratio * crank
    ground = math.hypot(coupler, rocker * math.cos(swing / 2))
    return FourBar(ground=ground, crank=crank, coupler=coupler, rocker=k * rocker)


def extended_rocker_tip(tip: float, swing: float, coupler_ratio: float, k: float) -> FourBar:
    """The extended-rocker design for tip arm ``tip`` L41 [m] and rocker ratio k = L41/L4
    (see the module docstring): rocker L4 = L41/k, crank, coupler and ground from it."""
    if not tip > 0 or not k > 0:
        raise InputError("need tip > 0 and k > 0", field="tip/k")
    return extended_rocker(tip / k, swing, coupler_ratio, 1.0)
