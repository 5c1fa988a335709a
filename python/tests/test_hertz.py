"""visco2d.hertz against independent computations: quadrature, energy balance, Johnson's numbers."""
import math

import numpy as np
import pytest

from visco2d import hertz

# Table 1's elastic sphere (the paper's): E, nu, R, rho, V.
E, NU, R, RHO, V = 18.11e6, 0.219, 0.0366, 756.85, 0.9982
M = RHO * 4.0 / 3.0 * math.pi * R ** 3


def test_time_constant_is_the_quadrature():
    """t_m = c alpha_m / V with c = int_0^1 dx / sqrt(1 - x^2.5), by the substitution x = 1 - u^2 (no singularity)."""
    u = np.linspace(0.0, 1.0, 200001)
    x = 1.0 - u ** 2
    integrand = np.where(u > 0, 2.0 * u / np.sqrt(np.maximum(1.0 - x ** 2.5, 1e-300)), 2.0 / math.sqrt(2.5))
    c = float(np.sum(0.5 * (integrand[1:] + integrand[:-1]) * np.diff(u)))   # the trapezoidal rule
    assert hertz.T_CONSTANT == pytest.approx(c, rel=1e-6)
    assert hertz.T_CONSTANT == pytest.approx(1.47, abs=0.005)   # the paper's eq. [44]


def test_alpha_max_is_the_energy_balance():
    """M V^2 / 2 = (2/5) k alpha_m^(5/2): the kinetic energy stored at the maximum approach."""
    alpha = hertz.alpha_max(E, NU, R, M, V)
    assert 0.4 * hertz.stiffness(E, NU, R) * alpha ** 2.5 == pytest.approx(0.5 * M * V ** 2, rel=1e-12)


def test_exact_reaches_the_closed_form_maximum():
    alpha_m, t_m, q_m, force, a = hertz.maxima(E, NU, R, M, V)
    t, alpha, q = hertz.exact(E, NU, R, M, V, 2.2 * t_m, steps=8000)
    peak = int(np.argmax(alpha))
    assert alpha[peak] == pytest.approx(alpha_m, rel=1e-6)
    assert t[peak] == pytest.approx(t_m, abs=2.2 * t_m / 8000)
    assert q[peak] == pytest.approx(q_m, rel=1e-6)
    assert force == pytest.approx(hertz.stiffness(E, NU, R) * alpha_m ** 1.5)
    assert a == pytest.approx(math.sqrt(R * alpha_m))


def test_contact_force_and_pressure_agree():
    """F = (2/3) pi a^2 q_0: the Hertz pressure's integral over the contact circle."""
    alpha_m, _, q_m, force, a = hertz.maxima(E, NU, R, M, V)
    assert force == pytest.approx(2.0 / 3.0 * math.pi * a ** 2 * q_m, rel=1e-12)


def test_goldsmith_peaks_near_hertz():
    alpha_m, t_m, *_ = hertz.maxima(E, NU, R, M, V)
    t = np.linspace(0.0, 2.0 * t_m, 4001)
    alpha, _ = hertz.goldsmith(E, NU, R, M, V, t)
    assert alpha.max() == pytest.approx(alpha_m, rel=1e-6)
    # Goldsmith's sine peaks at pi alpha_m / (2 1.068 V): within 0.1 % of t_m (1.4708 against 1.4716).
    assert t[int(np.argmax(alpha))] == pytest.approx(t_m, rel=2e-3)


def test_subsurface_shear_maximum_is_johnsons():
    """For nu = 0.3 the axis shear peaks at 0.31 q_0 at the depth 0.48 a (Johnson, Contact Mechanics, ch. 4)."""
    depths = np.linspace(0.0, 3.0, 30001)
    shear = hertz.subsurface_shear(0.3, 1.0, 1.0, depths)
    peak = int(np.argmax(shear))
    assert shear[peak] == pytest.approx(0.31, abs=0.005)
    assert depths[peak] == pytest.approx(0.48, abs=0.01)
    # at the surface sigma_z = -q_0, sigma_r = -(1/2 + nu) q_0: tau = (1/2 - nu) q_0 / 2
    assert shear[0] == pytest.approx(0.5 * (0.5 - 0.3), abs=1e-9)
