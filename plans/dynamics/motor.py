"""A motor's moment reduced to the crank: a torque–speed table of its shaft, or an induction
motor by Kloss' formula, through the gear ratio i = n_motor/n_crank (losses neglected:
M_crank = i·M_motor at ω_motor = i·ω_crank).

Kloss: M = 2·M_k·s·s_k/(s² + s_k²), s = 1 − n/n_sync the slip, M_k = λ·M_rated the breakdown
(largest) moment, M_rated = P/ω_rated, s_k = s_rated·(λ + √(λ² − 1)) (the curve through the
rated point). Written with s·s_k over s² + s_k² so that it is 0, not 0/0, at synchronous speed.
"""

from __future__ import annotations

import math

import numpy as np

from ..scene.dynamics import Motor

__all__ = ["motor_moment", "no_load_speed", "RPM"]

#: rad/s per rpm.
RPM = 2.0 * math.pi / 60.0


def motor_moment(motor: Motor, omega: np.ndarray | float) -> np.ndarray:
    """The motor's moment at the crank (N·m, driving when positive) at the crank's speed
    ``omega`` (rad/s, in its sense of rotation)."""
    w = np.asarray(omega, dtype=float) * motor.ratio          # the motor's shaft, rad/s
    if motor.torque:
        n = w / RPM
        xs = np.array([r[0] for r in motor.torque])
        ys = np.array([r[1] for r in motor.torque])
        m = np.interp(n, xs, ys)
        lo = (ys[1] - ys[0]) / (xs[1] - xs[0])              # linear beyond both ends
        hi = (ys[-1] - ys[-2]) / (xs[-1] - xs[-2])
        m = np.where(n < xs[0], ys[0] + lo * (n - xs[0]), m)
        m = np.where(n > xs[-1], ys[-1] + hi * (n - xs[-1]), m)
    else:
        lam = motor.breakdown
        s_r = 1.0 - motor.rated_rpm / motor.synchronous_rpm
        s_k = s_r * (lam + math.sqrt(lam * lam - 1.0))
        m_k = lam * motor.power / (motor.rated_rpm * RPM)
        s = 1.0 - w / (motor.synchronous_rpm * RPM)
        m = 2.0 * m_k * s * s_k / (s * s + s_k * s_k)
    return motor.ratio * m


def no_load_speed(motor: Motor) -> float:
    """The crank's speed (rad/s) where the motor's moment falls to 0: the synchronous speed, or
    the table's first zero past its largest moment (its last speed's extrapolation when none)."""
    if not motor.torque:
        return motor.synchronous_rpm * RPM / motor.ratio
    xs = np.array([r[0] for r in motor.torque])
    ys = np.array([r[1] for r in motor.torque])
    k = int(np.argmax(ys))
    for j in range(k, len(xs) - 1):
        if ys[j] > 0.0 >= ys[j + 1]:
            return float(xs[j] + (xs[j + 1] - xs[j]) * ys[j] / (ys[j] - ys[j + 1])) * RPM / motor.ratio
    slope = (ys[-1] - ys[-2]) / (xs[-1] - xs[-2])
    if slope < 0.0 and ys[-1] > 0.0:
        return float(xs[-1] - ys[-1] / slope) * RPM / motor.ratio
    return math.inf
