#!/usr/bin/python3
"""Discrete Stokes model of cosimFoam's gas operator (UEqn.H + pEqn.H) with one loaded cell,
on a periodic N^3 lattice of cubes (side D), odd N (no exact checkerboard null modes).

Unknowns: face superficial velocities w_a (one per face, face (c,a) between c and c+e_a),
cell pressures p, a uniform body force gam along z (the periodic counter-force; it plays the
role of rho g / the mean pressure gradient) fixed by the mean z flux = u_up.

Cell velocity   U_a[c] = (w_a[c] + w_a[c-e_a]) / (2 eps[c])              (reconstructFaceFlux/eps)
Viscous         L U   = mu sum_a D_a diag(ef_a) Gr_a U, ef_a = (eps[c]+eps[c+e_a])/2
dev2 term       Dev_j = sum_i g_i(eps mu g_j U_i) - 2/3 g_j(eps mu sum_k g_k U_k), g = central diff
R               = H - A_g U = ar (U_old - U) + KUp + Dev(U_build) + L U
face balance    I(A/eps^2) w = I(A_g/eps^2) w' + I(R/eps) - snGrad p + gam e_z
continuity      sum_a D_a w_a = 0
A = ar + av + Kx (ar = eps rho/dt, av = mu sum_f ef_f / D^2), A_g = A - Kx.

mode 'steady' : converged steady state (w = w', U_old = U): I(Kx/eps^2) w = I(R/eps) - snGrad p + gam
mode 'pimple' : the actual time step (Euler, 2 outer x 2 correctors, momentum predictor
                A U - N U = b + rec(ef (gam e_z - snGrad p))), stepped to its time-steady state.

It answers why the gas of scenarios/verify-wake answers a force more when the force is not all
"implicit K times the sampled slip" (docs/verification.md section 4): for each form in which
the drag reaches the gas (implicit K; K plus an explicit offset; an implicit K_eff) it prints
the disturbance of the loaded cell per unit force, d / (G F), and its ratio to the implicit-K
form. Stokes flow (Re 0.015), no convection, incompressible, periodic box (the absolute d / (G F)
carries the periodic images; the ratios change by at most 0.1 point from N = 9 to 13).

Run: /usr/bin/python3 scenarios/verify-wake/faceop.py N [cells of n_d diameters ...]
     e.g. faceop.py 9 2 3 5   (odd N; N = 13 takes about 4 min for the three sizes)
"""
import argparse
import sys
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl

MU, RHO, DT, DP = 1.8e-5, 1.16, 2e-4, 20e-6
KST = 3 * np.pi * MU * DP          # 3.393e-9
WT = 1.2111e-2
CINF = 0.2527310098586630
CV = 2.0 / 3.0 * CINF


