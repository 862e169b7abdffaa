"""A modal test against a scene's model: every sensor placed on a link, the model's modes read
at the test's channels by the element interpolation (``fe.sensors``), and the two mode sets
correlated by shape (``analysis.correlation``): MAC pairing, frequency errors of the pairs,
unpaired modes of both sides, CoMAC per channel, the test's autoMAC.

The model's modes are those of the scene's family (``analysis.families.part_modes``): in-plane
modes read zero on an out-of-plane (Z) channel and out-of-plane modes zero on an in-plane one,
so a test mode of the other part pairs with nothing, as it should.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.analysis.correlation import Correlation, correlate, pair_by_order
from flexlink.analysis.families import PartModes, paired, part_modes
from flexlink.analysis.identity import mode_identity
from flexlink.fe.motions import Part
from flexlink.fe.sensors import Placement, channel_operator, place_points
from flexlink.scene import Scene
from flexlink.studies.array_shapes import check_shape
from flexlink.studies.correlation.measured import ModalTest
from flexlink.units import UNITS

SPARE_MODES = 4  # model modes beyond the test's count, so a mode out of order can still pair


@dataclasses.dataclass(frozen=True)
class SensorsOnModel:
    """A test's sensors in the scene: ``points`` (P, 2) [m] in the scene's frame, their
    ``placement`` on the model's links, ``directions`` (C, 3) of the channels in the scene's
    frame, and ``metres_per_unit`` of the test file."""

    points: np.ndarray
    placement: Placement
    directions: np.ndarray
    metres_per_unit: float


@dataclasses.dataclass(frozen=True)
class ModelModes:
    """The model's lowest elastic modes over the family's parts, ascending: ``frequencies``
    (k,) [Hz], ``parts`` (k,) the part of each, ``source`` (k,) (index into ``solved``, index
    into that part's modes), ``labels`` (k,), ``solved`` the parts' models and shapes, and
    ``elements_per_link``."""

    frequencies: np.ndarray
    parts: tuple[Part, ...]
    source: tuple[tuple[int, int], ...]
    labels: tuple[str, ...]
    solved: tuple[PartModes, ...]
    elements_per_link: int

    def shape(self, mode: int) -> tuple[PartModes, np.ndarray]:
        """(the part solved, the shape (n_dofs,)) of model mode ``mode``."""
        p, k = self.source[mode]
        return self.solved[p], self.solved[p].shapes[:, k]


@dataclasses.dataclass(frozen=True)
class TestCorrelation:
    """A test correlated with a scene's model. ``model_readings`` (C, k_model): the model's
    mass-normalised shapes read at the test's channels; ``correlation``: by shape;
    ``by_order``: (test, model, MAC) of the pairing a frequency table by mode order implies,
    for comparison."""

    scene: Scene
    test: ModalTest
    sensors: SensorsOnModel
    model: ModelModes
    model_readings: np.ndarray
    correlation: Correlation
    by_order: tuple[tuple[int, int, float], ...]

    __test__ = False  # not a pytest class, whatever its name

    def __post_init__(self):
        check_shape("TestCorrelation", "model_readings", self.model_readings,
                    (len(self.test.channel_point), len(self.model.frequencies)))

    def errors_pct(self) -> np.ndarray:
        """Frequency error (model / test - 1) [%] of each accepted pair."""
        return np.array([100.0 * (self.model.frequencies[j] / self.test.frequencies[i] - 1.0)
                         for i, j in self.correlation.pairs])


def place_sensors(scene: Scene, test: ModalTest, model) -> SensorsOnModel:
    """The test's points and directions in the scene's frame ([test] table), each point on
    the nearest link of ``model`` (a FrameModel of the scene at its pose)."""
    frame = scene.options.test
    metres = test.metres_in_scene(frame, scene.path)
    points = frame.to_scene(test.coordinates, metres)
    placement = place_points(model, points, test.labels, frame.max_distance, source=test.source)
    return SensorsOnModel(points, placement, frame.direction_to_scene(test.channel_direction),
                          metres)


def model_modes(scene: Scene, n_modes: int, elements: int | None, labelled: bool = True
                ) -> ModelModes:
    """The lowest ``n_modes`` elastic modes of the scene's family at its pose; ``labelled``:
    name in-plane modes by their strain energy (``identity.mode_identity``), else by part."""
    solved = part_modes(scene, n_modes, elements)
    frequencies, source = paired(solved, n_modes)
    found = len(source)
    named = [mode_identity(part.model, part.shapes).labels
             if labelled and part.part is Part.IN_PLANE
             else (str(part.part),) * part.shapes.shape[1] for part in solved]
    labels = [named[p][k] for p, k in source]
    return ModelModes(frequencies[:found], tuple(solved[p].part for p, _ in source), source,
                      tuple(labels), solved, solved[0].model.links[0].elements)


def readings(modes: ModelModes, sensors: SensorsOnModel, channel_point) -> np.ndarray:
    """(C, k) the model's shapes read at the channels, each part by its own operator."""
    operators = {}
    out = np.zeros((len(channel_point), len(modes.frequencies)))
    for mode in range(len(modes.frequencies)):
        part, shape = modes.shape(mode)
        if part.part not in operators:
            operators[part.part] = channel_operator(part.part, part.model, sensors.placement,
                                                    channel_point, sensors.directions)
        out[:, mode] = operators[part.part] @ shape
    return out


def correlate_test(scene: Scene, test: ModalTest, n_modes: int | None = None,
                   elements: int | None = None, labelled: bool = True) -> TestCorrelation:
    """``test`` against the lowest ``n_modes`` (default: the test's modes + SPARE_MODES)
    elastic modes of ``scene``'s family at its pose, ``elements`` per link (``labelled`` as
    ``model_modes``)."""
    modes = model_modes(scene, n_modes or test.n_modes + SPARE_MODES, elements, labelled)
    sensors = place_sensors(scene, test, modes.solved[0].model)
    at_sensors = readings(modes, sensors, test.channel_point)
    result = correlate(test.shapes, at_sensors)
    by_order = tuple((i, j, float(result.mac[i, j]))
                     for i, j in pair_by_order(test.n_modes, len(modes.frequencies)))
    return TestCorrelation(scene, test, sensors, modes, at_sensors, result, by_order)


@dataclasses.dataclass(frozen=True)
class ModesAtPoints:
    """Model mode shapes at labelled points, for test software: ``labels`` (P,) positive
    integers, ``coordinates`` (P, 3) in ``unit`` in the frame they are written in,
    ``values`` (P, 3, k) along that frame's X, Y, Z [m / sqrt(kg), mass-normalised],
    ``frequencies`` (k,) [Hz]."""

    labels: np.ndarray
    coordinates: np.ndarray
    values: np.ndarray
    frequencies: np.ndarray
    unit: str

    def __post_init__(self):
        p, k = len(self.labels), len(self.frequencies)
        check_shape("ModesAtPoints", "coordinates", self.coordinates, (p, 3))
        check_shape("ModesAtPoints", "values", self.values, (p, 3, k))


def modes_at_nodes(model, shapes: np.ndarray, frequencies) -> ModesAtPoints:
    """In-plane ``shapes`` (n_dofs, k) at every node of ``model``: node i is label i + 1,
    coordinates and (ux, uy, 0) in the scene's frame, metres."""
    k = shapes.shape[1]
    nodal = shapes.reshape(-1, 3, k)
    values = np.concatenate([nodal[:, :2, :], np.zeros((len(model.nodes), 1, k))], axis=1)
    return ModesAtPoints(np.arange(1, len(model.nodes) + 1),
                         np.column_stack([model.nodes, np.zeros(len(model.nodes))]), values,
                         np.asarray(frequencies, dtype=float), "m")


def modes_at_test_points(scene: Scene, test: ModalTest, model, shapes: np.ndarray,
                         frequencies, part: Part = Part.IN_PLANE) -> ModesAtPoints:
    """``shapes`` (n_dofs, k) of ``part`` on ``model`` read at ``test``'s sensor points
    (placed by the scene's [test] table) along the test frame's X, Y and Z, with the test's
    own coordinates and unit (its labels where they are whole numbers, else 1, 2, ...)."""
    sensors = place_sensors(scene, test, model)
    n = len(test.labels)
    point = np.repeat(np.arange(n), 3)
    directions = scene.options.test.direction_to_scene(np.tile(np.eye(3), (n, 1)))
    S = channel_operator(part, model, sensors.placement, point, directions)
    values = (S @ shapes).reshape(n, 3, -1)
    labels = (np.array([int(x) for x in test.labels])
              if all(x.isdigit() and int(x) > 0 for x in test.labels) else np.arange(1, n + 1))
    unit = next((name for name, metres in UNITS["length"].items()
                 if abs(metres / sensors.metres_per_unit - 1) < 1e-9), None)
    coordinates = test.coordinates if unit else test.coordinates * sensors.metres_per_unit
    return ModesAtPoints(labels, coordinates, values,
                         np.asarray(frequencies, dtype=float), unit or "m")
