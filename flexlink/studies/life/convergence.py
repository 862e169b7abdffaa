"""The estimated error of each link's peak stress in the mesh and in the basis.

Estimated by refining each once: the mesh with twice the elements per link, the basis with
``EXTRA_MODES`` more static modes per pose behind it (``stability_map.periodic_model``'s
n_modes); the estimate is the larger relative change of the link's peak |sigma|. Where the
error falls at least linearly with the refinement, the change bounds the coarse answer's error
from about as much to twice as much; stated with every output as an estimate, not a bound.
The stress converges more slowly than the frequency: at an element end the axial and
bending stress of the static part is exact (``fe.stress``), the dynamic part's error falls as
h^2 for the Hermite element.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.scene import Scene
from flexlink.studies.life.stress_field import MODES, StressField, stress_field, stress_model

TOLERANCE = 0.02  # the default settings are meant to hold each link's peak stress within 2 %
EXTRA_MODES = 4
HOW = ("the larger relative change of each link's peak |stress| when the mesh is refined "
       "(elements per link doubled) and when the basis is enlarged (4 more static modes per "
       "pose), at the same speed")


@dataclasses.dataclass(frozen=True)
class PeakError:
    """Per link (``links``) the relative change [-] of the peak |sigma| on refining the mesh
    and the basis, and the estimate (their larger); tolerance [-] the settings aim at."""

    links: tuple[str, ...]
    mesh: np.ndarray
    basis: np.ndarray
    tolerance: float = TOLERANCE

    @property
    def estimate(self) -> np.ndarray:
        return np.maximum(self.mesh, self.basis)

    @property
    def met(self) -> bool:
        return bool(np.all(self.estimate <= self.tolerance))


def link_peaks(field: StressField) -> np.ndarray:
    """Each link's peak |sigma| [Pa] over the turn, in ``field.points.links`` order."""
    return np.array([np.abs(field.total[:, field.points.of(name)]).max()
                     for name in field.points.links])


def peak_error(scene: Scene, field: StressField, elements: int, n_modes: int = MODES,
               poses: int = 37, damping_ratio: float | None = None) -> PeakError:
    """``PeakError`` of ``field`` (computed on ``elements`` per link and ``n_modes``)."""
    base = link_peaks(field)
    changes = []
    for mesh, modes in ((2 * elements, n_modes), (elements, n_modes + EXTRA_MODES)):
        refined = stress_field(stress_model(scene, modes, poses, damping_ratio, mesh,
                                            verdict=False),
                               field.speed, len(field.angles), check_stability=False)
        peaks = link_peaks(refined)
        changes.append(np.abs(peaks - base) / np.maximum(peaks, 1e-300))
    return PeakError(field.points.links, changes[0], changes[1])
