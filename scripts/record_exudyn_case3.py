"""Record an independent time-domain answer for the steady response of the running linkage:
Table II case 3 (cases/case3.toml) integrated in time by Exudyn, for
tests/studies/test_time_domain_record.py.

Needs the ``timedomain`` extra (Exudyn, from PyPI); this script installs nothing:
    pip install -e '.[timedomain]'
    PYTHONPATH=. python scripts/record_exudyn_case3.py            # writes the record
    PYTHONPATH=. python scripts/record_exudyn_case3.py --checks   # the sanity checks only
About 4 minutes of CPU on one core for the record (the convergence runs included).

Only the inputs come from flexlink: the scene's geometry at its pose, the links' sections
(rule of mixtures), the bearing stiffness Kt, the drive. The mechanics is Exudyn's own:
- every link is a chain of ``ObjectANCFCable2D`` elements (planar Euler-Bernoulli ANCF cable,
  geometrically exact, no rotary inertia, as flexlink's Euler-Bernoulli links), start joint
  to end joint, with its own nodes at the joints;
- a joint of finite Kt is a Cartesian spring (stiffness Kt in x and y) from each attached link
  end to the first attached link end, or to the ground for a ground bearing; a rigid one
  (Kt = inf) is an ``ObjectJointRevolute2D``; Kr = 0 (the scene's) leaves the pins free to turn;
- the drive holds the direction of the crank's slope at O2 on the prescribed crank angle
  theta(t) (one constraint, -sin(theta) r'_x + cos(theta) r'_y = 0, which leaves the axial
  stretch free): at rest at the scene's pose, the speed ramped smoothly from 0 to Omega over
  RAMP_SECONDS (d theta/dt = Omega (tau - sin(2 pi tau) / (2 pi)), tau = t / RAMP_SECONDS, so
  the angular acceleration and its rate start and end at zero), then held for HOLD_SECONDS; at
  SLOW_SPEED (Rayleigh damping only), the quasi-static limit of the faster runs, over
  SLOW_RAMP_SECONDS and SLOW_HOLD_SECONDS (each ramp a whole number of turns);
- one more run at CONVERGENCE_RPM (Rayleigh) with the rigid motion's d'Alembert loads scaled by
  LOAD_SCALE: nodal loads carry the rest of each node's rigid acceleration (lumped masses; the
  joints' rigid paths from the scene's poses, differentiated by their Fourier series). A
  linear model's answer scales with the loads (its inertia preload with them); what does not
  is the time domain's geometric nonlinearity;
- generalized-alpha (Exudyn's implicit index-3 solver), spectral radius SPECTRAL_RADIUS,
  STEPS_PER_SAMPLE steps per recorded sample, so the last turn's SAMPLES samples fall on steps
  at flexlink's own crank angles (the scene's pose angle + 2 pi k / SAMPLES);
- the bending strain at each link's midspan on the fibre y = +depth/2 of the link frame (x from
  the start joint to the end joint): eps = -depth/2 * kappa, kappa Exudyn's CurvatureLocal, the
  mean of the two elements meeting at the midspan node.

Damping, on the rate of deformation only (strain rate of the cables, relative velocity of the
joint springs), never on the rigid motion:
- "rayleigh": C = beta K with the scene key [damping] rayleigh_beta = RAYLEIGH_BETA: cable
  bendingDamping beta EI and axialDamping beta EA, joint dampers beta Kt;
- "constant ratio", flexlink's ``--damping-ratio ZETA`` (the same ratio for every basis
  vector) as closely as strain-rate damping can hold it: each link's own stiffness-proportional
  beta (bending and axial), fitted so that the first mode of each link (the lowest mode whose
  bending strain energy lies mostly in it) has the ratio ZETA exactly, the joint dampers at the
  beta that gives mode 1 the ratio ZETA. Higher modes of a link get more (the ratios reached,
  from the complex eigenvalues of Exudyn's linearised model at the pose, are in the record).

Before the runs, closed-form checks of the element (pinned-pinned first frequency, cantilever
tip deflection and curvature), the linkage's frequencies at the pose (elastic and rigid pins)
for the test to hold against flexlink's ``modes``, and a convergence check in elements and
step (at the faster speed, where the coupler runs close to its first mode).
"""

from __future__ import annotations

