#!/usr/bin/python3
"""Benchmark: rotbeam against Siconos 4.4 on the same physical case, in the same run.

What it measures
    The frictionless plastic pass of the base case (550 rpm, p = 2 %, 5 modes, rigid start,
    every impact plastic, mu = 0), i.e. `rotbeam run --set surface.friction=0
    --set impact.plastic_below_m_s=10`, from the first contact to theta = +90 deg, solved
      * by Siconos 4.4 (siconos.kernel): Moreau-Jean time stepping (theta = 0.5, fixed step h),
        NewtonImpactNSL(e = 0), one frictionless unilateral constraint y = d - X_tip >= 0
        (LagrangianRheonomousR, h(q, t)), LCP at velocity level. The model (M(q) and the
        non-linear forces of docs/model.md §3) is written here in numpy, independently of rotbeam,
        and handed to Siconos as Python overrides of LagrangianDS (computeMass, computeFInt,
        computeFGyr and their exact analytic Jacobians);
      * by the rotbeam CLI (adaptive event-driven scheme, defaults) and two variants
        (simulation.integrating_factor=false, simulation.end_when_clear=true).
    For each: CPU time and wall time (median of --repeats runs), last separation angle, peak
    sustained normal force, total normal impulse, counts of impacts / contact episodes, and the
    ratio Siconos / rotbeam of the times. rotbeam's CPU time is the child's rusage (os.wait4,
    user + system); Siconos's is time.process_time() of this process around the simulation
    (model set-up and per-step bookkeeping in Python included; the verification is not timed).
    The rigid turn before the first contact is analytic in both (rotbeam: rigid start; here the
    Siconos run starts at theta* = -acos(d / (r_h + L)) with q = qdot = 0).

Install
    apt-get install python3-siconos        (Debian/Ubuntu; provides siconos.kernel for /usr/bin/python3)

Run
    /usr/bin/python3 bench/siconos_compare.py [--repeats 3] [--step 1e-6] [--rotbeam build/rotbeam]
                                              [--end-deg 90] [--json]
    (about 10 s of CPU per Siconos repeat at h = 1e-6, 29730 steps; rotbeam takes < 0.1 s per run;
    the verification of the numpy model, not timed, takes ~3 s). --end-deg shortens the pass for
    both tools (the output then says so).

Siconos answers, as defined in siconos_answers(): impacts = runs of steps with a positive impulse
(each opens with an impact), contact episodes = runs longer than one step, peak F_n = impulse / h
over the steps of a run after its impact step, last separation = end of the last such step.
"""
import argparse
import json
import math
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

# ---------------------------------------------------------------- the case (docs/configuration.md)
L, D, RHO, E, RH, RPM, NMODES, DEPTH = 0.0635, 5.08e-4, 7800.0, 2.2e11, 0.0635, 550.0, 5, 0.02
THETA0 = -math.pi / 2
ROTBEAM_CASE = ["--set", "surface.friction=0", "--set", "impact.plastic_below_m_s=10"]
VARIANTS = [("rotbeam (adaptive, defaults)", []),
            ("rotbeam integrating_factor=false", ["--set", "simulation.integrating_factor=false"]),
            ("rotbeam end_when_clear=true", ["--set", "simulation.end_when_clear=true"])]


# ---------------------------------------------------------------- modal basis (docs/model.md §2)
def cantilever_roots(n):
    """Roots of cos r cosh r = -1, by Newton on f(r) = cos r + sech r from (2i - 1) pi / 2."""
    roots = []
    for i in range(1, n + 1):
        r = (2 * i - 1) * math.pi / 2
        for _ in range(100):
            f = math.cos(r) + 1 / math.cosh(r)
            df = -math.sin(r) - math.tanh(r) / math.cosh(r)
            dr = f / df
            r -= dr
            if abs(dr) < 1e-15 * r:
                break
        roots.append(r)
    return np.array(roots)


