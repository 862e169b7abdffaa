"""Rigid kinematics of any planar linkage of revolute joints with one input, described as data.

Unknowns: the (x, y) [m] of every moving joint. Constraints (the loop-closure equations written
joint by joint; every closed loop of bodies is closed when every body keeps its shape):
  - a body's first two joints keep their distance:  |p1 - p0|^2 - l01^2 = 0;
  - any further joint k of a body sits at its local place (a_k, b_k) in the frame of p0 -> p1:
        p_k - p0 - (a_k (p1 - p0) + b_k perp(p1 - p0)) / l01 = 0      (linear, 2 equations),
    which also fixes the side of p0p1 the joint lies on, so a rigid triangle cannot flip;
  - the driving body (its first joint a ground pivot) has its second joint at the input angle q:
        p1 - p0 - l01 (cos q, sin q) = 0.
The system is square for a one-degree-of-freedom linkage. Positions by Newton-Raphson from a
guess; along a cycle, each pose starts from the previous one advanced by the velocity and
acceleration coefficients (a second-order predictor), so the assembly branch is kept.

Velocity coefficients: J x' = -dPhi/dq, and J x'' = -gamma, gamma the quadratic terms of the
second derivative. A body's angle theta (direction p0 -> p1) then has
    K = dtheta/dq = (d x d') / |d|^2,  L = dK/dq = (d x d'') / |d|^2 - 2 (d . d')(d x d') / |d|^4,
with d = p1 - p0, so that omega = K qdot and alpha = K qddot + L qdot^2.
A singular J (relative smallest singular value below ``SINGULAR_TOL``) is a dead centre.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence

import numpy as np

from flexlink.errors import InputError, KinematicsError

SINGULAR_TOL = 1e-9  # sigma_min / sigma_max of the scaled Jacobian below this: a dead centre
# ... and below this, a pose whose velocity coefficients are not determined: a pose solved to
# NEWTON_TOL sits within round-off of a dead centre (a change-point linkage's flat pose comes
# out at 1e-7, its poses a degree away at 3e-3), where K and L take one of the branches' values
NEAR_SINGULAR = 1e-6
NEWTON_TOL = 1e-13  # residual relative to the linkage size [-]
NEWTON_STEPS = 30


@dataclasses.dataclass(frozen=True)
class Body:
    """A rigid body carrying ``joints``; ``shape`` holds each joint's local (x, y) [m] in the
    body frame whose origin is joints[0] and whose x axis points to joints[1]. The body angle
    is the direction joints[0] -> joints[1]."""

    name: str
    joints: tuple[str, ...]
    shape: tuple[tuple[float, float], ...]

    def __post_init__(self):
        if len(self.joints) < 2 or len(self.joints) != len(self.shape):
            raise InputError(f"body {self.name!r} needs >= 2 joints, each with a local position",
                             field=f"bodies.{self.name}")
        if len(set(self.joints)) != len(self.joints):
            raise InputError(f"body {self.name!r} names a joint twice", field=f"bodies.{self.name}")
        if self.shape[0] != (0.0, 0.0) or self.shape[1][1] != 0.0 or not self.shape[1][0] > 0:
            raise InputError(f"body {self.name!r}: first joint at the origin, second on +x",
                             field=f"bodies.{self.name}")

    @classmethod
    def bar(cls, name: str, start: str, end: str, length: float) -> Body:
        return cls(name, (start, end), ((0.0, 0.0), (float(length), 0.0)))

    @classmethod
    def polar(cls, name: str, joints: Sequence[str], arms: Sequence[float],
              angles: Sequence[float]) -> Body:
        """Joint k >= 1 at distance arms[k-1] [m] from joints[0], at angles[k-1] [rad]
        (counter-clockwise) from the arm to joints[1]."""
        if len(arms) != len(joints) - 1 or len(angles) != len(arms) or angles[0] != 0.0:
            raise InputError(f"body {name!r}: one arm and one angle per joint after the first, "
                             "the first angle 0", field=f"bodies.{name}")
        shape = [(0.0, 0.0)] + [(r * math.cos(a), r * math.sin(a)) for r, a in zip(arms, angles)]
        shape[1] = (float(arms[0]), 0.0)
        return cls(name, tuple(joints), tuple(shape))

    @property
    def length(self) -> float:
        """Distance joints[0] -> joints[1] [m]."""
        return self.shape[1][0]


@dataclasses.dataclass(frozen=True)
class State:
    """One pose: q [rad]; points [m] by joint; per body (in ``Linkage.bodies`` order) angle
    [rad], K [-] and L [-]; ``xdot``/``xddot``: dp/dq and d2p/dq2 [m] by joint."""

    q: float
    points: dict[str, tuple[float, float]]
    angles: np.ndarray
    K: np.ndarray
    L: np.ndarray
    dpoints: dict[str, np.ndarray]
    ddpoints: dict[str, np.ndarray]


@dataclasses.dataclass(frozen=True)
class Cycle:
    """States along a sweep of q; arrays indexed [pose, body]; angles unwrapped [rad]."""

    q: np.ndarray
    angles: np.ndarray
    K: np.ndarray
    L: np.ndarray
    states: tuple[State, ...]
    body_names: tuple[str, ...]

    def column(self, body: str) -> int:
        return self.body_names.index(body)


@dataclasses.dataclass(frozen=True)
class Linkage:
    """Ground pivots (name -> (x, y) [m]), rigid bodies, and the driving body (whose first
    joint must be a ground pivot). One degree of freedom: the input angle q of ``driver``."""

    ground: Mapping[str, tuple[float, float]]
    bodies: tuple[Body, ...]
    driver: str

    def __post_init__(self):
        names = [b.name for b in self.bodies]
        if self.driver not in names:
            raise InputError(f"driver {self.driver!r} is not a body", field="linkage.driver",
                             expected=f"one of {names}")
        if self.body(self.driver).joints[0] not in self.ground:
            raise InputError(f"driver {self.driver!r} must turn about a ground pivot (its first "
                             "joint)", field="linkage.driver")
        n_eq = sum(1 + 2 * (len(b.joints) - 2) for b in self.bodies) + 1
        if n_eq != 2 * len(self.moving):
            raise InputError(f"{n_eq} loop equations for {2 * len(self.moving)} unknown "
                             "coordinates: the linkage must have exactly one degree of freedom",
                             field="bodies")

    def body(self, name: str) -> Body:
        return next(b for b in self.bodies if b.name == name)

    @property
    def moving(self) -> tuple[str, ...]:
        seen = []
        for b in self.bodies:
            seen += [j for j in b.joints if j not in self.ground and j not in seen]
        return tuple(seen)

    @property
    def size(self) -> float:
        return max(b.length for b in self.bodies)

    # -- the equations -------------------------------------------------------------------------
    def _unpack(self, x):
        pts = {name: np.asarray(p, float) for name, p in self.ground.items()}
        for i, name in enumerate(self.moving):
            pts[name] = x[2 * i:2 * i + 2]
        return pts

    def _per_joint(self, rates):
        """A rate of the moving joints' coordinates (x', x'') as one 2-vector per joint, zero at
        the ground joints."""
        per_joint = {name: np.zeros(2) for name in self.ground}
        for i, name in enumerate(self.moving):
            per_joint[name] = rates[2 * i:2 * i + 2]
        return per_joint

    def _equations(self, x, q):
        """Residual Phi, Jacobian dPhi/dx, dPhi/dq, and a function giving the quadratic terms
        gamma(x') of the second derivative."""
        pts = self._unpack(x)
        index = {name: 2 * i for i, name in enumerate(self.moving)}
        n = len(x)
        rows, jac, phi_q = [], [], []

        def row(entries, value, dq=0.0):
            r = np.zeros(n)
            for joint, coeff in entries:  # coeff: (2,) gradient w.r.t. the joint's (x, y)
                if joint in index:
                    r[index[joint]:index[joint] + 2] += coeff
            jac.append(r)
            rows.append(value)
            phi_q.append(dq)

        quadratic = []  # per equation: callable(dp) -> gamma
        for b in self.bodies:
            j0, j1 = b.joints[0], b.joints[1]
            d = pts[j1] - pts[j0]
            l01 = b.length
            if b.name == self.driver:
                c, s = math.cos(q), math.sin(q)
                for axis, (u, du) in enumerate(((c, -s), (s, c))):
                    e = np.eye(2)[axis]
                    row([(j1, e), (j0, -e)], d[axis] - l01 * u, -l01 * du)
                    quadratic.append(lambda dp, g=l01 * u: g)
            else:
                row([(j1, 2 * d), (j0, -2 * d)], d @ d - l01**2)
                quadratic.append(lambda dp, j0=j0, j1=j1: 2 * np.sum((dp[j1] - dp[j0])**2))
            perp = np.array([[0.0, -1.0], [1.0, 0.0]])
            for jk, (a, bb) in zip(b.joints[2:], b.shape[2:]):
                # p_k - p0 - (a d + bb perp d) / l01
                A = (a * np.eye(2) + bb * perp) / l01
                resid = pts[jk] - pts[j0] - A @ d
                for axis in range(2):
                    row([(jk, np.eye(2)[axis]), (j0, -np.eye(2)[axis] + A[axis]),
                         (j1, -A[axis])], resid[axis])
                    quadratic.append(lambda dp: 0.0)
        return np.array(rows), np.array(jac), np.array(phi_q), quadratic

    def conditioning(self, state: State) -> float:
        """sigma_min / sigma_max of the scaled loop Jacobian at ``state``: 0 at a dead centre,
        below NEAR_SINGULAR where the pose's velocity coefficients are not determined."""
        x = np.concatenate([np.asarray(state.points[j], float) for j in self.moving])
        s = np.linalg.svd(self._equations(x, state.q)[1] * self.size, compute_uv=False)
        return float(s[-1] / s[0])

    def _check_jacobian(self, J, q):
        s = np.linalg.svd(J * self.size, compute_uv=False)
        if s[-1] < SINGULAR_TOL * s[0]:
            raise KinematicsError(
                f"dead centre at q = {math.degrees(q):.4f} deg: the loop Jacobian is singular "
                f"(sigma_min/sigma_max = {s[-1] / s[0]:.2e}); the pose is not unique there")

    # -- solving -------------------------------------------------------------------------------
    def solve(self, q: float, guess: Mapping[str, Sequence[float]]) -> State:
        """The pose at input angle ``q`` [rad] nearest ``guess`` (joint -> (x, y) [m]), with its
        velocity and acceleration coefficients. KinematicsError if the loop cannot close or
        the pose is a dead centre."""
        missing = [j for j in self.moving if j not in guess]
        if missing:
            raise InputError(f"no initial guess for joint(s) {missing}", field="joints")
        x = np.concatenate([np.asarray(guess[j], float) for j in self.moving])
        scale = self.size
        for _ in range(NEWTON_STEPS):
            phi, J, _, _ = self._equations(x, q)
            if np.max(np.abs(phi)) < NEWTON_TOL * scale**2:
                break
            try:
                x = x - np.linalg.solve(J, phi)
            except np.linalg.LinAlgError:
                raise KinematicsError(f"the loop cannot close at q = {math.degrees(q):.4f} deg "
                                      "(singular Jacobian during Newton iteration)") from None
        else:
            raise KinematicsError(
                f"the loop cannot close at q = {math.degrees(q):.4f} deg: Newton-Raphson did not "
                f"converge (residual {np.max(np.abs(phi)):.3g} m^2); the link lengths cannot "
                "span the loop at this input angle")
        return self._state(x, q)

    def _state(self, x, q) -> State:
        _, J, phi_q, quadratic = self._equations(x, q)
        self._check_jacobian(J, q)
        xd = np.linalg.solve(J, -phi_q)
        dp = self._per_joint(xd)
        gamma = np.array([g(dp) for g in quadratic])
        ddp = self._per_joint(np.linalg.solve(J, -gamma))
        pts = self._unpack(x)
        angles, K, L = [], [], []
        for b in self.bodies:
            d = pts[b.joints[1]] - pts[b.joints[0]]
            d1 = dp[b.joints[1]] - dp[b.joints[0]]
            d2 = ddp[b.joints[1]] - ddp[b.joints[0]]
            dd = d @ d
            cross1 = d[0] * d1[1] - d[1] * d1[0]
            cross2 = d[0] * d2[1] - d[1] * d2[0]
            angles.append(math.atan2(d[1], d[0]))
            if b.name == self.driver:  # its angle is q itself: dq/dq = 1, d2q/dq2 = 0 exactly
                K.append(1.0)
                L.append(0.0)
                continue
            K.append(cross1 / dd)
            L.append(cross2 / dd - 2 * (d @ d1) * cross1 / dd**2)
        points = {k: (float(v[0]), float(v[1])) for k, v in pts.items()}
        return State(q=float(q), points=points, angles=np.array(angles), K=np.array(K),
                     L=np.array(L), dpoints=dp, ddpoints=ddp)

    def cycle(self, q: Sequence[float], guess: Mapping[str, Sequence[float]],
              progress=None) -> Cycle:
        """Poses at the input angles ``q`` [rad] in order, continued from ``guess`` at q[0]:
        each pose starts from the previous one advanced by x' dq + x'' dq^2 / 2."""
        q = np.asarray(q, float)
        states = []
        iterator = progress(q) if progress else q
        for qi in iterator:
            if states:
                prev = states[-1]
                h = qi - prev.q
                guess = {j: np.asarray(prev.points[j]) + prev.dpoints[j] * h
                         + 0.5 * prev.ddpoints[j] * h * h for j in self.moving}
            try:
                states.append(self.solve(qi, guess))
            except KinematicsError as exc:
                if not states:
                    raise
                reason = "a dead centre" if "dead centre" in str(exc) else "the loop does not close"
                raise KinematicsError(
                    f"the crank cannot turn fully: at q = {math.degrees(qi):.4f} deg, "
                    f"{reason} (the last pose reached is at q = "
                    f"{math.degrees(states[-1].q):.4f} deg)") from None
        angles = np.unwrap(np.array([s.angles for s in states]), axis=0)
        return Cycle(q=q, angles=angles, K=np.array([s.K for s in states]),
                     L=np.array([s.L for s in states]), states=tuple(states),
                     body_names=tuple(b.name for b in self.bodies))


def four_bar_linkage(ground: float, crank: float, coupler: float, rocker: float) -> Linkage:
    """The four-bar of ``kinematics.FourBar`` (O2 at the origin, O4 at (ground, 0); bodies
    crank O2->A, coupler A->B, rocker O4->B) as a general linkage."""
    return Linkage(ground={"O2": (0.0, 0.0), "O4": (float(ground), 0.0)},
                   bodies=(Body.bar("crank", "O2", "A", crank),
                           Body.bar("coupler", "A", "B", coupler),
                           Body.bar("rocker", "O4", "B", rocker)),
                   driver="crank")


def crank_angles(n: int, start: float = 0.0) -> np.ndarray:
    """``n`` input angles [rad] evenly over one revolution from ``start``, endpoint excluded."""
    if n < 3:
        raise InputError(f"need at least 3 poses per cycle, got {n}", field="poses")
    return start + 2 * math.pi * np.arange(n) / n


def crossings(q: np.ndarray, values: np.ndarray, level: float) -> np.ndarray:
    """Input angles [rad] where ``values`` (periodic over the cycle, sampled at ``q``) crosses
    ``level``, by linear interpolation between neighbouring samples."""
    v = values - level
    nxt = np.roll(v, -1)
    q_next = np.append(q[1:], q[0] + 2 * math.pi)
    hit = (v == 0) | (v * nxt < 0)
    i = np.flatnonzero(hit)
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.where(v[i] == 0, 0.0, v[i] / (v[i] - nxt[i]))
    return np.remainder(q[i] + t * (q_next[i] - q[i]), 2 * math.pi)
