"""Rigid kinematics of the planar four-bar in closed form.

Frame: ground pivot O2 at the origin, O4 at (L1, 0). theta2 is the crank angle from the line
O2->O4, counter-clockwise. A is the crank pin, B the coupler-rocker pin. Lengths in metres,
angles in radians.

Transmission angle mu: the interior angle between coupler and rocker at B,
    cos mu = (L4^2 + L3^2 - L2^2 - L1^2 + 2 L1 L2 cos theta2) / (2 L3 L4),
which depends on theta2 only (both assembly branches share it).

Assembly branch: with d = the diagonal from O4 to A, B lies on the circle of radius L4 about
O4 at angle psi3 from d. "open" turns d clockwise by psi3 (for a crank above the ground line,
B is above it too, as drawn in the paper's Fig. 3); "crossed" turns it counter-clockwise.
"""

from __future__ import annotations

import dataclasses
import enum
import math

import numpy as np

from flexlink.choices import parse_choice
from flexlink.errors import InputError, KinematicsError


class Branch(enum.StrEnum):
    """The assembly branch: which side of the diagonal O4-A the pin B lies on."""

    OPEN = "open"
    CROSSED = "crossed"


class GrashofClass(enum.StrEnum):
    """What a four-bar's links can do, from its shortest (s), longest (l) and other two (p,
    q) lengths: Grashof (s + l < p + q) by which link is shortest, change-point (s + l = p +
    q), or non-Grashof (s + l > p + q, a triple rocker)."""

    CRANK_ROCKER = "crank-rocker"
    DOUBLE_CRANK = "double-crank"
    DOUBLE_ROCKER = "double-rocker"
    CHANGE_POINT = "change-point"
    NON_GRASHOF = "non-Grashof"

CLOSE_TOL = 1e-12  # relative: a toggle closing within this is round-off, not a gap in the loop


@dataclasses.dataclass(frozen=True)
class FourBarPose:
    """A four-bar's rigid pose in closed form: joint coordinates [m] and link angles [rad]."""

    theta2: float
    theta3: float
    theta4: float
    mu: float
    branch: Branch
    joints: dict[str, tuple[float, float]]