def shapes(xi, r):
    """S, S', S'' (d/dxi) at points xi (shape (len(xi), n)), in an overflow-free form:
    S = a e^{-r(1-xi)} + b e^{-r xi} - cos(r xi) + s sin(r xi), a = e^r (1 - s) / 2, b = (1 + s) / 2."""
    x = np.asarray(xi)[:, None]
    em = np.exp(-r)
    s = (1 - em ** 2 - 2 * em * np.sin(r)) / (1 + em ** 2 + 2 * em * np.cos(r))
    a = (em + np.cos(r) + np.sin(r)) / (1 + 2 * em * np.cos(r) + em ** 2)
    b = 0.5 * (1 + s)
    e1, e2 = np.exp(-r * (1 - x)), np.exp(-r * x)
    c, sn = np.cos(r * x), np.sin(r * x)
    S = a * e1 + b * e2 - c + s * sn
    S1 = r * (a * e1 - b * e2 + sn + s * c)
    S2 = r ** 2 * (a * e1 + b * e2 + c - s * sn)
    return S, S1, S2


def gauss(a, b, panels, k=20):
    x, w = np.polynomial.legendre.leggauss(k)
    edges = np.linspace(a, b, panels + 1)
    xs = np.concatenate([(e1 - e0) / 2 * x + (e1 + e0) / 2 for e0, e1 in zip(edges[:-1], edges[1:])])
    ws = np.concatenate([(e1 - e0) / 2 * w for e0, e1 in zip(edges[:-1], edges[1:])])
    return xs, ws


