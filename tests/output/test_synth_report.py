"""`flexlink synth`'s JSON document and text against closed forms of the four-bar it reports:
the transmission angle's limits by the law of cosines at crank angles 0 and 180 deg, and the
ratios as the lengths over the ground link."""

import math

import pytest

from flexlink.output.pose.crank_rocker import crank_rocker_document, crank_rocker_text
from flexlink.studies.pose.crank_rocker import crank_rocker


def test_document_limits_and_ratios_follow_from_its_lengths():
    result = crank_rocker("brodell-soni", {"gamma_min": "40 deg", "swing": "60 deg"},
                          math.radians(40), math.radians(60), 0.3)
    doc = crank_rocker_document(result)
    lengths = doc["lengths_m"]
    g, a, b, c = (lengths[k] for k in ("ground", "crank", "coupler", "rocker"))
    # the coupler-rocker angle when the crank lies along the ground (g - a) and against it (g + a)
    mu = sorted(math.degrees(math.acos((b * b + c * c - d * d) / (2 * b * c)))
                for d in (g - a, g + a))
    assert (doc["mu_min_deg"], doc["mu_max_deg"]) == pytest.approx(mu, rel=1e-9)
    assert doc["mu_min_deg"] == pytest.approx(40.0, rel=1e-9)  # Brodell-Soni's target
    assert doc["ratios"] == pytest.approx({"R2": a / g, "R3": b / g, "R4": c / g}, rel=1e-12)
    assert doc["rocker_swing_deg"] == pytest.approx(60.0, rel=1e-9)
    text = crank_rocker_text(doc)
    assert f"transmission angle {mu[0]:.3f} .. {mu[1]:.3f} deg" in text
    assert f"rocker swing {60:.3f} deg" in text
