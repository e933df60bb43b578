"""`measure` through a gradient-index medium (docs/grin.md): the far field of a Luneburg
lens binned by angle agrees with the lens's analytic exit law."""
import numpy as np

import refract

LUNEBURG_BEAM = {
    "camera": {"location": [0, 0, -4], "look_at": [0, 0, 0], "angle": 40, "width": 8, "height": 6},
    "materials": {"lens": {"type": "grin", "profile": {"kind": "luneburg", "centre": [0, 0, 0], "radius": 1}}},
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "lens"}],
    "lights": [{"type": "beam", "position": [0, 0, -3], "direction": [0, 0, 1], "radius": 1.2}],
}


def test_luneburg_far_field_measured_by_angle_follows_sin_theta_equals_impact(tmp_path):
    # A ray at impact b (radius 1) leaves at the antipode, where n = 1, and Bouguer's
    # invariant n r sin(psi) = b gives its angle to the axis: sin(theta) = b. A uniform beam
    # puts b^2 uniform on [0, 1], so a fraction sin^2(theta) of what enters leaves within
    # theta: 3/4 within 60 degrees, 1/4 from 60 to 90, none beyond. The index is 1 at the
    # surface, so nothing reflects and no ray reflects inside (class "0 internal
    # reflections" holds it all).
    r = refract.farfield(LUNEBURG_BEAM, tmp_path, photons=20000, azimuth_bins=72, polar_bins=36,
                         wavelengths=[550], threads=2, plot=False, seed=3)
    entered = 1.0 - r["unscattered"][0]
    assert abs(entered - 1 / 1.44) < 0.015  # the sphere's share of the beam's disc
    # polar_bins = 36 rows of equal solid angle: rows 0-8 end at cos(theta) = 0.5 (60 degrees)
    # and 9-17 at 0 (90 degrees), so the 60-degree bins below split no row.
    h = refract.angle_histogram(tmp_path / "far_field.exr", bins=3, axis=[0, 0, 1])
    ch = list(h["channels"])
    total = h["power"][:, ch.index("total")]
    assert np.allclose([h["theta0_deg"][0], h["theta1_deg"][0]], [0, 60])
    # Binomial standard error of a share of the 13 900 photons that enter: 0.0037.
    assert abs(total[0] / entered - 0.75) < 0.015
    assert abs(total[1] / entered - 0.25) < 0.015
    assert total[2] == 0.0
    assert np.all(h["power"][:, ch.index("class0")] == 0.0)
    assert np.allclose(h["power"][:, ch.index("class1")], total, rtol=0, atol=1e-12)
