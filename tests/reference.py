"""An independent reference solver for planar linkages: the generic Jacobian solve.

It shares no code with ``plans.kinematics``: it reads only the :class:`plans.model.Mechanism`
(the links' local coordinates, the revolute and prismatic pairs, the drive) and solves the
constraint equations of the whole mechanism at once, the way a general-purpose multibody
code does, instead of group by group in closed form.

Coordinates
-----------
q holds the pose (x_o, y_o, θ) of every moving link, the driving link included; a pose maps
a local point x to o + R(θ)·x, and the frame has the identity pose. The drive is one more
equation (a "driving constraint"), so Φ(q, t) = 0 is square, 3n equations in 3n unknowns:

* revolute pair at P between links a and b (2 equations)::

      o_a + R(θ_a)·P_a − o_b − R(θ_b)·P_b = 0

* prismatic pair, slider s on guide g, local anchors A_s, A_g on the line, local direction
  u (the same in both links) and normal n = k × u (2 equations)::

      θ_s − θ_g = 0
      (o_s + R(θ_s)·A_s − o_g − R(θ_g)·A_g) · R(θ_g)·n = 0

* rotary drive, pivot O and tip T of the driving link d (angle of O → T is φ(t))::

      θ_d + atan2(T − O)_local − φ(t) = 0

* linear drive, link d sliding on a guide of direction u fixed in link g — the frame, or a
  moving link for a hydraulic cylinder (displacement s(t) along the guide from the sketch
  position, where every pose is the identity; the coupler drive is the rotary one's equation
  for a link not pivoted on the frame)::

      (o_d + R(θ_d)·A_d − o_g − R(θ_g)·A_g) · R(θ_g)·u − (A_d − A_g)·u − s(t) = 0

Positions are found by Newton's method, continued from the sketch (the identity pose) in small
steps with a second-order predictor; the sign of det Φ_q is watched so that the walk stays on
one assembly branch. Differentiating Φ(q(t), t) = 0 once and twice::

    Φ_q·q̇ = −Φ_t                    (only the driving row: the drive's speed)
    Φ_q·q̈ = γ = −(Φ_q·q̇)_q·q̇ − Φ_tt   (Φ_qt = 0 here)

with γ written out analytically below (:meth:`Reference.gamma`). Both are solved with
``numpy.linalg.solve``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Reference", "RefState", "ConvergenceError"]

_J = np.array([[0.0, -1.0], [1.0, 0.0]])   # k × (.): turns a plane vector by +90°


def _rot(theta: float) -> np.ndarray:
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s], [s, c]])


class ConvergenceError(RuntimeError):
    """Newton's method or the continuation did not converge."""


@dataclass
class RefState:
    """The reference solution at one drive value: q, q̇, q̈ (pose, velocity, acceleration of
    every moving link's origin and angle)."""

    ref: "Reference"
    value: float          # drive value in the scene's unit (degrees or metres)
    q: np.ndarray
    qd: np.ndarray | None = None
    qdd: np.ndarray | None = None

    def _pose(self, vec: np.ndarray | None, link: str) -> tuple[np.ndarray, float]:
        c = self.ref.col.get(link)
        if c is None or vec is None:
            return np.zeros(2), 0.0
        return vec[c:c + 2].copy(), float(vec[c + 2])

    def theta(self, link: str) -> float:
        return self._pose(self.q, link)[1]

    def omega(self, link: str) -> float:
        return self._pose(self.qd, link)[1]

    def epsilon(self, link: str) -> float:
        return self._pose(self.qdd, link)[1]

    def _arm(self, point: str, link: str | None) -> tuple[str, np.ndarray]:
        link = link or self.ref.carrier(point)
        o, th = self._pose(self.q, link)
        return link, _rot(th) @ self.ref.mech.links[link].local[point]

    def position(self, point: str, link: str | None = None) -> np.ndarray:
        link, r = self._arm(point, link)
        return self._pose(self.q, link)[0] + r

    def velocity(self, point: str, link: str | None = None) -> np.ndarray:
        """v_P = ȯ + θ̇ k × R(θ)·P."""
        link, r = self._arm(point, link)
        vo, w = self._pose(self.qd, link)
        return vo + w * (_J @ r)

    def acceleration(self, point: str, link: str | None = None) -> np.ndarray:
        """a_P = ö + θ̈ k × R(θ)·P − θ̇² R(θ)·P."""
        link, r = self._arm(point, link)
        _, w = self._pose(self.qd, link)
        ao, e = self._pose(self.qdd, link)
        return ao + e * (_J @ r) - w * w * r