class Model:
    """The filament of docs/model.md §2–§4 in numpy: M(q) qdd + fGyr(q, qd) + fInt(q) = Q."""

    def __init__(self, n=NMODES, rpm=RPM, depth=DEPTH):
        self.n = n
        self.omega = rpm * 2 * math.pi / 60
        self.rA = RHO * math.pi * D ** 2 / 4
        self.m = self.rA * L
        self.EI = E * math.pi * D ** 4 / 64
        self.d = RH + L - depth * L
        r = cantilever_roots(n)
        self.r = r
        panels = int(math.ceil(4 * r[-1] / 12)) + 4
        xs, ws = gauss(0.0, 1.0, panels)
        S, S1, S2 = shapes(xs, r)
        # normalisation check (docs/model.md §2): int S_i S_j = delta_ij, int S''_i S''_j = r^4 delta_ij
        self.orth_err = max(np.abs((S * ws[:, None]).T @ S - np.eye(n)).max(),
                            np.abs((S2 * ws[:, None]).T @ S2 / r[None, :] ** 4 - np.eye(n)).max())
        # ISP(xi_g) = int_0^xi_g S' S'^T, by Gauss on [0, xi_g] (same composite rule, scaled)
        gx, gw = np.polynomial.legendre.leggauss(20)
        edges = np.linspace(0, 1, panels + 1)
        ISP = np.empty((len(xs), n, n))
        full = [np.zeros((n, n))]
        for e0, e1 in zip(edges[:-1], edges[1:]):
            _, s1, _ = shapes((e1 - e0) / 2 * gx + (e1 + e0) / 2, r)
            full.append(full[-1] + (s1 * ((e1 - e0) / 2 * gw)[:, None]).T @ s1)
        for g, xg in enumerate(xs):
            p = min(int(xg * panels), panels - 1)
            e0 = edges[p]
            _, s1, _ = shapes((xg - e0) / 2 * gx + (xg + e0) / 2, r)
            ISP[g] = full[p] + (s1 * ((xg - e0) / 2 * gw)[:, None]).T @ s1
        P = np.einsum('gi,gj->gij', S2, S1) + np.einsum('gi,gj->gij', S1, S2)
        self.isp1 = full[-1]
        self.s1 = shapes(np.array([1.0]), r)[0][0]
        self.Imean = np.einsum('g,gij->ij', ws, ISP)
        self.Ixi = np.einsum('g,gij->ij', ws * xs, ISP)
        self.r4 = r ** 4
        A = np.einsum('g,gik,gjl->ikjl', ws, ISP, ISP)       # int ISP_ik ISP_jl
        Pp = np.einsum('g,gij,gkl->ijkl', ws, P, P)           # int P_ij P_kl
        B = np.einsum('g,gik,gj->ikj', ws, ISP, S)            # int ISP_ik S_j
        self.A, self.Pp, self.B = A, Pp, B
        # flattened views for matrix-vector contractions
        self.A_k = np.ascontiguousarray(A.transpose(1, 0, 2, 3).reshape(n, n ** 3))   # k | i j l
        self.A_jl = np.ascontiguousarray(A.reshape(n * n, n * n))                     # i k | j l
        self.Pp_kl = np.ascontiguousarray(Pp.reshape(n * n, n * n))                   # i j | k l
        self.Pp_j = np.ascontiguousarray(Pp.transpose(1, 0, 2, 3).reshape(n, n ** 3))  # j | i m l
        self.B_k = np.ascontiguousarray(B.transpose(1, 0, 2).reshape(n, n * n))       # k | i j
        self.B_j = np.ascontiguousarray(B.reshape(n * n, n))                          # i k | j
        self.B_i = np.ascontiguousarray(B.reshape(n, n * n))                          # j | k i
        self.Klin = RH / L * self.Imean + self.Ixi
        # for the energy check (quadrature data)
        self.xs, self.ws, self.S, self.ISP, self.S2n, self.Pn = xs, ws, S, ISP, S2, P
        om, m = self.omega, self.m
        self.K0 = m * om ** 2 * (self.Klin - np.eye(n)) + self.EI / L ** 3 * np.diag(self.r4)   # K(q = 0)
        self._key = None
        self.evaluations, self.eval_time = 0, 0.0   # numpy model evaluations (cache misses)

    # --- dynamics, all at once (the Siconos callbacks share one evaluation per (q, qd))
    def evaluate(self, q, v):
        key = q.tobytes() + v.tobytes()
        if key == self._key:
            return self._cache
        t_start = time.perf_counter()
        n, om, m, rA, EI = self.n, self.omega, self.m, self.rA, self.EI
        qq = np.outer(q, q).ravel()
        Zq = (q @ self.A_k).reshape(n, n, n)                 # Zq[i,j,l] = sum_k A_ikjl q_k
        Aqq = Zq @ q                                         # sum_kl A_ikjl q_k q_l -> [i,j]
        M = m * np.eye(n) + rA / L * Aqq
        Bq = (q @ self.B_k).reshape(n, n)                    # Bq[i,j] = sum_k B_ikj q_k
        G = rA * (Bq - Bq.T)
        W = (self.A_jl @ qq).reshape(n, n)                   # sum_jl A_ikjl q_j q_l -> [i,k]
        Avv = (self.A_jl @ np.outer(v, v).ravel()).reshape(n, n)
        fgyr = 2 * om * G @ v + rA / L * Avv @ q
        c = W @ q
        Zp = (self.Pp_kl @ qq).reshape(n, n)                 # sum_kl Pp_ijkl q_k q_l -> [i,j]
        b = Zp @ q
        fint = m * om ** 2 * (self.Klin @ q - c / (2 * L ** 2) - q) \
            + EI / L ** 3 * (self.r4 * q + b / (2 * L ** 2))
        # Jacobians (exact): d c_i/d q_m = W_im + 2 sum_kl A_ikml q_k q_l (A_ikjl = A_iklj)
        dc = W + 2 * Aqq
        db = Zp + 2 * (q @ self.Pp_j).reshape(n, n, n) @ q  # sum_jl Pp_ijml q_j q_l
        Jfint_q = m * om ** 2 * (self.Klin - dc / (2 * L ** 2) - np.eye(n)) \
            + EI / L ** 3 * (np.diag(self.r4) + db / (2 * L ** 2))
        Bv = (self.B_j @ v).reshape(n, n)                    # Bv[i,k] = sum_j B_ikj v_j
        Bv2 = (v @ self.B_i).reshape(n, n)                   # Bv2[k,i] = sum_j B_jki v_j
        Jgyr_q = 2 * om * rA * (Bv - Bv2.T) + rA / L * Avv
        Jgyr_v = 2 * om * G + 2 * rA / L * (Zq @ v)
        self._key = key
        self._cache = (M, fgyr, fint, Jfint_q, Jgyr_q, Jgyr_v)
        self.evaluations += 1
        self.eval_time += time.perf_counter() - t_start
        return self._cache

    def accel(self, q, v):
        M, fg, fi = self.evaluate(q, v)[:3]
        return np.linalg.solve(M, -fg - fi)

    # --- constraint y = d - X_tip >= 0 (y = -C of docs/model.md §4)
    def tip(self, q, t):
        th = THETA0 + self.omega * t
        xt = RH + L - q @ self.isp1 @ q / (2 * L)
        yt = self.s1 @ q
        return xt * math.cos(th) - yt * math.sin(th), xt * math.sin(th) + yt * math.cos(th), th

    def jacobi(self, q, v):
        """h = T2 - T0 + U by quadrature from the shapes (independent of the constant arrays)."""
        x = RH + L * self.xs - np.einsum('gij,i,j->g', self.ISP, q, q) / (2 * L)
        y = self.S @ q
        T0 = 0.5 * self.omega ** 2 * self.m * np.sum(self.ws * (x ** 2 + y ** 2))
        x2 = -np.einsum('gij,i,j->g', self.Pn, q, q) / (2 * L)   # d2x/dxi2
        y2 = self.S2n @ q
        U = 0.5 * self.EI / L ** 3 * np.sum(self.ws * (x2 ** 2 + y2 ** 2))
        M = self.evaluate(q, v)[0]
        return 0.5 * v @ M @ v - T0 + U