@dataclasses.dataclass(frozen=True)
class FourBar:
    """Four-bar linkage by its lengths [m]: ground L1, crank L2, coupler L3, rocker L4."""

    ground: float
    crank: float
    coupler: float
    rocker: float

    def __post_init__(self):
        for name in ("ground", "crank", "coupler", "rocker"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                raise InputError(f"link length must be a positive finite number, got {value!r}",
                                 field=name, expected="length > 0 m")
        lengths = sorted(self.lengths)
        if lengths[3] >= lengths[0] + lengths[1] + lengths[2]:
            raise KinematicsError(
                f"the four-bar cannot close: the longest link ({lengths[3]:g} m) is not shorter "
                f"than the sum of the other three ({sum(lengths[:3]):g} m)")

    @classmethod
    def from_ratios(cls, R2: float, R3: float, R4: float, ground: float) -> FourBar:
        """Table II style: R2 = L2/L1, R3 = L3/L1, R4 = L4/L1, with L1 = ``ground`` [m]."""
        return cls(ground=ground, crank=R2 * ground, coupler=R3 * ground, rocker=R4 * ground)

    @property
    def lengths(self) -> tuple[float, float, float, float]:
        return (self.ground, self.crank, self.coupler, self.rocker)

    @property
    def ratios(self) -> tuple[float, float, float]:
        return (self.crank / self.ground, self.coupler / self.ground, self.rocker / self.ground)

    # -- classification ----------------------------------------------------------------------
    def grashof_class(self) -> GrashofClass:
        """The linkage's class; a Grashof one by its shortest link: the ground (double-crank),
        the crank (crank-rocker), the coupler or the rocker (double-rocker)."""
        lengths = self.lengths
        s, l = min(lengths), max(lengths)
        pq = sum(lengths) - s - l
        if math.isclose(s + l, pq, rel_tol=1e-12):
            return GrashofClass.CHANGE_POINT
        if s + l > pq:
            return GrashofClass.NON_GRASHOF
        return (GrashofClass.DOUBLE_CRANK, GrashofClass.CRANK_ROCKER, GrashofClass.DOUBLE_ROCKER,
                GrashofClass.DOUBLE_ROCKER)[lengths.index(s)]

    def crank_turns_fully(self) -> bool:
        """Grashof's criterion with its equality: the crank turns a full revolution when
        s + l <= p + q and the shortest link is the crank or the ground. A change-point linkage
        (s + l = p + q) turns fully too, passing flat poses where every link lies on the ground
        line and the assembly branch can change."""
        lengths = self.lengths
        s, l = min(lengths), max(lengths)
        grashof = (self.grashof_class() is GrashofClass.CHANGE_POINT
                   or s + l < sum(lengths) - s - l)
        return grashof and min(self.ground, self.crank) == s

    def flat_poses(self) -> tuple[float, ...]:
        """Crank angles [rad] in [0, 2 pi) of a change-point linkage's flat poses, where all
        four joints lie on the ground line (crank along it at 0 or 180 deg and the loop
        closing there); none for other linkages."""
        if self.grashof_class() is not GrashofClass.CHANGE_POINT:
            return ()
        return tuple(t for t in (0.0, math.pi) if self._closes_flat(t))

    def dead_centres(self) -> tuple[float, ...]:
        """Crank angles [rad] in [0, 2 pi) where coupler and rocker are collinear (mu = 0 or
        180 deg): from cos mu = +-1 in the closed form of ``cos_mu``. None for a crank-rocker
        or a double-crank, whose transmission angle stays clear of both."""
        L1, L2, L3, L4 = self.lengths
        out = set()
        for c in (1.0, -1.0):
            cos_t = (2 * L3 * L4 * c - L4**2 - L3**2 + L2**2 + L1**2) / (2 * L1 * L2)
            if abs(cos_t) <= 1.0 + CLOSE_TOL:
                t = math.acos(min(1.0, max(-1.0, cos_t)))
                out |= {t, (2 * math.pi - t) % (2 * math.pi)}
        return tuple(sorted(out))

    def _closes_flat(self, theta2: float) -> bool:
        L1, L2, L3, L4 = self.lengths
        diag = abs(L1 - L2) if theta2 == 0.0 else L1 + L2
        return any(math.isclose(diag, d, rel_tol=1e-12) for d in (L3 + L4, abs(L3 - L4)))

    # -- transmission angle ------------------------------------------------------------------
    def cos_mu(self, theta2):
        L1, L2, L3, L4 = self.lengths
        return (L4**2 + L3**2 - L2**2 - L1**2 + 2 * L1 * L2 * np.cos(theta2)) / (2 * L3 * L4)

    def transmission_angle(self, theta2):
        """mu(theta2) [rad]; NaN where the linkage cannot close at that crank angle."""
        c = np.asarray(self.cos_mu(theta2), dtype=float)
        with np.errstate(invalid="ignore"):
            return np.where(np.abs(c) <= 1.0, np.arccos(np.clip(c, -1.0, 1.0)), np.nan)

    def transmission_limits(self) -> tuple[float, float]:
        """(mu_min, mu_max) [rad] for a crank that turns fully: at theta2 = 0 and 180 deg."""
        self._require_full_crank("mu_min and mu_max")
        return float(self.transmission_angle(0.0)), float(self.transmission_angle(math.pi))

    def crank_angles_for_mu(self, mu: float) -> tuple[float, float]:
        """The two crank angles in [0, 2 pi) where the transmission angle equals ``mu`` [rad].

        They are mirror images (theta2 and 2 pi - theta2)."""
        L1, L2, L3, L4 = self.lengths
        c = (2 * L3 * L4 * math.cos(mu) - L4**2 - L3**2 + L2**2 + L1**2) / (2 * L1 * L2)
        if abs(c) > 1.0:
            lo, hi = np.degrees(self._reachable_mu_range())
            raise KinematicsError(
                f"transmission angle {math.degrees(mu):.3f} deg is not reachable: over the crank "
                f"cycle mu stays within [{lo:.3f}, {hi:.3f}] deg")
        t = math.acos(c)
        return (t, 2 * math.pi - t)

    def _reachable_mu_range(self) -> tuple[float, float]:
        theta = np.linspace(0.0, math.pi, 2001)
        mu = self.transmission_angle(theta)
        return float(np.nanmin(mu)), float(np.nanmax(mu))

    def _require_full_crank(self, what: str):
        if not self.crank_turns_fully():
            raise KinematicsError(
                f"{what} need a crank that turns fully; this linkage is {self.grashof_class()} "
                f"(lengths {self.lengths} m)")

    # -- positions ---------------------------------------------------------------------------
    def pose(self, theta2: float, branch: Branch | str = Branch.OPEN) -> FourBarPose:
        """Joint positions at crank angle ``theta2`` [rad] on the chosen assembly ``branch``
        (a ``Branch`` or its text).

        Raises KinematicsError where the loop cannot close: the diagonal O4-A longer than
        coupler + rocker or shorter than |coupler - rocker| by more than ``CLOSE_TOL``
        (relative). A toggle that closes within it (a dead centre, mu = 0 or 180 deg; a
        change-point linkage's flat pose) is a pose like any other: both branches meet there,
        and the callers warn about it (``scene.plausibility.pose_warnings``).
        """
        branch = parse_choice(Branch, branch, "branch")
        L1, L2, L3, L4 = self.lengths
        A = np.array([L2 * math.cos(theta2), L2 * math.sin(theta2)])
        O4 = np.array([L1, 0.0])
        d = A - O4
        diag = math.hypot(*d)
        if diag == 0.0:
            raise KinematicsError(
                f"at theta2 = {math.degrees(theta2):.4f} deg the crank pin A lies on the ground "
                "pivot O4: the rocker's angle is not determined there")
        longest, shortest = L3 + L4, abs(L3 - L4)
        for bound, too, what in ((longest, diag - longest, "longer than coupler + rocker"),
                                 (shortest, shortest - diag, "shorter than |coupler - rocker|")):
            if too > CLOSE_TOL * max(longest, L1 + L2):
                raise KinematicsError(
                    f"the loop cannot close at theta2 = {math.degrees(theta2):.4f} deg: the "
                    f"diagonal O4-A is {diag:.9g} m, {what} ({bound:.9g} m) by more than the "
                    f"round-off tolerance ({CLOSE_TOL:g} relative)")
        cos_psi3 = (L4**2 + diag**2 - L3**2) / (2 * L4 * diag)
        mu = float(np.arccos(np.clip(self.cos_mu(theta2), -1.0, 1.0)))
        psi3 = math.acos(min(1.0, max(-1.0, cos_psi3)))
        sign = -1.0 if branch is Branch.OPEN else 1.0
        theta4 = math.atan2(d[1], d[0]) + sign * psi3
        B = O4 + L4 * np.array([math.cos(theta4), math.sin(theta4)])
        theta3 = math.atan2(*(B - A)[::-1])
        joints = {"O2": (0.0, 0.0), "A": (float(A[0]), float(A[1])), "B": (float(B[0]), float(B[1])),
                  "O4": (float(L1), 0.0)}
        return FourBarPose(theta2=float(theta2), theta3=theta3, theta4=theta4, mu=mu, branch=branch,
                    joints=joints)

    def pose_at_mu(self, mu: float, branch: Branch | str = Branch.OPEN,
                   which: int = 0) -> FourBarPose:
        """Pose where the transmission angle is ``mu`` [rad]; ``which`` 0 takes the crank angle
        in [0, 180] deg, 1 its mirror in [180, 360] deg."""
        return self.pose(self.crank_angles_for_mu(mu)[which], branch)

    def rocker_swing(self) -> float:
        """Rocker swing angle [rad] of a crank-rocker, between its two toggle (extreme)
        positions where crank and coupler are collinear."""
        if self.grashof_class() is not GrashofClass.CRANK_ROCKER:
            raise KinematicsError(f"rocker swing is defined for a crank-rocker; this linkage is "
                                  f"{self.grashof_class()}")
        L1, L2, L3, L4 = self.lengths

        def angle_at_O4(diag):
            return math.acos((L1**2 + L4**2 - diag**2) / (2 * L1 * L4))

        return angle_at_O4(L3 + L2) - angle_at_O4(L3 - L2)