import argparse
import datetime
import json
import math
import subprocess
import sys
import time
from importlib.metadata import version
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import exudyn as exu  # noqa: E402
from exudyn.itemInterface import (  # noqa: E402
    LoadForceVector, MarkerBodyPosition, MarkerNodeCoordinates, MarkerNodePosition,
    NodePoint2DSlope1, NodePointGround, ObjectANCFCable2D, ObjectConnectorCartesianSpringDamper,
    ObjectConnectorCoordinateVector, ObjectGround, ObjectJointRevolute2D, SensorBody)

from flexlink.scene import load_scene  # noqa: E402

SCENE = "cases/case3.toml"
OUT = ROOT / "tests" / "data" / "exudyn_case3.json"
SPEEDS = (600.0, 1200.0)  # rev/min, with both damping laws
SLOW_SPEED = 60.0  # rev/min, Rayleigh only: the quasi-static limit the faster runs are
# compared with (strain times (speed / SLOW_SPEED)^2 where the response is quasi-static)
ZETA = 0.02  # the constant ratio compared (flexlink --damping-ratio 0.02)
RAYLEIGH_BETA = 1.1423e-4  # s: zeta 0.02 at flexlink's mode 1 (55.73 Hz)
ELEMENTS = 32  # per link (the convergence check below)
STEPS_PER_SAMPLE = 4  # time steps per recorded sample: 720 a turn
SAMPLES = 180  # per turn, as flexlink's response (2 deg)
SPECTRAL_RADIUS = 0.8  # generalized-alpha's rho_inf: damps the stiff axial and bearing modes
RAMP_SECONDS = 0.6  # a whole number of turns at both SPEEDS (3 and 6)
HOLD_SECONDS = 1.0  # mode 1 (zeta 0.02 at 350 rad/s) decays by e^-7 meanwhile
SLOW_RAMP_SECONDS = 2.0  # one whole turn at SLOW_SPEED
SLOW_HOLD_SECONDS = 3.0  # three turns: mode 1 decays by e^-21, the last two turns compared
LOAD_SCALE = 0.25  # a run at CONVERGENCE_RPM (Rayleigh) with the rigid motion's loads scaled
# by it: the linear answer scales with the loads, the geometric nonlinearity does not
KINEMATIC_HARMONICS = 40  # of the joints' rigid paths over the turn (theirs fall below 1e-12)
NEWTON_ABS_TOL = 1e-6  # N: a force residual that moves the coupler's midspan by ~1e-9 m
CONVERGENCE_RPM = 1200.0
CONVERGENCE_MESHES = (8, 16, 32)  # at STEPS_PER_SAMPLE
CONVERGENCE_STEPS = (2, 4, 8)  # steps per sample, at 16 elements
RPM = 2.0 * math.pi / 60.0


# -- the model ---------------------------------------------------------------------------------

def cable_chain(mbs, start, end, elements, section, beta):
    """ANCF cable elements from ``start`` to ``end`` [m]; strain-rate damping beta [s] times
    EI and EA. Returns (nodes, objects)."""
    start, end = np.asarray(start, float), np.asarray(end, float)
    length = float(np.hypot(*(end - start)))
    direction = (end - start) / length
    nodes = [mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[
        *(start + direction * length * i / elements), *direction])) for i in range(elements + 1)]
    objects = [mbs.AddObject(ObjectANCFCable2D(
        length=length / elements, massPerLength=section.mass_per_length,
        bendingStiffness=section.EI, axialStiffness=section.EA, bendingDamping=beta * section.EI,
        axialDamping=beta * section.EA, nodeNumbers=[nodes[i], nodes[i + 1]]))
        for i in range(elements)]
    return nodes, objects


