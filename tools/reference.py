"""Independent reference for gearshock's time integration.

A from-scratch NumPy implementation of docs/model.md (not a port of the
Rust code: mesh vectors are built densely, the mass matrix is inverted with
numpy, the ODE is integrated by scipy's DOP853 at rtol 1e-12 without event
location) used to produce test fixtures in crates/solver/tests/fixtures/.

Usage: python3 tools/reference.py > crates/solver/tests/fixtures/reference.json
"""
import json
import sys

import numpy as np
from scipy.integrate import solve_ivp


def ravigneaux(backlash_um=100.0, te_sin_um=20.0, v=0.3, xi=0.06, N=3):
    m, al = 4e-3, np.radians(20.0)
    zs1, zs2, za, zr = 36, 48, 21, 84
    zb = (zr - zs2) // 2
    R = lambda z: m * z / 2
    rho = lambda z: R(z) * np.cos(al)
    rs1, rs2, ra, rb, rr = rho(zs1), rho(zs2), rho(za), rho(zb), rho(zr)
    rca, rcb = R(zs1) + R(za), R(zs2) + R(zb)
    Js1, Js2, Jr, Jc, Ja, Jb = 0.015, 0.059, 0.152, 0.08, 0.0019, 0.0022
    ma, mb = 1.997, 3.139
    n = 4 + 2 * N
    s1, s2, c, r = 0, 1, 2, 3
    A = lambda i: 4 + i
    B = lambda i: 4 + N + i
    # Mass matrix from the kinetic energy, built by differentiating T twice
    # numerically would be overkill: write the quadratic form directly.
    M = np.zeros((n, n))
    M[s1, s1], M[s2, s2], M[r, r] = Js1, Js2, Jr
    M[c, c] = Jc + N * ma * rca**2 + N * mb * rcb**2
    for i in range(N):
        for idx, J in ((A(i), Ja), (B(i), Jb)):
            # 1/2 J (thc' + phi')^2 -> J on (c,c), (c,idx), (idx,c), (idx,idx)
            M[c, c] += J
            M[c, idx] += J
            M[idx, c] += J
            M[idx, idx] += J
    W, te = [], []
    for i in range(N):
        w = np.zeros(n); w[s1] = rs1; w[c] = -rs1; w[A(i)] = ra; W.append(w); te.append(te_sin_um * 1e-6)
    for i in range(N):
        w = np.zeros(n); w[s2] = rs2; w[c] = -rs2; w[B(i)] = rb; W.append(w); te.append(0.0)
    for i in range(N):
        w = np.zeros(n); w[A(i)] = -ra; w[B(i)] = -rb; W.append(w); te.append(0.0)
    for i in range(N):
        w = np.zeros(n); w[B(i)] = rb; w[r] = -rr; w[c] = rr; W.append(w); te.append(0.0)
    W = np.array(W)
    te = np.array(te)
    Minv = np.linalg.inv(M)
    me = 1.0 / np.einsum('ji,ik,jk->j', W, Minv, W)
    km = 1e9 * np.ones(len(W))
    cd = 2 * xi * np.sqrt(km * me)
    Ksup = np.zeros((n, n)); Ksup[r, r] = 1e9 * rr**2
    tau = np.zeros(n); tau[s1] = 2000.0
    u = np.zeros(n); u[s1] = 1 - zr / zs1; u[s2] = 1 + zr / zs2; u[c] = 1.0
    for i in range(N):
        u[A(i)] = zr / za; u[B(i)] = -zr / zb
    tau[s2] = -tau[s1] * u[s1] / u[s2]
    b = backlash_um * 1e-6
    omega_ref = np.sqrt(km[0] / me[0])
    return dict(M=M, Minv=Minv, W=W, te=te, km=km, cd=cd, Ksup=Ksup, tau=tau, b=b, v=v, omega_ref=omega_ref, u=u, n=n)


def static_state(s):
    # K q = tau + sum w k b (all drive contact), minimum-norm in the M metric:
    # solve with the rigid mode pinned by an augmented Lagrange system.
    n = s['n']
    K = s['Ksup'] + (s['W'].T * s['km']) @ s['W']
    f = s['tau'] + s['W'].T @ (s['km'] * s['b'])
    Mu = s['M'] @ s['u']
    aug = np.block([[K, Mu[:, None]], [Mu[None, :], np.zeros((1, 1))]])
    sol = np.linalg.solve(aug, np.concatenate([f, [0.0]]))
    return np.concatenate([sol[:n], np.zeros(n)])


def rhs_factory(s, omega):
    W, Minv, n = s['W'], s['Minv'], s['n']
    def rhs(t, y):
        q, qd = y[:n], y[n:]
        d, dd = W @ q, W @ qd
        e = s['te'] * np.sin(omega * t)
        de = s['te'] * omega * np.cos(omega * t)
        x = d - e
        g = np.where(x > s['b'], x - s['b'], np.where(x < -s['b'], x + s['b'], 0.0))
        k = s['km'] * (1 + s['v'] * np.cos(omega * t))
        F = k * g + s['cd'] * (dd - de)
        acc = Minv @ (s['tau'] - s['Ksup'] @ q - W.T @ F)
        return np.concatenate([qd, acc])
    return rhs


def run(Omega, periods, **kw):
    s = ravigneaux(**kw)
    omega = Omega * s['omega_ref']
    T = 2 * np.pi / omega
    y0 = static_state(s)
    t_eval = np.arange(periods + 1) * T
    sol = solve_ivp(rhs_factory(s, omega), (0, periods * T), y0, method='DOP853',
                    rtol=1e-12, atol=1e-16, t_eval=t_eval, max_step=T / 40)
    d = s['W'] @ sol.y[:s['n']]
    dd = s['W'] @ sol.y[s['n']:]
    return dict(omega=Omega, periods=periods, kw=kw,
                poincare_delta_s1a1_m=d[0].tolist(), poincare_velocity_s1a1_m_s=dd[0].tolist(),
                poincare_delta_rb1_m=d[9].tolist())


if __name__ == '__main__':
    cases = [
        run(0.5, 40),
        run(1.2, 40),
        run(0.84, 40, backlash_um=200.0, te_sin_um=30.0),
    ]
    json.dump(dict(source='tools/reference.py (scipy DOP853, rtol 1e-12, no event location)', cases=cases),
              sys.stdout, indent=1)
