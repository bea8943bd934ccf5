"""Writes tests/data/near_coincident7.json: a 7-dof system (stiffness spread ~1e5) with two nearly coincident zero
curves of det H, the situation in which an earlier search missed two real SPPs of a random stiff 7-dof system.

Built in modal coordinates: two modes of nearly equal frequencies (10 and 10 (1 + 1e-5)) that barely see the contact
(modal participations 3e-4 and -3.9e-4 of |u| ~ 1) give two zero curves of det H near t1 + t2 = pi / 10, about 1e-3
apart in lambda_{k+1}; the onset function g = c^T b is small along both. In (0.110, 0.113] x (0.201, 0.204] each
curve holds one SPP, (0.111823204333, 0.202333000865) and (0.111819649129, 0.202339666461), 3.6e-6 apart in t1;
brute_force.py finds only the first.
Usage: /usr/bin/python3 tests/crosscheck/make_near_coincident.py OUT.json"""
import json
import sys

import numpy as np

rng = np.random.default_rng(1)
n = 7
omega = np.sort(10 ** rng.uniform(0, 2.5, n))
omega[3], omega[4] = 10.0, 10.0 * (1 + 1e-5)  # nearly repeated frequency
u = rng.standard_normal(n)
u[3], u[4] = 3e-4, -1.3 * 3e-4                 # both barely see the contact
A = rng.standard_normal((n, n))
M = A @ A.T + n * np.eye(n)
Phi = np.linalg.solve(np.linalg.cholesky(M).T, np.linalg.qr(rng.standard_normal((n, n)))[0])  # Phi^T M Phi = I
K = M @ Phi @ np.diag(omega ** 2) @ Phi.T @ M
w = M @ Phi @ u                                # Phi^T w = u
json.dump({"name": "near_coincident7", "M": M.tolist(), "K": ((K + K.T) / 2).tolist(),
           "w": (w / np.linalg.norm(w)).tolist(), "g0": 1.0}, open(sys.argv[1], "w"), indent=1)