# ---------------------------------------------------------------- verification of the numpy model
def verify(model, rotbeam):
    out = {}
    n = model.n
    out['orthonormality_max_error'] = float(model.orth_err)
    M0 = model.evaluate(np.zeros(n), np.zeros(n))[0]
    out['M0_minus_m_identity'] = float(np.abs(M0 - model.m * np.eye(n)).max() / model.m)
    f = np.sqrt(np.sort(np.linalg.eigvalsh(model.K0 / model.m))) / (2 * math.pi)
    out['linear_frequencies_hz'] = [float(x) for x in f]
    try:
        res = subprocess.run([rotbeam, 'modes', '--json'], capture_output=True, text=True, timeout=60)
        js = json.loads(res.stdout)
        row = js['frequencies_hz'][[abs(s - RPM) < 1e-9 for s in js['speeds_rpm']].index(True)]
        out['rotbeam_frequencies_hz'] = row
        out['frequency_max_rel_diff'] = float(max(abs(a - b) / b for a, b in zip(f, row)))
    except Exception as exc:  # noqa: BLE001 - a report, not a failure
        out['rotbeam_frequencies_hz'] = 'unavailable: %s' % exc
    # Jacobians against central differences at a large deflection (tip ~ 15 mm)
    rng = np.random.default_rng(1)
    q = 5e-3 * rng.standard_normal(n) / np.arange(1, n + 1) ** 2
    v = 0.5 * rng.standard_normal(n)
    M, fg, fi, Jfq, Jgq, Jgv = [x.copy() for x in model.evaluate(q, v)]
    num = np.zeros((3, n, n))
    for k in range(n):
        e = np.zeros(n)
        e[k] = 1e-7 * max(1e-3, abs(q[k]))
        a, b = model.evaluate(q + e, v), model.evaluate(q - e, v)
        num[0][:, k] = (a[2] - b[2]) / (2 * e[k])
        num[1][:, k] = (a[1] - b[1]) / (2 * e[k])
        e[k] = 1e-6
        a, b = model.evaluate(q, v + e), model.evaluate(q, v - e)
        num[2][:, k] = (a[1] - b[1]) / (2 * e[k])
    out['jacobian_max_rel_error'] = float(max(np.abs(num[i] - J).max() / np.abs(J).max()
                                              for i, J in enumerate((Jfq, Jgq, Jgv))))
    # Jacobi integral in free flight (RK4, 1 ms from a flexible state): tests Psi against T and U
    q0, v0 = np.array([2e-3, -3e-4, 1e-4, 0, 0])[:n], np.array([2.0, 0.5, 0.1, 0, 0])[:n]
    y, h = np.concatenate([q0, v0]), 1e-7   # 10000 steps: 1 ms
    f = lambda s: np.concatenate([s[n:], model.accel(s[:n], s[n:])])  # noqa: E731
    j0 = model.jacobi(y[:n], y[n:])
    for _ in range(10000):
        k1 = f(y); k2 = f(y + h / 2 * k1); k3 = f(y + h / 2 * k2); k4 = f(y + h * k3)  # noqa: E702
        y = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    jmax = abs(model.jacobi(y[:n], y[n:]) - j0)
    out['jacobi_scale_J'] = float(abs(0.5 * v0 @ model.evaluate(q0, v0)[0] @ v0))
    out['jacobi_drift_over_T2'] = float(jmax / out['jacobi_scale_J'])
    return out