class Linkage:
    """The scene's linkage in Exudyn at crank ``theta0`` [rad] (its rigid pose), at rest.

    ``link_beta``: link name -> strain-rate damping beta [s]; ``spring_beta`` [s]: the joint
    dampers' c = spring_beta Kt; ``angle(t)``: the prescribed crank angle [rad] (None: held at
    theta0)."""

    def __init__(self, scene, theta0, elements, link_beta, spring_beta, angle=None):
        topology = scene.topology()
        points = scene.rigid_state(theta0).points
        self.system = exu.SystemContainer()
        self.mbs = mbs = self.system.AddSystem()
        ground = mbs.AddObject(ObjectGround())
        self.links = {}  # name -> (objects, length, depth, nodes)
        ends = {}
        for link in topology.links:
            nodes, objects = cable_chain(mbs, points[link.start], points[link.end], elements,
                                         link.section, link_beta[link.name])
            length = float(np.hypot(*np.subtract(points[link.end], points[link.start])))
            self.links[link.name] = (objects, length, link.section.depth, nodes)
            ends.setdefault(link.start, []).append(nodes[0])
            ends.setdefault(link.end, []).append(nodes[-1])
        for joint in topology.joints:
            if joint.Kr != 0.0:
                raise ValueError(f"joint {joint.name}: Kr = {joint.Kr} N*m/rad; this model "
                                 "has free pins only (Kr = 0)")
            attached = ends[joint.name]
            for node in attached if joint.ground else attached[1:]:
                here = mbs.AddMarker(MarkerNodePosition(nodeNumber=node))
                if joint.ground:
                    x, y = points[joint.name]
                    there = mbs.AddMarker(MarkerBodyPosition(bodyNumber=ground,
                                                             localPosition=[x, y, 0.0]))
                else:
                    there = mbs.AddMarker(MarkerNodePosition(nodeNumber=attached[0]))
                if math.isinf(joint.Kt):
                    mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[there, here]))
                else:
                    mbs.AddObject(ObjectConnectorCartesianSpringDamper(
                        markerNumbers=[there, here], stiffness=[joint.Kt, joint.Kt, 0.0],
                        damping=[spring_beta * joint.Kt] * 2 + [0.0]))
        drive = topology.drive
        if drive is None or not math.isinf(drive.stiffness):
            raise ValueError("this model drives the crank rigidly; the scene's drive is "
                             f"{drive}")
        spec = next(link for link in topology.links if link.name == drive.link)
        nodes = self.links[drive.link][3]
        root = nodes[0] if spec.start == drive.joint else nodes[-1]
        angle = angle or (lambda t: theta0)

        def constraint(mbs, t, item, q, q_t, velocity_level):  # q: total coordinates
            a = angle(t)
            return [-math.sin(a) * q[2] + math.cos(a) * q[3]]

        def jacobian(mbs, t, item, q, q_t, velocity_level):
            a = angle(t)
            J = np.zeros((1, len(q)))
            J[0, 2], J[0, 3] = -math.sin(a), math.cos(a)
            return J

        slope = mbs.AddMarker(MarkerNodeCoordinates(nodeNumber=root))
        fixed = mbs.AddMarker(MarkerNodeCoordinates(nodeNumber=mbs.AddNode(NodePointGround())))
        mbs.AddObject(ObjectConnectorCoordinateVector(
            markerNumbers=[slope, fixed], scalingMarker0=np.zeros((1, 4)),
            constraintUserFunction=constraint, jacobianUserFunction=jacobian))

    def midspan_sensors(self):
        """link -> the CurvatureLocal sensors of the two elements meeting at its midspan."""
        sensors = {}
        for name, (objects, length, _, _) in self.links.items():
            n = len(objects)
            if n % 2:
                raise ValueError("an even element count puts a node at each midspan")
            sensors[name] = [self.mbs.AddSensor(SensorBody(
                bodyNumber=objects[e], localPosition=[x, 0.0, 0.0], storeInternal=True,
                outputVariableType=exu.OutputVariableType.CurvatureLocal))
                for e, x in ((n // 2 - 1, length / n), (n // 2, 0.0))]
        return sensors

    def bending_energy(self, displacement):
        """link -> EI/2 * integral of kappa^2 [J] for nodal ``displacement`` (ODE2 coordinates
        of the assembled system) about the straight reference, kappa = n . u'' by the cables'
        cubic Hermite functions (n the link's normal), integrated by 2-point Gauss (exact for
        the linear kappa of an element)."""
        gauss = 0.5 + np.array([-1.0, 1.0]) / (2.0 * math.sqrt(3.0))
        energy = {}
        for name, (objects, length, _, nodes) in self.links.items():
            h = length / len(objects)
            ref = self.mbs.GetNodeParameter(nodes[0], "referenceCoordinates")
            normal = np.array([-ref[3], ref[2]])
            u = np.array([displacement[self.mbs.GetNodeODE2Index(k) + np.arange(4)]
                          for k in nodes])  # (nodes, [x, y, x', y'])
            w = u[:, :2] @ normal, u[:, 2:] @ normal  # transverse and its slope
            kappa = [(-6 + 12 * g) / h**2 * w[0][:-1] + (-4 + 6 * g) / h * w[1][:-1]
                     + (6 - 12 * g) / h**2 * w[0][1:] + (-2 + 6 * g) / h * w[1][1:]
                     for g in gauss]
            EI = self.mbs.GetObjectParameter(objects[0], "bendingStiffness")
            energy[name] = float(EI / 2 * h / 2 * sum(np.abs(k) ** 2 for k in kappa).sum())
        return energy


def linear_modes(linkage, count):
    """Frequencies [Hz], damping ratios [-] and the link holding most of the bending strain
    energy, of the ``count`` lowest modes of ``linkage`` linearised at rest (its constraints
    eliminated by Exudyn's null space of their Jacobian)."""
    mbs = linkage.mbs
    mbs.Assemble()
    M, K, D, _, N = mbs.ComputeLinearizedSystem(returnConstraintNullspace=True)
    if len(N) == 0:  # no constraint
        N = np.eye(M.shape[0])
    m, k, d = (N @ A @ N.T for A in (M, K, D))
    n = m.shape[0]
    first_order = np.block([[np.zeros((n, n)), np.eye(n)],
                            [-np.linalg.solve(m, k), -np.linalg.solve(m, d)]])
    lam, vectors = np.linalg.eig(first_order)
    keep = lam.imag > 0
    order = np.argsort(np.abs(lam[keep]))[:count]
    lam, shapes = lam[keep][order], N.T @ vectors[:n, keep][:, order]
    owners = []
    for shape in shapes.T:
        energy = linkage.bending_energy(shape)
        owners.append(max(energy, key=energy.get))
    return np.abs(lam) / (2 * math.pi), -lam.real / np.abs(lam), owners


# -- the damping laws --------------------------------------------------------------------------

def rayleigh_law(scene):
    """C = RAYLEIGH_BETA K: every link's and joint's beta [s]."""
    return {link.name: RAYLEIGH_BETA for link in scene.topology().links}, RAYLEIGH_BETA


def constant_ratio_law(scene, theta0, elements, iterations=20, tolerance=1e-4):
    """Per-link betas [s] giving each link's first mode the ratio ZETA, and the joint
    dampers' beta (ZETA at mode 1 as if all were stiffness-proportional), by fixed-point
    iteration on the ratios of the linearised model (each link's first mode, the lowest whose
    bending energy lies mostly in it, answers mainly to its own link's beta), until every
    first mode's ratio is within ``tolerance`` of ZETA, relative."""
    names = [link.name for link in scene.topology().links]
    f, _, _ = linear_modes(Linkage(scene, theta0, elements, dict.fromkeys(names, 0.0), 0.0), 1)
    spring_beta = 2.0 * ZETA / (2.0 * math.pi * f[0])
    betas = dict.fromkeys(names, spring_beta)
    for _ in range(iterations):
        f, zeta, owners = linear_modes(Linkage(scene, theta0, elements, betas, spring_beta),
                                       2 * len(names))
        first = {name: owners.index(name) for name in names}
        error = max(abs(zeta[i] / ZETA - 1.0) for i in first.values())
        if error < tolerance:
            return betas, spring_beta
        betas = {name: betas[name] * ZETA / zeta[i] for name, i in first.items()}
    raise RuntimeError(f"the per-link betas did not reach zeta {ZETA} (relative error {error})")


# -- one run -----------------------------------------------------------------------------------

def crank_angle(theta0, speed, ramp=RAMP_SECONDS):
    """theta(t) [rad]: at rest at theta0, d theta/dt = speed (tau - sin(2 pi tau) / (2 pi)) over
    the ramp (tau = t / ``ramp`` [s]), then ``speed`` [rad/s] held."""

    def angle(t):
        if t >= ramp:
            return theta0 + speed * ramp / 2.0 + speed * (t - ramp)
        tau = t / ramp
        return theta0 + speed * ramp * (tau**2 / 2.0 + (math.cos(2 * math.pi * tau) - 1.0)
                                        / (4.0 * math.pi**2))
    return angle


def crank_rates(theta0, speed, ramp=RAMP_SECONDS):
    """t -> (theta, d theta/dt, d2 theta/dt2) [rad, rad/s, rad/s^2] of ``crank_angle``."""
    angle = crank_angle(theta0, speed, ramp)

    def rates(t):
        if t >= ramp:
            return angle(t), speed, 0.0
        tau = t / ramp
        return (angle(t), speed * (tau - math.sin(2 * math.pi * tau) / (2 * math.pi)),
                speed / ramp * (1.0 - math.cos(2 * math.pi * tau)))
    return rates


def joint_paths(scene, theta0):
    """theta -> (first, second) derivatives in theta of the joints' rigid positions [m/rad,
    m/rad^2], as complex x + iy per joint (topology order), by the Fourier series of the
    scene's rigid poses at the SAMPLES crank angles of a turn."""
    names = [joint.name for joint in scene.topology().joints]
    grid = theta0 + 2.0 * np.pi * np.arange(4 * SAMPLES) / (4 * SAMPLES)
    positions = np.array([[complex(*scene.rigid_state(a).points[name]) for name in names]
                          for a in grid])
    k = np.fft.fftfreq(len(grid), 1.0 / len(grid))
    keep = np.abs(k) <= KINEMATIC_HARMONICS
    c, k = (np.fft.fft(positions, axis=0) / len(grid))[keep], k[keep]

    def derivatives(theta):
        e = c * np.exp(1j * k * (theta - theta0))[:, None]
        return (e * (1j * k)[:, None]).sum(axis=0), (e * -(k**2)[:, None]).sum(axis=0)
    return derivatives


def add_counter_loads(linkage, scene, theta0, rates, scale):
    """Nodal loads (1 - ``scale``) m a [N] that carry that share of each node's rigid-motion
    acceleration a (lumped mass m of its element halves; the rigid acceleration is linear
    along a link between its joints'), so the links' elastic response answers to ``scale``
    times the rigid motion's d'Alembert loads. ``rates``: ``crank_rates``."""
    derivatives = joint_paths(scene, theta0)
    index = {joint.name: i for i, joint in enumerate(scene.topology().joints)}
    latest = {}

    def joint_accelerations(t):
        if t not in latest:
            latest.clear()
            theta, rate, acceleration = rates(t)
            first, second = derivatives(theta)
            latest[t] = second * rate**2 + first * acceleration
        return latest[t]

    for link in scene.topology().links:
        _, length, _, nodes = linkage.links[link.name]
        elements = len(nodes) - 1
        share = (1.0 - scale) * link.section.mass_per_length * length / elements
        for i, node in enumerate(nodes):
            mass = share * (0.5 if i in (0, elements) else 1.0)

            def load(mbs, t, vector, x=i / elements, mass=mass, a=index[link.start],
                     b=index[link.end]):
                acc = joint_accelerations(t)
                here = acc[a] + x * (acc[b] - acc[a])
                return [mass * here.real, mass * here.imag, 0.0]
            linkage.mbs.AddLoad(LoadForceVector(
                markerNumber=linkage.mbs.AddMarker(MarkerNodePosition(nodeNumber=node)),
                loadVector=[0.0, 0.0, 0.0], loadVectorUserFunction=load))


def steady_turn(scene, theta0, rpm, elements, steps_per_sample, law, ramp=RAMP_SECONDS,
                hold=HOLD_SECONDS, load_scale=1.0):
    """The last turn's midspan strain [-] per link at SAMPLES crank angles theta0 + 2 pi k /
    SAMPLES, its change from the turn before (relative to its peak), and the CPU time [s];
    the speed ramped over ``ramp`` [s] (a whole number of turns), then held for about
    ``hold`` [s] (whole turns); the rigid motion's loads scaled by ``load_scale``
    (``add_counter_loads``)."""
    speed = rpm * RPM
    turn = 2.0 * math.pi / speed
    turns = round((ramp / 2.0 + hold) / turn)  # whole turns, ramp included
    ramp_turns = ramp * speed / (4.0 * math.pi)
    if abs(ramp_turns - round(ramp_turns)) > 1e-9:
        raise ValueError(f"the ramp ends between samples at {rpm} rev/min")
    if turns - ramp_turns < 2:
        raise ValueError(f"the hold at {rpm} rev/min has fewer than the two turns compared")
    steps_per_turn = SAMPLES * steps_per_sample
    steps = round((ramp / turn + turns - ramp_turns) * steps_per_turn)
    betas, spring_beta = law
    linkage = Linkage(scene, theta0, elements, betas, spring_beta,
                      crank_angle(theta0, speed, ramp))
    if load_scale != 1.0:
        add_counter_loads(linkage, scene, theta0, crank_rates(theta0, speed, ramp), load_scale)
    sensors = linkage.midspan_sensors()
    mbs = linkage.mbs
    mbs.Assemble()
    settings = exu.SimulationSettings()
    settings.timeIntegration.numberOfSteps = steps
    settings.timeIntegration.endTime = steps * turn / steps_per_turn
    settings.timeIntegration.verboseMode = 0
    settings.timeIntegration.generalizedAlpha.spectralRadius = SPECTRAL_RADIUS
    settings.timeIntegration.newton.absoluteTolerance = NEWTON_ABS_TOL
    settings.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = 0.0  # every step
    cpu = time.process_time()
    mbs.SolveDynamic(settings)
    cpu = time.process_time() - cpu
    strain, change = {}, {}
    for name, pair in sensors.items():
        kappa = np.mean([mbs.GetSensorStoredData(s)[:, 1] for s in pair], axis=0)
        if len(kappa) != steps + 1:
            raise RuntimeError(f"{len(kappa)} sensor rows for {steps} steps")
        eps = -linkage.links[name][2] / 2.0 * kappa
        last = eps[steps - steps_per_turn:steps:steps_per_sample]
        before = eps[steps - 2 * steps_per_turn:steps - steps_per_turn:steps_per_sample]
        strain[name] = last
        change[name] = float(np.abs(last - before).max() / np.abs(last).max())
    return {"strain": strain, "turn_to_turn_change": change, "cpu_s": cpu,
            "turns": turns + ramp_turns, "time_step_s": turn / steps_per_turn,
            "ramp_turns": ramp_turns, "ramp_s": ramp, "hold_s": hold}


# -- sanity checks against closed forms --------------------------------------------------------

def closed_form_checks(section, length=0.27, elements=ELEMENTS):
    """A straight beam of ``section`` and ``length`` [m] (the coupler's): the pinned-pinned
    first frequency against (pi / L)^2 sqrt(EI / rho A) / (2 pi), and the clamped-free tip
    deflection and midspan curvature under a small tip load P against P L^3 / (3 EI) and
    P L / (2 EI) (the cubic deflection that cubic elements hold exactly)."""
    out = {}
    system = exu.SystemContainer()
    mbs = system.AddSystem()
    nodes, _ = cable_chain(mbs, (0.0, 0.0), (length, 0.0), elements, section, 0.0)
    mbs.Assemble()
    fixed = [mbs.GetNodeODE2Index(nodes[0]) + i for i in (0, 1)] \
        + [mbs.GetNodeODE2Index(nodes[-1]) + 1]
    f = mbs.ComputeODE2Eigenvalues(constrainedCoordinates=fixed, convert2Frequencies=True,
                                   autoAssemble=False)[0]
    exact = (math.pi / length) ** 2 * math.sqrt(section.EI / section.mass_per_length) \
        / (2 * math.pi)
    out["pinned_pinned_first_Hz"] = {"exudyn": float(f[0]), "closed_form": exact,
                                     "relative_difference": float(f[0] / exact - 1)}

    system = exu.SystemContainer()
    mbs = system.AddSystem()
    nodes, objects = cable_chain(mbs, (0.0, 0.0), (length, 0.0), elements, section, 0.0)
    _clamp(mbs, nodes[0])
    tip_deflection = length / 1e4  # small: the geometric nonlinearity stays near 1e-8, while
    # the load (1.2 mN) is 1e4 times the residual left
    load = tip_deflection * 3 * section.EI / length**3
    mbs.AddLoad(LoadForceVector(markerNumber=mbs.AddMarker(MarkerNodePosition(
        nodeNumber=nodes[-1])), loadVector=[0.0, load, 0.0]))
    n = len(objects)
    pair = [mbs.AddSensor(SensorBody(bodyNumber=objects[e], localPosition=[x, 0.0, 0.0],
                                     storeInternal=True,
                                     outputVariableType=exu.OutputVariableType.CurvatureLocal))
            for e, x in ((n // 2 - 1, length / n), (n // 2, 0.0))]
    mbs.Assemble()
    settings = exu.SimulationSettings()
    settings.solution.file.write = False
    settings.staticSolver.verboseMode = 0
    # the round-off floor of the residual is ~5e-8 N here (EA / element length ~2e8 N/m)
    settings.staticSolver.newton.absoluteTolerance = 1e-7
    mbs.SolveStatic(settings)
    tip = mbs.GetNodeOutput(nodes[-1], exu.OutputVariableType.Displacement)[1]
    kappa = float(np.mean([mbs.GetSensorValues(s) for s in pair]))
    exact_kappa = load * length / 2 / section.EI
    out["cantilever_tip_deflection_m"] = {"exudyn": float(tip), "closed_form": tip_deflection,
                                          "relative_difference": float(tip / tip_deflection - 1)}
    out["cantilever_midspan_curvature_per_m"] = {
        "exudyn": kappa, "closed_form": exact_kappa,
        "relative_difference": kappa / exact_kappa - 1,
        "sign": "positive for a load towards +y on a beam along +x: eps(+depth/2) < 0"}
    out["elements"] = elements
    out["length_m"] = length
    return out


def _clamp(mbs, node):
    """Fix a cable node's position and slope direction (x, y and the slope's y) to ground."""
    from exudyn.itemInterface import MarkerNodeCoordinate, ObjectConnectorCoordinate

    anchor = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()),
                                                coordinate=0))
    for i in (0, 1, 3):
        mbs.AddObject(ObjectConnectorCoordinate(markerNumbers=[
            anchor, mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node, coordinate=i))]))


def linkage_frequencies(scene, theta0, elements, count=6):
    """The lowest frequencies [Hz] of the undamped linkage at its pose, and which link holds
    most of each mode's bending strain energy."""
    names = [link.name for link in scene.topology().links]
    f, _, owners = linear_modes(Linkage(scene, theta0, elements, dict.fromkeys(names, 0.0),
                                        0.0), count)
    return {"frequencies_Hz": [float(v) for v in f], "bending_energy_mostly_in": owners}


# -- the record --------------------------------------------------------------------------------

def convergence(scene, theta0, law, finest):
    """The midspan curves at CONVERGENCE_RPM over meshes and steps: the largest difference
    from the finest of each series, relative to the finest's peak, per link."""
    def spread(runs, best):
        ref = runs[best]["strain"]
        return {str(key): {name: float(np.abs(r["strain"][name] - ref[name]).max()
                                        / np.abs(ref[name]).max()) for name in ref}
                for key, r in runs.items() if key != best}

    meshes = {e: finest if e == ELEMENTS else
              steady_turn(scene, theta0, CONVERGENCE_RPM, e, STEPS_PER_SAMPLE, law)
              for e in CONVERGENCE_MESHES}
    steps = {m: meshes[16] if m == STEPS_PER_SAMPLE else
             steady_turn(scene, theta0, CONVERGENCE_RPM, 16, m, law)
             for m in CONVERGENCE_STEPS}
    return {
        "speed_rev_min": CONVERGENCE_RPM,
        "damping": "constant ratio",
        "elements_per_link": {
            "steps_per_sample": STEPS_PER_SAMPLE,
            "difference_from_finest": spread(meshes, max(CONVERGENCE_MESHES)),
            "peak_microstrain": {str(e): {k: float(np.abs(v).max() * 1e6)
                                          for k, v in r["strain"].items()}
                                 for e, r in meshes.items()}},
        "steps_per_sample": {
            "elements_per_link": 16,
            "difference_from_finest": spread(steps, max(CONVERGENCE_STEPS)),
            "cpu_s": {str(m): r["cpu_s"] for m, r in steps.items()}},
    }


def record(checks_only=False):
    scene = load_scene(ROOT / SCENE)
    theta0 = scene.rigid_state(None).q
    section = scene.topology().links[1].section  # all three links share it in case 3
    checks = closed_form_checks(section)
    print(json.dumps(checks, indent=2))
    frequencies = {
        "elastic_pins": linkage_frequencies(scene, theta0, ELEMENTS),
        "rigid_pins": linkage_frequencies(load_scene(ROOT / SCENE, {"joints.Kt": "rigid"}),
                                          theta0, ELEMENTS)}
    print(json.dumps(frequencies, indent=2))
    if checks_only:
        return
    laws = {"constant ratio": constant_ratio_law(scene, theta0, ELEMENTS),
            "rayleigh": rayleigh_law(scene)}
    damping = {}
    for name, (betas, spring_beta) in laws.items():
        f, zeta, owners = linear_modes(Linkage(scene, theta0, ELEMENTS, betas, spring_beta), 6)
        damping[name] = {"link_beta_s": betas, "joint_damper_beta_s": spring_beta,
                         "modes_Hz": [float(v) for v in f],
                         "damping_ratios": [float(v) for v in zeta],
                         "bending_energy_mostly_in": owners}
        print(name, json.dumps(damping[name]))
    runs = []
    finest = None
    schedule = [(rpm, name, RAMP_SECONDS, HOLD_SECONDS, 1.0) for rpm in SPEEDS for name in laws]
    schedule.append((SLOW_SPEED, "rayleigh", SLOW_RAMP_SECONDS, SLOW_HOLD_SECONDS, 1.0))
    schedule.append((CONVERGENCE_RPM, "rayleigh", RAMP_SECONDS, HOLD_SECONDS, LOAD_SCALE))
    for rpm, name, ramp, hold, scale in schedule:
        law = laws[name]
        run = steady_turn(scene, theta0, rpm, ELEMENTS, STEPS_PER_SAMPLE, law, ramp, hold,
                          scale)
        if rpm == CONVERGENCE_RPM and name == "constant ratio":
            finest = run
        runs.append({"speed_rev_min": rpm, "damping": name, "load_scale": scale,
                     "strain_microstrain": {k: [float(x * 1e6) for x in v]
                                            for k, v in run["strain"].items()},
                     **{k: run[k] for k in ("turn_to_turn_change", "cpu_s", "turns",
                                            "ramp_turns", "ramp_s", "hold_s",
                                            "time_step_s")}})
        print(f"{rpm:g} rev/min, {name}, loads x {scale:g}: peaks "
              + ", ".join(f"{k} {np.abs(v).max() * 1e6:.3f}" for k, v in
                          run["strain"].items())
              + f" microstrain; {run['cpu_s']:.1f} s CPU", flush=True)
    study = convergence(scene, theta0, laws["constant ratio"], finest)
    print(json.dumps(study, indent=2))
    commit = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True,
                            text=True).stdout.strip()
    document = {
        "what": "the steady bending strain [microstrain] at each link's midspan (fibre y = "
                "+depth/2 of the link frame, x from start to end joint) over the last crank "
                "turn, integrated in time by Exudyn from rest: ANCF cable links, bearings as "
                "springs, the crank angle prescribed (ramped, then held), generalized-alpha",
        "scene": SCENE,
        "exudyn": version("exudyn"),
        "date": datetime.date.today().isoformat(),
        "flexlink_commit": commit,
        "command": "PYTHONPATH=. python scripts/record_exudyn_case3.py",
        "model": {
            "element": "ObjectANCFCable2D (planar Euler-Bernoulli ANCF cable, geometrically "
                       "exact), default Gauss orders",
            "elements_per_link": ELEMENTS,
            "links": {name: {"length_m": length, "depth_m": depth}
                      for name, (_, length, depth, _) in
                      Linkage(scene, theta0, 2, rayleigh_law(scene)[0], 0.0).links.items()},
            "joints": "Kt as Cartesian spring-dampers (each link end to the first attached "
                      "one, or to ground); Kr = 0: free pins",
            "drive": "the crank's slope direction at O2 held on theta(t) by one constraint "
                     "(its axial stretch free)",
            "strain": "-depth/2 * CurvatureLocal, the mean of the two elements at the "
                      "midspan node",
            "not_modelled": "gravity (flexlink has none either); shear and rotary inertia "
                            "(flexlink's Euler-Bernoulli links have none)"},
        "integration": {
            "method": "generalized-alpha, index 3 (Exudyn's implicit second-order solver)",
            "spectral_radius": SPECTRAL_RADIUS,
            "steps_per_turn": SAMPLES * STEPS_PER_SAMPLE,
            "newton_absolute_tolerance_N": NEWTON_ABS_TOL,
            "ramp": "d theta/dt = Omega (tau - sin(2 pi tau) / (2 pi)), tau = t / ramp_s",
            "ramp_s": RAMP_SECONDS, "hold_s": HOLD_SECONDS,
            "slow_speed": "each run's own ramp_s and hold_s"},
        "samples": {"count": SAMPLES, "first_crank_angle_rad": theta0,
                    "step_rad": 2 * math.pi / SAMPLES},
        "closed_form_checks": checks,
        "linkage_frequencies_at_pose": frequencies,
        "damping": {
            "constant ratio": {
                "meaning": f"flexlink --damping-ratio {ZETA}",
                "law": f"stiffness-proportional per link (strain rate), each link's beta "
                       f"fitted so its first mode has zeta {ZETA}; joint dampers beta Kt with "
                       f"the beta giving mode 1 zeta {ZETA}",
                **damping["constant ratio"]},
            "rayleigh": {"meaning": f"[damping] rayleigh_beta = {RAYLEIGH_BETA}",
                         "law": "C = beta K: cable bendingDamping beta EI, axialDamping beta "
                                "EA, joint dampers beta Kt", **damping["rayleigh"]}},
        "convergence": study,
        "runs": runs,
    }
    OUT.write_text(json.dumps(document, indent=1) + "\n")
    print(f"wrote {OUT}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--checks", action="store_true", help="the sanity checks only")
    record(parser.parse_args().checks)


if __name__ == "__main__":
    main()
