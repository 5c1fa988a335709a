"""Hertz's impact of an elastic sphere on a rigid plate: the paper's eqs. [43]-[46].

E is Young's modulus (Pa), nu Poisson's ratio, R the radius (m), M the mass (kg),
V the impact speed (m/s). The closed forms take scalars; the pressure and the
shear take numpy arrays too.
"""
import math

import numpy as np

#: t_m = T alpha_m / V, T = (2/5) Gamma(2/5) Gamma(1/2) / Gamma(9/10) = 1.4716 (eq. [44]).
T_CONSTANT = 0.4 * math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9)


def stiffness(young, poisson, radius):
    """k of F = k alpha^1.5: (4/3) E / (1 - nu^2) sqrt(R) (N/m^1.5)."""
    return 4.0 / 3.0 * young / (1.0 - poisson ** 2) * math.sqrt(radius)


def alpha_max(young, poisson, radius, mass, speed):
    """Eq. [43]: alpha_m = (15 (1 - nu^2) M V^2 / (16 E sqrt(R)))^0.4 (m)."""
    return (15.0 * (1.0 - poisson ** 2) * mass * speed ** 2 / (16.0 * young * math.sqrt(radius))) ** 0.4


def pressure(young, poisson, radius, alpha):
    """Eq. [45] at any approach: q = 2 E / (pi (1 - nu^2)) sqrt(alpha / R) (Pa)."""
    return 2.0 * young / (math.pi * (1.0 - poisson ** 2)) * np.sqrt(np.maximum(alpha, 0.0) / radius)


def maxima(young, poisson, radius, mass, speed):
    """Eqs. [43]-[45] at the maximum: alpha_m (m), t_m (s), q_m (Pa), F_m (N), contact radius a_m (m)."""
    alpha = alpha_max(young, poisson, radius, mass, speed)
    t_m = T_CONSTANT * alpha / speed
    q_m = float(pressure(young, poisson, radius, alpha))
    force = stiffness(young, poisson, radius) * alpha ** 1.5
    return alpha, t_m, q_m, force, math.sqrt(radius * alpha)


def exact(young, poisson, radius, mass, speed, t_end, steps=4000):
    """The impact M alpha'' = -k alpha^1.5, alpha(0) = 0, alpha'(0) = V, integrated to t_end.

    scipy's solve_ivp (rtol 1e-10) when present, else classical RK4 with `steps` steps.
    Returns t (s), alpha (m), q (Pa) on steps + 1 equal intervals.
    """
    k = stiffness(young, poisson, radius)

    def rate(_t, y):
        return np.array([y[1], -k / mass * max(y[0], 0.0) ** 1.5])

    t = np.linspace(0.0, t_end, steps + 1)
    try:
        from scipy.integrate import solve_ivp
        alpha = solve_ivp(rate, (0.0, t_end), [0.0, speed], t_eval=t, rtol=1e-10, atol=1e-14).y[0]
    except ImportError:
        y = np.array([0.0, speed])
        alpha = np.empty_like(t)
        alpha[0] = 0.0
        h = t[1] - t[0]
        for n in range(steps):
            k1 = rate(t[n], y)
            k2 = rate(t[n] + h / 2, y + h / 2 * k1)
            k3 = rate(t[n] + h / 2, y + h / 2 * k2)
            k4 = rate(t[n] + h, y + h * k3)
            y = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            alpha[n + 1] = y[0]
    return t, alpha, pressure(young, poisson, radius, alpha)


def goldsmith(young, poisson, radius, mass, speed, t):
    """Goldsmith's approximation, eq. [46]: alpha(t) = alpha_m sin(1.068 V t / alpha_m), q(t) by eq. [45].

    Returns alpha (m), q (Pa)."""
    alpha_m = alpha_max(young, poisson, radius, mass, speed)
    alpha = alpha_m * np.sin(np.minimum(1.068 * speed * np.asarray(t) / alpha_m, math.pi))
    return alpha, pressure(young, poisson, radius, alpha)


def subsurface_shear(poisson, q0, a, depths):
    """tau = (sigma_z - sigma_r)/2 on the axis under a Hertz contact at the given depths (Pa).

    sigma_z = -q0/(1 + s^2), sigma_r = -q0 [(1 + nu)(1 - s atan(1/s)) - 1/(2 (1 + s^2))], s = z/a"""
    s = np.maximum(np.asarray(depths) / a, 1e-12)
    sigma_z = -q0 / (1.0 + s ** 2)
    sigma_r = -q0 * ((1.0 + poisson) * (1.0 - s * np.arctan(1.0 / s)) - 0.5 / (1.0 + s ** 2))
    return 0.5 * np.abs(sigma_z - sigma_r)