# ---------------------------------------------------------------- Siconos
def run_siconos(step, end_deg, n=NMODES):
    import siconos.kernel as sk

    model = Model(n)
    om = model.omega
    theta_star = -math.acos(model.d / (RH + L))
    t0 = (theta_star - THETA0) / om
    t_end = (math.radians(end_deg) - THETA0) / om

    class Filament(sk.LagrangianDS):
        """The model as a LagrangianDS: M q'' + fGyr(q, v) + fInt(q) = p (Siconos's signs).
        Siconos calls these with (q), (q, v), (t, q, v) or only (t): missing q, v are the DS's
        current (Newton iterate) state."""

        def __init__(self):
            sk.LagrangianDS.__init__(self, np.zeros(n), np.zeros(n), model.m * np.eye(n))
            self.setFIntPtr(np.zeros(n))
            self.setFGyrPtr(np.zeros(n))
            self.setJacobianFIntqPtr(np.zeros((n, n)))
            self.setJacobianFIntqDotPtr(np.zeros((n, n)))
            self.setJacobianFGyrqPtr(np.zeros((n, n)))
            self.setJacobianFGyrqDotPtr(np.zeros((n, n)))
            # without these two the Newton matrix of Moreau-Jean is W = M (Jacobians never called)
            self.keep = (sk.SimpleMatrix(n, n), sk.SimpleMatrix(n, n))
            self._jacobianqForces, self._jacobianqDotForces = self.keep

        def _ev(self, args):
            arrs = [x for x in args if isinstance(x, np.ndarray)]
            q = arrs[0] if len(arrs) >= 1 else np.asarray(self.q())
            v = arrs[1] if len(arrs) >= 2 else np.asarray(self.velocity())
            return model.evaluate(q, v)

        def computeMass(self, *a):
            self.mass()[:, :] = self._ev(a)[0]

        def computeFInt(self, *a):
            self.fInt()[:] = self._ev(a)[2]

        def computeFGyr(self, *a):
            self.fGyr()[:] = self._ev(a)[1]

        def computeJacobianFIntq(self, *a):
            self.jacobianFIntq()[:, :] = self._ev(a)[3]

        def computeJacobianFIntqDot(self, *a):
            pass                                    # stays zero

        def computeJacobianFGyrq(self, *a):
            self.jacobianFGyrq()[:, :] = self._ev(a)[4]

        def computeJacobianFGyrqDot(self, *a):
            self.jacobianFGyrqDot()[:, :] = self._ev(a)[5]

    class Plane(sk.LagrangianRheonomousR):
        """y = h(q, t) = d - X_tip(q, t) >= 0; dy/dt = jachq(q, t) v + hDot(q, t), hDot = omega Y_tip.
        Work-arounds for Siconos 4.4's Python bindings: hDot is not allocated without a C plugin;
        C() (= jachq) reaches MoreauJeanOSI::computeFreeOutput through the SWIG director as a
        dangling matrix (segmentation fault once the constraint is active), so C() returns a
        persistent SimpleMatrix kept equal to jachq."""

        def __init__(self):
            sk.LagrangianRheonomousR.__init__(self)
            self.keep = (sk.SiconosVector(1), sk.SimpleMatrix(1, n))
            self._hDot = self.keep[0]
            self.Cmat = self.keep[1]

        def computeh(self, t, q, z, y):
            X, _, _ = model.tip(np.asarray(q), t)
            y[0] = model.d - X

        def computeJachq(self, t, q, z):
            q = np.asarray(q)
            th = THETA0 + om * t
            row = math.cos(th) / L * (model.isp1 @ q) + math.sin(th) * model.s1
            self.jachq()[0, :] = row
            for j in range(n):
                self.Cmat.setValue(0, j, row[j])

        def computehDot(self, t, q, z):
            _, Y, _ = model.tip(np.asarray(q), t)
            self.hDot()[0] = om * Y

        def C(self):
            return self.Cmat

    ds = Filament()
    nsds = sk.NonSmoothDynamicalSystem(t0, t_end)
    nsds.insertDynamicalSystem(ds)
    rel = Plane()
    inter = sk.Interaction(sk.NewtonImpactNSL(0.0), rel)
    nsds.link(inter, ds)
    osi = sk.MoreauJeanOSI(0.5)
    lcp = sk.LCP()
    sim = sk.TimeStepping(nsds, sk.TimeDiscretisation(t0, step), osi, lcp)
    sim.setNewtonTolerance(1e-10)
    sim.setNewtonMaxIteration(20)

    nsteps = int(round((t_end - t0) / step))
    imp = np.zeros(nsteps)      # impulse of the step (lambda(1)), N s
    vpre = np.zeros(nsteps)     # constraint velocity at the start of the step
    tend = np.zeros(nsteps)
    newton = np.zeros(nsteps, dtype=np.int32)
    ymin = 0.0
    k = 0
    ydot_prev = om * model.tip(np.zeros(n), t0)[1]   # dy/dt at the start: omega Y_tip (< 0)
    while sim.hasNextEvent() and k < nsteps:
        sim.computeOneStep()
        lam = inter.lambda_(1)
        imp[k] = lam[0] if lam is not None else 0.0
        vpre[k] = ydot_prev
        tend[k] = sim.nextTime()
        newton[k] = sim.getNewtonNbIterations()
        ydot_prev = float(inter.y(1)[0])
        ymin = min(ymin, float(inter.y(0)[0]))
        sim.nextStep()
        k += 1
    imp, vpre, tend = imp[:k], vpre[:k], tend[:k]
    return dict(model=model, t0=t0, theta_star_deg=math.degrees(theta_star), impulses=imp, vpre=vpre,
                tend=tend, steps=k, ymin=ymin, evaluations=model.evaluations, eval_time=model.eval_time, newton_mean=float(newton[:k].mean()),
                newton_max=int(newton[:k].max()))