class Lattice:
    def __init__(self, N, D, epsP):
        self.N, self.D = N, D
        n = self.n = N ** 3
        idx = np.arange(n).reshape(N, N, N)
        self.P = idx[N // 2, N // 2, N // 2]
        I = sp.identity(n, format='csr')
        def shift(a, s):
            cols = np.roll(idx, -s, axis=a).ravel()
            return sp.csr_matrix((np.ones(n), (np.arange(n), cols)), shape=(n, n))
        self.Sp = [shift(a, 1) for a in range(3)]
        self.Sm = [shift(a, -1) for a in range(3)]
        eps = np.ones(n); eps[self.P] = epsP
        self.eps = eps
        self.Ia = [0.5 * (I + self.Sp[a]) for a in range(3)]          # cell -> face a
        self.Gr = [(self.Sp[a] - I) / D for a in range(3)]            # snGrad on face a
        self.Dv = [(I - self.Sm[a]) / D for a in range(3)]            # face a -> cell div
        self.Rc = [sp.diags(0.5 / eps) @ (I + self.Sm[a]) for a in range(3)]   # face a -> U_a
        self.Rf = [0.5 * (I + self.Sm[a]) for a in range(3)]          # face a -> cell mean (reconstruct)
        self.g = [(self.Sp[a] - self.Sm[a]) / (2 * D) for a in range(3)]
        self.ef = [self.Ia[a] @ eps for a in range(3)]
        L = sum(self.Dv[a] @ sp.diags(self.ef[a]) @ self.Gr[a] for a in range(3)) * MU
        self.L = L.tocsr()
        self.av = -self.L.diagonal()
        E = sp.diags(eps * MU)
        B = [[None] * 3 for _ in range(3)]
        for j in range(3):
            for i in range(3):
                B[j][i] = self.g[i] @ E @ self.g[j] - 2.0 / 3.0 * self.g[j] @ E @ self.g[i]
        self.Dev = sp.bmat(B, format='csr')
        self.Lb = sp.block_diag([self.L] * 3, format='csr')
        self.Rec = sp.block_diag(self.Rc, format='csr')


def steady(lat, Kc, dev=True):
    """Converged steady state. Returns U_Pz per unit u_up (S=0) and per unit S (u_up=0), gam's."""
    n = lat.n
    Kx = np.zeros(n); Kx[lat.P] = Kc
    ieps = sp.diags(1.0 / lat.eps)
    M = lat.Lb + (lat.Dev if dev else 0 * lat.Dev)
    MR = (M @ lat.Rec).tocsr()
    rows = []
    for a in range(3):
        KF = sp.diags(lat.Ia[a] @ (Kx / lat.eps ** 2))
        blk = -(lat.Ia[a] @ ieps) @ MR[a * n:(a + 1) * n, :]
        blk = blk.tolil()
        blk[:, a * n:(a + 1) * n] = blk[:, a * n:(a + 1) * n] + KF
        g_col = sp.csr_matrix((-np.ones(n), (np.arange(n), np.zeros(n))), shape=(n, 1)) if a == 2 \
            else sp.csr_matrix((n, 1))
        rows.append(sp.hstack([blk.tocsr(), lat.Gr[a], g_col]))
    cont = sp.hstack(lat.Dv + [sp.csr_matrix((n, n)), sp.csr_matrix((n, 1))]).tolil()
    cont[0, :] = 0
    cont[0, 3 * n] = 1.0          # p_0 = 0 (continuity of cell 0 is redundant)
    cons = sp.hstack([sp.csr_matrix((1, 2 * n)), sp.csr_matrix(np.ones((1, n))),
                      sp.csr_matrix((1, n)), sp.csr_matrix((1, 1))])
    A = sp.vstack(rows + [cont.tocsr(), cons]).tocsc()
    lu = spl.splu(A)
    out = {}
    for name, (u, S) in {'u': (1.0, 0.0), 'S': (0.0, 1.0)}.items():
        rhs = np.zeros(4 * n + 1)
        Sv = np.zeros(n); Sv[lat.P] = S
        rhs[2 * n:3 * n] = lat.Ia[2] @ (Sv / lat.eps)
        rhs[-1] = n * u
        x = lu.solve(rhs)
        w = x[:3 * n]
        U = lat.Rec @ w
        out[name] = (U[2 * n + lat.P], x[-1], U, w)
    return out


def pimple(lat, Kc, u_up, S, steps=300, state=None, dev=True, nOuter=2, nCorr=2, tol=1e-11):
    """Time-steady state of the PIMPLE step (Stokes, incompressible). Returns U_Pz, gam, state."""
    n = lat.n
    Kx = np.zeros(n); Kx[lat.P] = Kc
    Sv = np.zeros(3 * n); Sv[2 * n + lat.P] = S
    ar = lat.eps * RHO / DT
    A = ar + lat.av + Kx
    Ag = ar + lat.av
    af = [lat.Ia[a] @ (A / lat.eps ** 2) for a in range(3)]
    agf = [lat.Ia[a] @ (Ag / lat.eps ** 2) for a in range(3)]
    pred = spl.splu((sp.diags(ar + Kx) - lat.L).tocsc())
    # pressure system: sum_a Dv_a (B_a + gam e_z - Gr_a p)/af_a = 0, constraint sum w_z = n u_up
    Pm = -sum(lat.Dv[a] @ sp.diags(1 / af[a]) @ lat.Gr[a] for a in range(3))
    gc = lat.Dv[2] @ (1 / af[2])
    Pb = sp.bmat([[Pm, sp.csr_matrix(gc[:, None])],
                  [sp.csr_matrix(-(sp.diags(1 / af[2]) @ lat.Gr[2]).sum(axis=0)),
                   sp.csr_matrix([[np.sum(1 / af[2])]])]]).tolil()
    Pb[0, :] = 0; Pb[0, 0] = 1.0
    plu = spl.splu(Pb.tocsc())
    ieps = 1.0 / lat.eps
    if state is None:
        w = np.zeros(3 * n); w[2 * n:] = u_up
        p = np.zeros(n); gam = 0.0
    else:
        w, p, gam = [s.copy() if hasattr(s, 'copy') else s for s in state]
    U = lat.Rec @ w
    hist = []
    for it in range(steps):
        Uold = U.copy()
        for o in range(nOuter):
            devb = lat.Dev @ U if dev else 0 * U
            b = np.tile(ar, 3) * Uold + Sv + devb
            ff = [lat.ef[a] * ((gam if a == 2 else 0.0) - lat.Gr[a] @ p) for a in range(3)]
            rhs = b + np.concatenate([lat.Rf[a] @ ff[a] for a in range(3)])
            U = np.concatenate([pred.solve(rhs[a * n:(a + 1) * n]) for a in range(3)])
            for c in range(nCorr):
                R = np.tile(ar, 3) * (Uold - U) + Sv + devb + lat.Lb @ U
                Bf = [agf[a] * w[a * n:(a + 1) * n] + lat.Ia[a] @ (R[a * n:(a + 1) * n] * ieps)
                      for a in range(3)]
                rp = np.zeros(n + 1)
                rp[:n] = -sum(lat.Dv[a] @ (Bf[a] / af[a]) for a in range(3))
                rp[0] = 0.0
                rp[n] = n * u_up - np.sum(Bf[2] / af[2])
                x = plu.solve(rp)
                p, gam = x[:n], x[n]
                w = np.concatenate([(Bf[a] + (gam if a == 2 else 0.0) - lat.Gr[a] @ p) / af[a]
                                    for a in range(3)])
                U = lat.Rec @ w
        hist.append(U[2 * n + lat.P])
        if it > 5 and abs(hist[-1] - hist[-2]) < tol * max(abs(u_up), 1e-3):
            break
    return U[2 * n + lat.P], gam, (w, p, gam), len(hist)


def geometry(nd):
    D = nd * DP
    epsP = 1 - np.pi / 6 * (DP / D) ** 3
    return D, epsP


def forms(resp, D, epsP, Kmul3=5.0):
    """resp(Kc) -> (a, b): U_Pz = a u_up + b S. Returns d/(G F) per form (G = c_v/(eps_f mu D))."""
    V = D ** 3
    G = CV / (0.5 * (1 + epsP) * MU * D)
    u = WT
    res = {}
    # 1: implicit K times sampled slip (held sphere, v = 0: KUp = 0)
    Kc = KST / V; a, b = resp(Kc)
    UP = a * u; F = V * Kc * UP
    res['implicit K'] = ((u - UP) / (G * F), F / (KST * u))
    # 4: implicit K + explicit extra K (u_und - u_f) = K G F (on the gas: S = -K G F / V)
    # F = V (Kc UP - S), S = -K G F/V, UP = a u + b S
    M = np.array([[1.0, -V * Kc, V], [KST * G / V, 0.0, 1.0], [0.0, 1.0, -b]])
    F4, UP4, S4 = np.linalg.solve(M, [0.0, 0.0, a * u])
    res['K + explicit K(u_und-u_f)'] = ((u - UP4) / (G * F4), F4 / (KST * u), -S4 * V / (Kc * UP4 * V))
    # 2, 3: implicit K_eff, KUp = K_eff v_eff/V so that F = K w_t
    KE = 1.0 / (1.0 - KST * G)
    for lab, m in (('K_eff %.2f K' % KE, KE), ('K_eff %.2f K (0.9x)' % (0.9 * KE), 0.9 * KE)):
        Kc = m * KST / V; a, b = resp(Kc)
        S = (Kc * a * u * V - KST * u) / (V * (1 - Kc * b))
        UP = a * u + b * S; F = V * (Kc * UP - S)
        res[lab] = ((u - UP) / (G * F), F / (KST * u))
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('N', type=int, help='odd number of cells along each side of the periodic box')
    ap.add_argument('nd', type=int, nargs='+', help='cell size in sphere diameters (2 3 5)')
    args = ap.parse_args()
    if args.N % 2 == 0:
        sys.exit('faceop.py: N must be odd (an even lattice has checkerboard face modes)')
    for nd in args.nd:
        D, epsP = geometry(nd)
        lat = Lattice(args.N, D, epsP)
        G = CV / (0.5 * (1 + epsP) * MU * D)
        for mode in (['steady'] if args.N <= 9 else []) + ['pimple']:
            cache = {}

            def resp(Kc):
                if Kc not in cache:
                    if mode == 'steady':
                        o = steady(lat, Kc)
                        cache[Kc] = (o['u'][0], o['S'][0])
                    else:
                        cache[Kc] = (pimple(lat, Kc, 1.0, 0.0, steps=800)[0],
                                     pimple(lat, Kc, 0.0, 1.0, steps=800)[0])
                return cache[Kc]

            r = forms(resp, D, epsP)
            base = r['implicit K'][0]
            for k, v in r.items():
                print('N %d  %d d  %-7s %-28s d/GF %.4f  ratio %.4f  F/(K w_t) %.3f'
                      % (args.N, nd, mode, k, v[0], v[0] / base, v[1]), flush=True)


if __name__ == '__main__':
    main()
