#!/usr/bin/env python3
"""Side-by-side with SymPy on the same exact proofs: eqs. (26) (corrected: the factor
1/15), (33) and (38) of the paper, in 3D with general non-symmetric sigma and mu, and
the symbolic A² derivation of Appendix A (yield gradient at the state, D^(ep), the
elimination through (58)-(60) with both signs of the moment balance, (61), (54); every
result reduced with `cancel`, as cosserat-check keeps its rational functions reduced).

Run from the repository root:  python3 benches/sympy_compare.py
It installs SymPy into target/sympy-venv (nothing global) and prints, for each proof,
the median time of cosserat-check deciding the claim in process (`cargo bench --bench
bench -- --claim ID`: the claim as printed and its correction, after the files are
read) and of SymPy doing the same proof in process (expand both sides, average the
normal's monomials with the same moment formula, compare), and their ratio.
"""
import os
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VENV = os.path.join(ROOT, "target", "sympy-venv")
PY = os.path.join(VENV, "bin", "python")


def ensure_venv():
    if sys.prefix != VENV:
        if not os.path.exists(PY):
            import venv

            venv.create(VENV, with_pip=True)
            subprocess.check_call([PY, "-m", "pip", "install", "--quiet", "sympy"])
        os.execv(PY, [PY] + sys.argv)


def sympy_proofs():
    import sympy as sp
    from itertools import product

    n = sp.symbols("n1:4")
    sigma = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"sigma_{i+1}{j+1}"))
    mu = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"mu_{i+1}{j+1}"))
    Rg = sp.Symbol("R_g")
    delta = lambda i, j: 1 if i == j else 0
    eps = lambda i, j, k: sp.LeviCivita(i, j, k)

    def dfact(a):  # (a-1)!! for even a
        r = 1
        for k in range(1, a, 2):
            r *= k
        return r

    def moment(alpha):
        if any(a % 2 for a in alpha):
            return 0
        k = sum(alpha)
        den = 1
        for m in range(k // 2):
            den *= 3 + 2 * m
        num = 1
        for a in alpha:
            num *= dfact(a)
        return sp.Rational(num, den)

    def avg(expr):
        poly = sp.Poly(sp.expand(expr), *n)
        return sp.expand(sum(c * moment(m) for m, c in poly.terms()))

    def eq26():
        for i, j, k, l in product(range(3), repeat=4):
            lhs = avg(n[i] * n[j] * n[k] * n[l])
            rhs = sp.Rational(1, 15) * (delta(i, j) * delta(k, l) + delta(i, k) * delta(j, l) + delta(i, l) * delta(j, k))
            assert sp.expand(lhs - rhs) == 0

    def stress_parts():
        p = sigma.trace() / 3
        s = sigma - p * sp.eye(3)
        t = [sum(sigma[k, i] * n[k] for k in range(3)) for i in range(3)]
        tn = sum(t[i] * n[i] for i in range(3))
        tt = [t[i] - tn * n[i] for i in range(3)]
        return s, tt

    def eq33():
        s, tt = stress_parts()
        lhs = avg(sum(x * x for x in tt))
        rhs = sum(sp.Rational(4, 15) * s[i, j] ** 2 - sp.Rational(1, 15) * s[i, j] * s[j, i] for i in range(3) for j in range(3))
        assert sp.expand(lhs - rhs) == 0

    def eq38():
        _, tt = stress_parts()
        muc = sp.Matrix(3, 3, lambda i, j: mu[i, j] + sum(eps(j, k, l) * Rg * n[l] * sigma[i, k] for k in range(3) for l in range(3)))
        m = [sum(mu[k, i] * n[k] for k in range(3)) for i in range(3)]
        mn = sum(m[i] * n[i] for i in range(3))
        mt = [m[i] - mn * n[i] for i in range(3)]
        mc = [sum(muc[k, i] * n[k] for k in range(3)) for i in range(3)]
        mnc = sum(mc[i] * n[i] for i in range(3))
        mtc = [mc[i] - mnc * n[i] for i in range(3)]
        lhs = avg(sum(x * x for x in mtc))
        rhs = avg(sum(x * x for x in mt)) + Rg**2 * avg(sum(x * x for x in tt))
        assert sp.expand(lhs - rhs) == 0

    def a_squared():
        f, K, G, h, h2, R, sig, tau = sp.symbols("f_r K G h_C h_2 R_g sigma tau")
        c = sp.symbols("s11 s22 s12 s21 m13 m23")
        s11, s22, s12, s21, m13, m23 = c
        p = (s11 + s22) / 2
        q2 = ((s11 - s22) ** 2 + (s12 + s21) ** 2) / 4
        r2 = (s12 - s21) ** 2 / 4
        M2 = (m13**2 + m23**2) / 2
        X = 2 * M2 / R**2 + q2 + 2 * r2
        state = {s11: sig, s22: sig, s12: tau, s21: tau, m13: 0, m23: 0}
        assert sp.expand(X.subs(state) - tau**2) == 0
        grads = [sp.cancel((sp.diff(X, v).subs(state) / (2 * tau) + f * sp.diff(p, v)).subs(tau, -f * sig)) for v in c]
        Q = sp.Matrix(grads[:4])
        D = G * sp.Matrix([[K + 1, K - 1, 0, 0], [K - 1, K + 1, 0, 0], [0, 0, 1 + h, 1 - h], [0, 0, 1 - h, 1 + h]])
        DQ = D * Q
        H = (Q.T * D * Q)[0] + h2
        Dep = (D - DQ * DQ.T / H).applyfunc(sp.cancel)
        M22 = 4 * G * R**2
        # Gamma = (0, v2', -w3, v1' + w3); sigma_dot = Dep Gamma
        a, b, w = sp.symbols("a b w")
        gam = sp.Matrix([0, b, -w, a + w])
        sd = Dep * gam
        sol = sp.solve([sd[1], sd[3]], [a, b], dict=True)[0]
        alpha = sp.cancel(sp.diff((sd[2] - sd[3]).subs(sol), w))
        results = []
        for sign in (-1, 1):
            results.append(sp.cancel(sign * alpha * R**2 / M22))
        d = lambda i, j: Dep[i - 1, j - 1] / G
        results.append(sp.cancel(4 * (d(3, 2) * d(4, 4) - d(3, 4) * d(4, 2)) / (d(4, 2) + d(4, 4))))
        results.append(sp.cancel(16 * f**2 * (1 + 2 * f**2) / (1 + 8 * f**2 * (1 + 3 * f**2))))
        return results

    return {"eq26": eq26, "eq33": eq33, "eq38": eq38, "A2": a_squared}


def median_seconds(f, reps):
    from sympy.core.cache import clear_cache

    times = []
    for _ in range(reps):
        # Each repetition starts from scratch, as cosserat-check's does: SymPy's cache
        # would otherwise hand later repetitions the results of the first.
        clear_cache()
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def main():
    ensure_venv()
    proofs = sympy_proofs()
    print("| proof | cosserat-check | SymPy | ratio |")
    print("|---|---|---|---|")
    for claim, proof in proofs.items():
        mode = ["--derive-a2"] if claim == "A2" else ["--claim", claim]
        out = subprocess.run(
            ["cargo", "bench", "--quiet", "--bench", "bench", "--"] + mode,
            cwd=ROOT, check=True, capture_output=True, text=True,
        )
        ours = float(out.stdout.strip().splitlines()[-1]) / 1e3
        theirs = median_seconds(proof, 3)
        print(f"| {claim} | {ours * 1e3:.2f} ms | {theirs * 1e3:.0f} ms | {theirs / ours:.0f}x |")


if __name__ == "__main__":
    main()