class Reference:
    """The generic Jacobian solver of one mechanism (see the module docstring)."""

    def __init__(self, mech):
        self.mech = mech
        self.moving = [name for name, link in mech.links.items() if not link.is_frame]
        self.col = {name: 3 * i for i, name in enumerate(self.moving)}
        self.n = 3 * len(self.moving)
        neq = 2 * len(mech.revolutes) + 2 * len(mech.prismatics) + 1
        if neq != self.n:
            raise ValueError(f"{neq} constraint equations for {self.n} unknowns: not a one-drive mechanism")
        d = mech.drive
        self.rotary = d.kind in ("rotary", "coupler")
        if self.rotary:
            local = mech.links[d.link].local
            arm = local[d.tip] - local[d.pivot]
            self.arm_angle = math.atan2(arm[1], arm[0])
            #: drive value (degrees) at the identity pose of every link (the sketch)
            self.start = math.degrees(self.arm_angle)
        else:
            self.guide = d.guide
            self.u = np.asarray(d.guide.direction, float)
            self.offset = float((d.guide.anchor[d.link] - d.guide.anchor[d.guide.guide]) @ self.u)
            self.start = 0.0
        self.speed, self.rate = float(d.speed), float(d.rate)

    # --- helpers ------------------------------------------------------------------------

    def carrier(self, point: str) -> str:
        return next(name for name, link in self.mech.links.items() if point in link.local)

    def _pose(self, q: np.ndarray, link: str) -> tuple[np.ndarray, float]:
        c = self.col.get(link)
        if c is None:
            return np.zeros(2), 0.0
        return q[c:c + 2], float(q[c + 2])

    def _si(self, value: float) -> float:
        """Drive value in SI (rad or m)."""
        return math.radians(value) if self.rotary else float(value)

    # --- the constraint equations ---------------------------------------------------------

    def residual(self, q: np.ndarray, value: float) -> np.ndarray:
        """Φ(q) at drive ``value`` (degrees or metres)."""
        out = []
        for r in self.mech.revolutes:
            pa = self._world(q, r.a, self.mech.links[r.a].local[r.point])
            pb = self._world(q, r.b, self.mech.links[r.b].local[r.point])
            out += list(pa - pb)
        for p in self.mech.prismatics:
            _, ts = self._pose(q, p.slider)
            _, tg = self._pose(q, p.guide)
            d = self._world(q, p.slider, p.anchor[p.slider]) - self._world(q, p.guide, p.anchor[p.guide])
            out += [ts - tg, float(d @ (_rot(tg) @ p.normal))]
        out.append(self._drive_residual(q, value))
        return np.array(out)

    def _world(self, q: np.ndarray, link: str, local: np.ndarray) -> np.ndarray:
        o, th = self._pose(q, link)
        return o + _rot(th) @ local

    def _drive_residual(self, q: np.ndarray, value: float) -> float:
        o, th = self._pose(q, self.mech.drive.link)
        if self.rotary:
            return th + self.arm_angle - self._si(value)
        p = self.guide
        d = self._world(q, p.slider, p.anchor[p.slider]) - self._world(q, p.guide, p.anchor[p.guide])
        return float(d @ (_rot(self._pose(q, p.guide)[1]) @ self.u)) - self.offset - self._si(value)

    def jacobian(self, q: np.ndarray) -> np.ndarray:
        """Φ_q, analytic."""
        Jac = np.zeros((self.n, self.n))
        row = 0

        def put(link: str, rows: slice, d_o: np.ndarray, d_th: np.ndarray) -> None:
            c = self.col.get(link)
            if c is not None:
                Jac[rows, c:c + 2] += d_o
                Jac[rows, c + 2] += d_th

        for r in self.mech.revolutes:
            ra = _rot(self._pose(q, r.a)[1]) @ self.mech.links[r.a].local[r.point]
            rb = _rot(self._pose(q, r.b)[1]) @ self.mech.links[r.b].local[r.point]
            put(r.a, slice(row, row + 2), np.eye(2), _J @ ra)
            put(r.b, slice(row, row + 2), -np.eye(2), -(_J @ rb))
            row += 2
        def offset(p, local: np.ndarray, rows: slice) -> None:
            """∂/∂q of (X_s − Y_g)·R(θ_g)·local: a prismatic pair's normal row, a cylinder's stroke."""
            tg = self._pose(q, p.guide)[1]
            dg = _rot(tg) @ local
            rs = _rot(self._pose(q, p.slider)[1]) @ p.anchor[p.slider]
            rg = _rot(tg) @ p.anchor[p.guide]
            d = self._world(q, p.slider, p.anchor[p.slider]) - self._world(q, p.guide, p.anchor[p.guide])
            put(p.slider, rows, dg[None], np.array([(_J @ rs) @ dg]))
            put(p.guide, rows, -dg[None], np.array([-(_J @ rg) @ dg + d @ (_J @ dg)]))

        for p in self.mech.prismatics:
            put(p.slider, slice(row, row + 1), np.zeros((1, 2)), np.array([1.0]))
            put(p.guide, slice(row, row + 1), np.zeros((1, 2)), np.array([-1.0]))
            offset(p, p.normal, slice(row + 1, row + 2))
            row += 2
        if self.rotary:
            put(self.mech.drive.link, slice(row, row + 1), np.zeros((1, 2)), np.array([1.0]))
        else:
            offset(self.guide, self.u, slice(row, row + 1))
        return Jac

    def gamma(self, q: np.ndarray, qd: np.ndarray, rate: float) -> np.ndarray:
        """Right-hand side of Φ_q·q̈ = γ: every term of d²Φ/dt² that is not linear in q̈."""
        out = []
        for r in self.mech.revolutes:
            # d²/dt² (o + R P) = ö + θ̈ k×R P − θ̇² R P
            (_, ta), (_, tb) = self._pose(q, r.a), self._pose(q, r.b)
            (_, wa), (_, wb) = self._pose(qd, r.a), self._pose(qd, r.b)
            ra = _rot(ta) @ self.mech.links[r.a].local[r.point]
            rb = _rot(tb) @ self.mech.links[r.b].local[r.point]
            out += list(wa * wa * ra - wb * wb * rb)
        def quad(p, local: np.ndarray) -> float:
            """The terms of Φ̈ not linear in q̈, for Φ = (X_s − Y_g)·d_g, d_g = R(θ_g)·local:
            Φ̈ = d̈·d_g + 2 ḋ·ḋ_g + d·d̈_g, ḋ_g = θ̇_g k×d_g, d̈_g = θ̈_g k×d_g − θ̇_g² d_g."""
            (os_, ts), (og, tg) = self._pose(q, p.slider), self._pose(q, p.guide)
            (vs, ws), (vg, wg) = self._pose(qd, p.slider), self._pose(qd, p.guide)
            rs, rg = _rot(ts) @ p.anchor[p.slider], _rot(tg) @ p.anchor[p.guide]
            dg = _rot(tg) @ local
            d = (os_ + rs) - (og + rg)
            dd = (vs + ws * (_J @ rs)) - (vg + wg * (_J @ rg))
            return (-ws * ws * rs + wg * wg * rg) @ dg + 2.0 * wg * (dd @ (_J @ dg)) - wg * wg * (d @ dg)

        for p in self.mech.prismatics:
            out += [0.0, -quad(p, p.normal)]
        out.append(rate if self.rotary else rate - quad(self.guide, self.u))
        return np.array(out)

    def _e_drive(self, speed: float) -> np.ndarray:
        rhs = np.zeros(self.n)
        rhs[-1] = speed
        return rhs

    # --- solving --------------------------------------------------------------------------

    def newton(self, q0: np.ndarray, value: float, *, tol: float = 1e-13, maxiter: int = 40) -> np.ndarray:
        """Positions at drive ``value`` by Newton's method from the guess ``q0``.

        Iterates until the residual is below ``tol`` (scaled by the size of q when the
        positions are large) and then twice more, so the result is as exact as the
        arithmetic allows."""
        q = np.array(q0, float)
        polish = 0
        for _ in range(maxiter):
            res = self.residual(q, value)
            if np.max(np.abs(res)) < tol * max(1.0, float(np.max(np.abs(q)))):
                polish += 1
                if polish > 2:
                    return q
            q = q - np.linalg.solve(self.jacobian(q), res)
        res = self.residual(q, value)
        if np.max(np.abs(res)) < tol * max(1.0, float(np.max(np.abs(q)))):
            return q
        raise ConvergenceError(f"Newton did not converge at {value}: |Φ| = {np.max(np.abs(res)):.3g}")

    def rates(self, q: np.ndarray, value: float, speed: float | None = None,
              rate: float | None = None) -> RefState:
        """The full state (q, q̇, q̈) at a solved position ``q``."""
        speed = self.speed if speed is None else speed
        rate = self.rate if rate is None else rate
        Jac = self.jacobian(q)
        qd = np.linalg.solve(Jac, self._e_drive(speed))
        qdd = np.linalg.solve(Jac, self.gamma(q, qd, rate))
        return RefState(self, value, q, qd, qdd)

    def at(self, value: float, guess: np.ndarray) -> RefState:
        """Newton from ``guess`` (e.g. another solver's pose, perturbed), then the rates."""
        return self.rates(self.newton(guess, value), value)

    def solve(self, values, *, step: float | None = None) -> list[RefState]:
        """States at the drive ``values``, each reached by continuation from the sketch
        (the identity pose) along the drive, in steps of at most ``step`` (default 1° or
        1/400 of the sketch size), halved whenever Newton fails or det Φ_q changes sign
        (which would mean the walk jumped to another assembly branch)."""
        values = [float(v) for v in np.atleast_1d(values)]
        if step is None:
            step = 1.0 if self.rotary else self._sketch_size() / 400.0
        q0 = self.newton(np.zeros(self.n), self.start, tol=1e-12)
        out: dict[float, RefState] = {}
        for direction in (1.0, -1.0):
            targets = sorted((v for v in values if (v - self.start) * direction >= 0), key=lambda v: direction * v)
            q, v = q0, self.start
            for target in targets:
                q = self._walk(q, v, target, step)
                v = target
                out[target] = self.rates(q, target)
        return [out[v] for v in values]

    def _sketch_size(self) -> float:
        pts = np.array(list(self.mech.sketch.values()))
        return float(np.hypot(*(pts.max(axis=0) - pts.min(axis=0)))) or 1.0

    def _walk(self, q: np.ndarray, v: float, target: float, step: float) -> np.ndarray:
        sign0 = np.sign(np.linalg.det(self.jacobian(q)))
        h = step
        while v != target:
            dv = math.copysign(min(h, abs(target - v)), target - v)
            nxt = target if abs(target - v) <= h else v + dv
            st = self.rates(q, v, speed=1.0, rate=0.0)        # dq/dφ and d²q/dφ² (SI drive units)
            ds = self._si(nxt) - self._si(v)
            guess = q + st.qd * ds + 0.5 * st.qdd * ds * ds
            try:
                q_new = self.newton(guess, nxt, tol=1e-12)
                ok = np.sign(np.linalg.det(self.jacobian(q_new))) == sign0
                # the corrector must stay close to the predictor, or it may have changed branch
                ok = ok and np.max(np.abs(q_new - guess)) < 0.05 * max(1e-9, np.max(np.abs(st.qd * ds)))
            except (ConvergenceError, np.linalg.LinAlgError):
                ok = False
            if not ok:
                h /= 2.0
                if h < 1e-9 * step:
                    raise ConvergenceError(f"continuation stalls at {v} (singular position or no assembly)")
                continue
            q, v = q_new, nxt
            h = min(step, 2.0 * h)
        return self.newton(q, target)

    # --- singular positions ---------------------------------------------------------------

    def fold(self, state: RefState, *, maxiter: int = 50) -> RefState:
        """The nearest limit (turning) position of the drive: solve the extended system
        Φ(q, φ) = 0, Φ_q(q)·w = 0, c·w = 1 (Moore–Spence) by Newton, from a state near it.
        Returns the position (``value`` = the singular drive value) with q̇, q̈ unset."""
        q = state.q.copy()
        phi = self._si(state.value)
        _, _, vt = np.linalg.svd(self.jacobian(q))
        w = vt[-1].copy()
        c = w.copy()
        n = self.n
        to_value = math.degrees if self.rotary else float

        def F(q, phi, w):
            return np.concatenate([self.residual(q, to_value(phi)), self.jacobian(q) @ w, [c @ w - 1.0]])

        for _ in range(maxiter):
            f = F(q, phi, w)
            if np.max(np.abs(f)) < 1e-14:
                break
            Jq = self.jacobian(q)
            big = np.zeros((2 * n + 1, 2 * n + 1))
            big[:n, :n] = Jq
            big[n - 1, n] = -1.0                      # ∂Φ_drive/∂φ (both drive kinds)
            h = 1e-6
            for j in range(n):                        # (Φ_q w)_q by central differences of Φ_q
                e = np.zeros(n)
                e[j] = h
                big[n:2 * n, j] = (self.jacobian(q + e) @ w - self.jacobian(q - e) @ w) / (2 * h)
            big[n:2 * n, n + 1:] = Jq
            big[2 * n, n + 1:] = c
            step = np.linalg.solve(big, -f)
            q, phi, w = q + step[:n], phi + step[n], w + step[n + 1:]
        f = F(q, phi, w)
        if np.max(np.abs(f)) > 1e-12:
            raise ConvergenceError(f"fold search did not converge: |F| = {np.max(np.abs(f)):.3g}")
        return RefState(self, to_value(phi), q)