def siconos_answers(res, step):
    """Contact runs = maximal runs of consecutive steps with a positive impulse (lambda(1) > 0).
    Each run opens with an impact (the tip arrives from free flight; e = 0 so no impact happens
    inside a run). A run of one step is a lift-off (rotbeam's 'lift_off': the plastic impact leaves
    the tip pulling), a longer run is a contact episode. Sustained force = impulse / h over the
    steps of a run after its first (impact) step; peak F_n is their maximum. Last separation =
    end of the last step with a positive impulse."""
    imp, tend = res['impulses'], res['tend']
    om = res['model'].omega
    pos = imp > 0.0
    starts = np.nonzero(pos & ~np.concatenate([[False], pos[:-1]]))[0]
    ends = np.nonzero(pos & ~np.concatenate([pos[1:], [False]]))[0]
    lengths = ends - starts + 1
    sustained = pos.copy()
    sustained[starts] = False
    last_sep = math.degrees(THETA0 + om * tend[ends[-1]]) if len(ends) else float('nan')
    return dict(last_separation_deg=last_sep,
                peak_normal_force_n=float(imp[sustained].max() / step) if sustained.any() else 0.0,
                normal_impulse_n_s=float(imp.sum()),
                first_impact_impulse_n_s=float(imp[0]),
                impacts=int(len(starts)), contact_episodes=int((lengths > 1).sum()),
                lift_offs=int((lengths == 1).sum()),
                contact_time_s=float(sustained.sum() * step),
                impact_speeds_m_s=[float(-res['vpre'][k]) for k in starts],
                max_penetration_m=float(-res['ymin']),
                steps=int(res['steps']), newton_mean=res['newton_mean'], newton_max=res['newton_max'],
                model_evaluations=int(res['evaluations']), model_eval_wall_s=float(res['eval_time']))


