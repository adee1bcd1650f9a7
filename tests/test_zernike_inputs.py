"""lo.noll_index, lo.zernike and Aberrations.wavefront refuse what is not a Noll index or a finite
pupil point with a ValueError naming it: a float index was cut to an integer, 2**32 gave pybind11's
signature dump, and a NaN or infinite coordinate gave a NaN wavefront without a word."""

import math

import numpy as np
import pytest

import lidar_overlap as lo


@pytest.mark.parametrize("j", [1.5, True, math.nan, math.inf, None, (1, 2), 0, 1001, 2**32, 2**64])
def test_noll_index_and_zernike_refuse_what_is_not_an_index_from_1_to_1000(j):
    with pytest.raises(ValueError, match=r"^j = .* expected an integer from 1 to 1000"):
        lo.noll_index(j)
    with pytest.raises(ValueError, match=r"^j = .* expected an integer from 1 to 1000"):
        lo.zernike(j, [0.1], [0.2])


def test_the_valid_indices_are_unchanged():
    # Noll's ordering: j = 4 is defocus (2, 0), 11 spherical (4, 0), 1000 of radial order 44
    assert lo.noll_index(np.int64(4)) == (2, 0)
    assert lo.noll_index(11) == (4, 0)
    assert lo.noll_index(1000)[0] == 44
    # Z4 = sqrt(3) (2 rho^2 - 1)
    np.testing.assert_allclose(
        lo.zernike(4, [0.0, 0.6], [0.0, 0.0]), np.sqrt(3) * np.array([-1, -0.28])
    )


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf, None, "x", True])
@pytest.mark.parametrize("axis", ["x", "y"])
def test_pupil_points_must_be_finite_real_numbers(bad, axis):
    points = {"x": [0.1, 0.2], "y": [0.0, 0.3]}
    points[axis] = [0.1, bad] if bad is not None and not isinstance(bad, (str, bool)) else bad
    with pytest.raises(ValueError, match=rf"^{axis} = "):
        lo.zernike(5, points["x"], points["y"])
    with pytest.raises(ValueError, match=rf"^{axis} = "):
        lo.Aberrations(w040=1e-7).wavefront(points["x"], points["y"])


@pytest.mark.parametrize("x, y", [(0.0, 1e300), (1e300, 0.0), (1e200, -1e200)])
def test_points_where_the_polynomial_overflows_are_refused_naming_x_and_y(x, y):
    # Z4 = sqrt(3) (2 rho^2 - 1) is infinite in double precision at |rho| = 1e300: it was returned
    with pytest.raises(ValueError, match=r"^x, y = .* Z_4 overflows"):
        lo.zernike(4, [0.5, x], [0.5, y])
    with pytest.raises(ValueError, match=r"^x, y = .* wavefront overflows"):
        lo.Aberrations(w040=1e-7).wavefront([0.5, x], [0.5, y])
    # outside the pupil but finite: the polynomial's value, as before
    assert lo.zernike(4, 2.0, 0.0) == pytest.approx(np.sqrt(3) * 7.0, rel=1e-14)