# ---------------------------------------------------------------- rotbeam
def run_rotbeam(exe, extra, end_deg):
    tmp = tempfile.mkdtemp(prefix='rotbeam_siconos_')
    try:
        cmd = [exe, 'run'] + ROTBEAM_CASE + extra + ['-o', os.path.join(tmp, 'out'), '--quiet']
        if end_deg != 90.0:
            cmd[2:2] = ['--set', 'simulation.end_angle_deg=%r' % end_deg]
        w0 = time.perf_counter()
        with open(os.path.join(tmp, 'stderr'), 'w') as err:
            p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err)
            _, status, ru = os.wait4(p.pid, 0)
        wall = time.perf_counter() - w0
        p.returncode = os.waitstatus_to_exitcode(status)
        if p.returncode != 0:
            with open(os.path.join(tmp, 'stderr')) as err:
                return dict(error='exit %d: %s' % (p.returncode, err.read().strip()[:200]))
        with open(os.path.join(tmp, 'out', 'summary.json')) as fh:
            s = json.load(fh)
        return dict(cpu=ru.ru_utime + ru.ru_stime, wall=wall, last_separation_deg=s['last_separation_deg'],
                    peak_normal_force_n=s['peak_normal_force_n'], normal_impulse_n_s=s['normal_impulse_n_s'],
                    impacts=s['impacts'], contact_episodes=s['contact_episodes'], steps=s.get('steps'),
                    contact_time_s=s.get('contact_time_s'))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


# ---------------------------------------------------------------- main
def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--repeats', type=int, default=3, help='runs per tool; the median time is reported')
    ap.add_argument('--step', type=float, default=1e-6, help='Siconos time step h [s]')
    ap.add_argument('--rotbeam', default=os.path.join(os.path.dirname(here), 'build', 'rotbeam'),
                    help='rotbeam CLI (default: <repo>/build/rotbeam)')
    ap.add_argument('--end-deg', type=float, default=90.0,
                    help='end angle of the pass [deg] for both tools (default 90: the whole pass)')
    ap.add_argument('--json', action='store_true', help='print one JSON object instead of the table')
    args = ap.parse_args()

    model = Model()
    ver = verify(model, args.rotbeam)

    rows = []
    # rotbeam first (fast), then Siconos; one simulation at a time
    for name, extra in VARIANTS:
        runs = [run_rotbeam(args.rotbeam, extra, args.end_deg) for _ in range(args.repeats)]
        if 'error' in runs[0]:
            rows.append(dict(tool=name, skipped=runs[0]['error']))
            continue
        r = dict(runs[0])
        r.update(tool=name, cpu=statistics.median(x['cpu'] for x in runs),
                 wall=statistics.median(x['wall'] for x in runs))
        rows.append(r)
    sic = []
    for _ in range(args.repeats):
        c0, w0 = time.process_time(), time.perf_counter()
        res = run_siconos(args.step, args.end_deg)
        sic.append((time.process_time() - c0, time.perf_counter() - w0, res))
    ans = siconos_answers(sic[0][2], args.step)
    ans.update(tool='Siconos 4.4 Moreau-Jean h=%g' % args.step,
               cpu=statistics.median(x[0] for x in sic), wall=statistics.median(x[1] for x in sic))
    rows.insert(0, ans)
    for r in rows[1:]:
        if 'cpu' in r:
            r['siconos_over_this_cpu'] = ans['cpu'] / r['cpu']
            r['siconos_over_this_wall'] = ans['wall'] / r['wall']

    shortened = args.end_deg != 90.0
    out = dict(case='550 rpm, p = 2 %, 5 modes, mu = 0, every impact plastic (e = 0), rigid start',
               span_deg=[sic[0][2]['theta_star_deg'], args.end_deg], span_shortened=shortened,
               repeats=args.repeats, siconos_step_s=args.step, verification=ver, rows=rows)
    if args.json:
        json.dump(out, sys.stdout, indent=1, default=float)
        print()
        return
    print('Case: %s; from theta* = %.4f deg to %g deg%s; median of %d run(s).'
          % (out['case'], out['span_deg'][0], args.end_deg,
             ' (SPAN SHORTENED: not the whole pass)' if shortened else '', args.repeats))
    print()
    print('| tool | CPU [s] | wall [s] | last separation [deg] | peak F_n [N] | normal impulse [mN s] '
          '| impacts / episodes | Siconos / this, CPU | Siconos / this, wall |')
    print('|---|---|---|---|---|---|---|---|---|')
    for r in rows:
        if 'skipped' in r:
            print('| %s | skipped: %s | | | | | | | |' % (r['tool'], r['skipped']))
            continue
        print('| %s | %.4g | %.4g | %.6f | %.5f | %.6f | %d / %d | %s | %s |' % (
            r['tool'], r['cpu'], r['wall'], r['last_separation_deg'], r['peak_normal_force_n'],
            1e3 * r['normal_impulse_n_s'], r['impacts'], r['contact_episodes'],
            '%.4g' % r['siconos_over_this_cpu'] if 'siconos_over_this_cpu' in r else '',
            '%.4g' % r['siconos_over_this_wall'] if 'siconos_over_this_wall' in r else ''))
    print()
    print('Siconos: %d steps, Newton iterations per step mean %.4f max %d; %d lift-off(s) (one-step '
          'contact runs), contact time %.4g ms (rotbeam %.4g ms), max penetration %.3g m; %d evaluations '
          'of the numpy model took %.3g s of the Siconos wall time (Python callbacks: the SWIG director '
          'overhead comes on top). Impacts = contact runs (each opens with an impact), episodes = runs '
          'longer than one step, peak F_n = impulse/h over a run\'s steps after its impact step.'
          % (ans['steps'], ans['newton_mean'], ans['newton_max'], ans['lift_offs'],
             1e3 * ans['contact_time_s'], 1e3 * (rows[1].get('contact_time_s') or float('nan')),
             ans['max_penetration_m'], ans['model_evaluations'], ans['model_eval_wall_s']))
    f = ver['linear_frequencies_hz']
    print('Numpy model checks (untimed): orthonormality error %.1e; M(0) = m*1 to %.1e; linear frequencies '
          'at %g rpm %s Hz, max relative difference from `rotbeam modes --json` %s; exact Jacobians vs '
          'central differences %.1e; Jacobi integral drift over 1 ms of free flight (RK4) %.1e of T2.'
          % (ver['orthonormality_max_error'], ver['M0_minus_m_identity'], RPM,
             ', '.join('%.4f' % x for x in f),
             '%.1e' % ver['frequency_max_rel_diff'] if 'frequency_max_rel_diff' in ver
             else ver['rotbeam_frequencies_hz'],
             ver['jacobian_max_rel_error'], ver['jacobi_drift_over_T2']))


if __name__ == '__main__':
    main()
