#!/usr/bin/env python3
"""Side by side with FORM and Symbolica, the strongest peers, on the same exact tasks.

Run from the repository root:  python3 benches/peers.py [--rounds R] [--reps K]

Tasks (each peer does the complete job and checks its answer, and each also refutes a
wrong version, so that no verdict of "equal" is vacuous):

- eq26      the printed (26) with 1/3 is found false, the corrected one with 1/15 true
- eq33      (33) in 3D with a general non-symmetric sigma (and a changed coefficient refuted)
- eq38      (38) with sigma, mu, the transport by R_g and the Levi-Civita symbol
- rank6     <n_i n_j n_k n_l n_m n_p> = (sum of the 15 delta pairings)/105 (729 components)
- rank8     the same at rank 8: 105 pairings over 945 (6,561 components)
- rank10    the same at rank 10: 945 pairings over 10,395 (59,049 components); FORM and
            cosserat-check only (the Symbolica program here goes component by component
            in Python)
- a2        Q at the Appendix's state, D^(ep) once and the four A^2 of the Appendix from it
            as reduced rational functions in f_r, K, G, h^C, h_2, R_g (Symbolica and
            cosserat-check, whose four expressions are one probe of the file; not written
            for FORM)

How each is timed:

- cosserat-check: in process by `cargo bench --bench bench -- --task NAME K` (each
  repetition decides from the parsed files: the claim and its correction, a moment
  identity read and decided, the A^2 derivation); as a whole process by the release
  binary (`check --only ID`, `verify` of the identity's file, `check --only appA-a2`).
- FORM (Debian package `form`): its timer resolves only 10 ms, so in process is the
  difference between a run that repeats the task K+1 times and one that does it once,
  divided by K; a whole process is `form` on the task's program once. FORM works on
  symbolic indices (`dd_` gives the symmetric delta products); cosserat-check proves
  the identity for every value of the free indices, component by component.
- Symbolica (PyPI `symbolica`, installed into target/peers-venv; its free mode prints a
  banner and uses one thread): in process by `time.perf_counter` around each repetition
  in one Python process; a whole process is Python importing Symbolica and doing the
  task once.

Every measurement is taken in rounds, the tools interleaved (the order rotates every
round), and the table gives the minimum and the median over all rounds. The programs
run are written to target/peers/ so that they can be read and re-run by hand.
"""
import argparse
import os
import shutil
import statistics
import subprocess
import sys
import time
from fractions import Fraction
from itertools import product

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "target", "peers")
VENV = os.path.join(ROOT, "target", "peers-venv")
PY = os.path.join(VENV, "bin", "python")
SYMBOLICA = "symbolica==3.0.2"
TASKS = ["eq26", "eq33", "eq38", "rank6", "rank8", "rank10", "a2"]
CLAIM_OF = {"eq26": "eq26", "eq33": "eq33", "eq38": "eq38", "a2": "appA-a2"}


def ensure_venv():
    """Re-executes this script in target/peers-venv, with Symbolica installed there."""
    if sys.prefix != VENV:
        if not os.path.exists(PY):
            import venv

            venv.create(VENV, with_pip=True)
        # A venv left by an install that failed (a pinned version withdrawn, no network)
        # is completed rather than trusted.
        if subprocess.call([PY, "-c", "import symbolica"], stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL) != 0:
            subprocess.check_call([PY, "-m", "pip", "install", "--quiet", SYMBOLICA])
        os.execv(PY, [PY] + sys.argv)


def pairings(letters):
    """Every way of splitting the letters into pairs (15 for six, 105 for eight)."""
    if not letters:
        return [[]]
    out = []
    for k in range(1, len(letters)):
        rest = letters[1:k] + letters[k + 1:]
        for p in pairings(rest):
            out.append([(letters[0], letters[k])] + p)
    return out


def double_factorial_odd(k):
    """3 * 5 * ... * (2k + 1): the denominator of a rank-2k moment in 3D."""
    r = 1
    for m in range(k):
        r *= 3 + 2 * m
    return r


# ---------------------------------------------------------------------------- FORM

FORM_PRELUDE = """#-
Off statistics;
Dimension 3;
Vectors n;
CTensor sigma, mu, ntens;
Symbols Rg;
Table norm(0:16);
""" + "".join(
    f"Fill norm({k}) = {0 if k % 2 else '1/' + str(double_factorial_odd(k // 2))};\n"
    for k in range(17)
)


def form_average():
    """The average over the unit normal: n.n = 1, then every product of n's becomes the
    totally symmetric delta product dd_ over its normalisation."""
    return "id n.n = 1;\nToTensor n, ntens;\nid ntens(?a) = dd_(?a)*norm(nargs_(?a));\n"


def form_program(task):
    """The FORM program of a task: `REPS` repetitions, the last one printed. Each
    prints `good` (must be 0) and `bad` (must not be)."""
    if task == "eq26":
        idx = ["i1", "i2", "i3", "i4"]
        pair_sum = "(d_(i1,i2)*d_(i3,i4)+d_(i1,i3)*d_(i2,i4)+d_(i1,i4)*d_(i2,i3))"
        body = f"""Local lhs = n(i1)*n(i2)*n(i3)*n(i4);
Local corrected = 1/15*{pair_sum};
Local printed = 1/3*{pair_sum};
{form_average()}.sort
Local good = lhs - corrected;
Local bad = lhs - printed;
"""
    elif task in ("rank6", "rank8", "rank10"):
        rank = int(task[4:])
        idx = [f"i{k}" for k in range(1, rank + 1)]
        terms = ["*".join(f"d_({a},{b})" for a, b in p) for p in pairings(idx)]
        den = double_factorial_odd(rank // 2)
        body = f"""Local lhs = {'*'.join(f'n({i})' for i in idx)};
Local rhs = 1/{den}*({' + '.join(terms)});
Local wrong = 1/{den}*({' + '.join(terms[:-1])});
{form_average()}.sort
Local good = lhs - rhs;
Local bad = lhs - wrong;
"""
    elif task == "eq33":
        idx = "i,j,k,l1,l2,a1,b1,a2,b2,m1,m2,m3,m4".split(",")

        def tt(k, l, a, b):
            return f"(sigma({l},{k})*n({l}) - sigma({a},{b})*n({a})*n({b})*n({k}))"

        def s(i, j, m):
            return f"(sigma({i},{j}) - d_({i},{j})*sigma({m},{m})/3)"

        body = f"""Local lhs = {tt('k', 'l1', 'a1', 'b1')}*{tt('k', 'l2', 'a2', 'b2')};
Local rhs = 4/15*{s('i', 'j', 'm1')}*{s('i', 'j', 'm2')} - 1/15*{s('i', 'j', 'm3')}*{s('j', 'i', 'm4')};
Local wrong = 4/15*{s('i', 'j', 'm1')}*{s('i', 'j', 'm2')} - 2/15*{s('i', 'j', 'm3')}*{s('j', 'i', 'm4')};
Sum {','.join(idx)};
{form_average()}.sort
Local good = lhs - rhs;
Local bad = lhs - wrong;
"""
    elif task == "eq38":
        idx = "i,k,a,b,c,d,e,f,g,h,p,q,s".split(",")

        def mtc(i, k, l, a, b, c, d):
            return (
                f"((mu({k},{i}) + e_({i},{c},{l})*Rg*n({l})*sigma({k},{c}))*n({k}) - "
                f"(mu({a},{b}) + e_({b},{c},{d})*Rg*n({d})*sigma({a},{c}))*n({a})*n({b})*n({i}))"
            )

        def mt(t, i, k, a, b):
            return f"({t}({k},{i})*n({k}) - {t}({a},{b})*n({a})*n({b})*n({i}))"

        m2 = f"{mt('mu', 'i', 'k', 'a', 'b')}*{mt('mu', 'i', 'f', 'g', 'h')}"
        t2 = f"{mt('sigma', 'i', 'k', 'a', 'b')}*{mt('sigma', 'i', 'f', 'g', 'h')}"
        body = f"""Local lhs = {mtc('i', 'k', 'e', 'a', 'b', 'c', 'd')}*{mtc('i', 'f', 's', 'g', 'h', 'p', 'q')};
Local rhs = {m2} + Rg^2*{t2};
Local wrong = {m2} + 2*Rg^2*{t2};
Sum {','.join(idx)};
Contract;
{form_average()}.sort
Local good = lhs - rhs;
Local bad = lhs - wrong;
"""
    else:
        return None
    return (
        FORM_PRELUDE
        + f"Indices {','.join(idx)};\n"
        + "#do rep = 1, `REPS'\n"
        + body
        + "#if `rep' == `REPS'\nPrint good, bad;\n#endif\n.sort\nDrop;\n.sort\n#enddo\n.end\n"
    )


def form_verdict(output):
    """Whether the printed `good` is 0 and `bad` is not."""
    text = " ".join(output.split())
    return "good = 0;" in text and "bad =" in text and "bad = 0;" not in text


# ----------------------------------------------------------------------- Symbolica


def symbolica_tasks():
    from symbolica import S, Expression

    def q(fr):
        return Expression.num(fr.numerator) / Expression.num(fr.denominator)

    def dfact(a):
        r = 1
        for k in range(1, a, 2):
            r *= k
        return r

    def moment(alpha):
        if any(a % 2 for a in alpha):
            return Fraction(0)
        num = 1
        for a in alpha:
            num *= dfact(a)
        return Fraction(num, double_factorial_odd(sum(alpha) // 2))

    n = S("n1", "n2", "n3")
    sigma = [[S(f"sigma_{i + 1}{j + 1}") for j in range(3)] for i in range(3)]
    mu = [[S(f"mu_{i + 1}{j + 1}") for j in range(3)] for i in range(3)]
    Rg = S("R_g")
    zero = Expression.num(0)

    def avg(e):
        total = zero
        poly = e.expand().to_polynomial()
        present = [v for v in n if v in poly.get_variables()]
        if not present:
            return e.expand()
        for exps, c in poly.coefficient_list(present):
            full = dict(zip(present, exps))
            m = moment([full.get(v, 0) for v in n])
            if m:
                total = total + c.to_expression() * q(m)
        return total.expand()

    def same(a, b):
        return (a - b).expand() == zero

    def delta(a, b):
        return 1 if a == b else 0

    def eps(i, j, k):
        return (i - j) * (j - k) * (k - i) // 2

    def rank(k):
        def run():
            letters = list(range(k))
            ps = pairings(letters)
            den = double_factorial_odd(k // 2)
            good = bad = True
            for comp in product(range(3), repeat=k):
                prod = Expression.num(1)
                for c in comp:
                    prod = prod * n[c]
                lhs = avg(prod)
                counts = [sum(all(comp[a] == comp[b] for a, b in p) for p in ps[:m]) for m in (len(ps), len(ps) - 1)]
                good &= same(lhs, q(Fraction(counts[0], den)))
                bad &= same(lhs, q(Fraction(counts[1], den)))
            return good and not bad
        return run

    def eq26():
        printed_holds, corrected_holds = True, True
        for i, j, k, l in product(range(3), repeat=4):
            lhs = avg(n[i] * n[j] * n[k] * n[l])
            pairs = delta(i, j) * delta(k, l) + delta(i, k) * delta(j, l) + delta(i, l) * delta(j, k)
            printed_holds &= same(lhs, q(Fraction(pairs, 3)))
            corrected_holds &= same(lhs, q(Fraction(pairs, 15)))
        return corrected_holds and not printed_holds

    def traction(t):
        tv = [sum((t[k][i] * n[k] for k in range(3)), zero) for i in range(3)]
        tn = sum((tv[i] * n[i] for i in range(3)), zero)
        return [tv[i] - tn * n[i] for i in range(3)]

    def eq33():
        tt = traction(sigma)
        lhs = avg(sum((x * x for x in tt), zero))
        p = (sigma[0][0] + sigma[1][1] + sigma[2][2]) * q(Fraction(1, 3))
        s = [[sigma[i][j] - (p if i == j else zero) for j in range(3)] for i in range(3)]

        def rhs(c):
            return sum((q(Fraction(4, 15)) * s[i][j] * s[i][j] - q(c) * s[i][j] * s[j][i]
                        for i in range(3) for j in range(3)), zero)
        return same(lhs, rhs(Fraction(1, 15))) and not same(lhs, rhs(Fraction(2, 15)))

    def eq38():
        muc = [[mu[i][j] + sum((eps(j, k, l) * Rg * n[l] * sigma[i][k]
                                for k in range(3) for l in range(3)), zero)
                for j in range(3)] for i in range(3)]
        lhs = avg(sum((x * x for x in traction(muc)), zero))
        m2 = avg(sum((x * x for x in traction(mu)), zero))
        t2 = avg(sum((x * x for x in traction(sigma)), zero))
        return same(lhs, m2 + Rg**2 * t2) and not same(lhs, m2 + 2 * Rg**2 * t2)

    def a2():
        f, K, G, h, h2, R, sig, tau = S("f_r", "K", "G", "h_C", "h_2", "R_g", "sigma", "tau")
        s11, s22, s12, s21, m13, m23 = c = S("s11", "s22", "s12", "s21", "m13", "m23")
        half, quarter = q(Fraction(1, 2)), q(Fraction(1, 4))
        p = (s11 + s22) * half
        q2 = ((s11 - s22) ** 2 + (s12 + s21) ** 2) * quarter
        r2 = (s12 - s21) ** 2 * quarter
        m2 = (m13**2 + m23**2) * half
        x = 2 * m2 / R**2 + q2 + 2 * r2

        def at_state(e):
            for v, val in ((s11, sig), (s22, sig), (s12, tau), (s21, tau), (m13, zero), (m23, zero)):
                e = e.replace(v, val)
            return e

        assert same(at_state(x), tau**2)
        grads = [(at_state(x.derivative(v)) / (2 * tau) + f * p.derivative(v)).replace(tau, -f * sig)
                 .to_rational_polynomial() for v in c]
        Q = grads[:4]
        one = Expression.num(1)
        D = [[G * (K + 1), G * (K - 1), zero, zero], [G * (K - 1), G * (K + 1), zero, zero],
             [zero, zero, G * (one + h), G * (one - h)], [zero, zero, G * (one - h), G * (one + h)]]
        D = [[e.to_rational_polynomial() for e in row] for row in D]
        DQ = [D[i][0] * Q[0] + D[i][1] * Q[1] + D[i][2] * Q[2] + D[i][3] * Q[3] for i in range(4)]
        H = Q[0] * DQ[0] + Q[1] * DQ[1] + Q[2] * DQ[2] + Q[3] * DQ[3] + h2.to_rational_polynomial()
        Dep = [[D[i][j] - DQ[i] * DQ[j] / H for j in range(4)] for i in range(4)]
        # Gamma = (0, b, -w, a + w) with w = 1; solve rows 2 and 4 of Dep Gamma = 0 for a, b.
        a11, a12, r1 = Dep[1][3], Dep[1][1], Dep[1][2] - Dep[1][3]
        a21, a22, r2_ = Dep[3][3], Dep[3][1], Dep[3][2] - Dep[3][3]
        det = a11 * a22 - a12 * a21
        a = (r1 * a22 - a12 * r2_) / det
        b = (a11 * r2_ - r1 * a21) / det
        alpha = (Dep[2][1] - Dep[3][1]) * b - (Dep[2][2] - Dep[3][2]) + (Dep[2][3] - Dep[3][3]) * (a + one.to_rational_polynomial())
        m22 = (4 * G * R**2).to_rational_polynomial()
        r2r = (R**2).to_rational_polynomial()
        derived = -alpha * r2r / m22
        corrected = alpha * r2r / m22
        d = lambda i, j: Dep[i - 1][j - 1] / G.to_rational_polynomial()
        four = Expression.num(4).to_rational_polynomial()
        eq61 = four * (d(3, 2) * d(4, 4) - d(3, 4) * d(4, 2)) / (d(4, 2) + d(4, 4))
        eq54 = (16 * f**2 * (1 + 2 * f**2) / (1 + 8 * f**2 * (1 + 3 * f**2))).to_rational_polynomial()
        closed = ((f**2 * K * G * h + (K + 1) * h * h2)
                  / (f**2 * K * G * (1 + h) + K * G * h + G * h + (K + 1) * (1 + h) * h2)).to_rational_polynomial()
        zero_rf = zero.to_rational_polynomial()
        # The derived A^2 is the closed form of appA-a2; the corrected sign is not; (54)
        # is not (61) (the paper's slip, eq61/eq54 in the table).
        return (derived - closed == zero_rf and corrected - closed != zero_rf
                and eq61 - eq54 != zero_rf)

    return {"eq26": eq26, "eq33": eq33, "eq38": eq38, "rank6": rank(6), "rank8": rank(8), "a2": a2}


def symbolica_main(task, reps):
    """`--symbolica TASK REPS` (inside the venv): each repetition's milliseconds, then
    `ok` or `WRONG`."""
    tasks = symbolica_tasks()
    verdicts = []
    for _ in range(reps):
        t = time.perf_counter()
        verdicts.append(tasks[task]())
        print(f"{(time.perf_counter() - t) * 1e3:.4f}")
    print("ok" if all(verdicts) else "WRONG")


# --------------------------------------------------------------------- the driver


def moment_file(rank):
    """The rank-`rank` identity and the same with its last pairing dropped (refuted), as
    a derivation file (as benches/bench.rs writes it: past rank 8, the right side is a
    sum of definitions of 35 pairings each and one of the last pairing)."""
    letters = "ijklmpqrst"[:rank]
    ns = " ".join(f"n_{c}" for c in letters)
    terms = [" ".join(f"delta_{a}{b}" for a, b in p) for p in pairings(list(letters))]
    defs = ""
    if rank > 8:
        last = terms.pop()
        parts = [f'"P{k}_{letters} = {" + ".join(terms[i:i + 35])}"'
                 for k, i in enumerate(range(0, len(terms), 35))]
        parts.append(f'"L_{letters} = {last}"')
        defs = f"define = [{', '.join(parts)}]\n"
        terms = [f"P{k}_{letters}" for k in range(len(parts) - 1)] + [f"L_{letters}"]

    def claim(cid, expect, ts):
        return (f'[[claim]]\nid = "{cid}"\nprinted = \'{cid}\'\nexpect = "{expect}"\n'
                f'sides = ["avg({ns})", "1/{double_factorial_odd(rank // 2)} ({" + ".join(ts)})"]\n')
    return ('section = "b"\ntitle = "b"\ndimension = 3\nnormal = "n"\n' + defs
            + claim("m", "holds", terms) + claim("wrong", "fails", terms[:-1])
            + 'reason = "one pairing dropped"\n')


def wall(cmd, env=None):
    t = time.perf_counter()
    out = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, env=env)
    return time.perf_counter() - t, out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--tasks", default=",".join(TASKS))
    ap.add_argument("--symbolica", nargs=2, metavar=("TASK", "REPS"), help=argparse.SUPPRESS)
    args = ap.parse_args()
    ensure_venv()
    if args.symbolica:
        symbolica_main(args.symbolica[0], int(args.symbolica[1]))
        return
    form = shutil.which("form")
    if form is None:
        sys.exit("FORM is not installed: apt-get install form (Debian's package)")
    os.makedirs(OUT, exist_ok=True)
    subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=ROOT, check=True)
    subprocess.run(["cargo", "bench", "--quiet", "--bench", "bench", "--no-run"], cwd=ROOT, check=True,
                   capture_output=True)
    exe = os.path.join(ROOT, "target", "release", "cosserat-check")
    tasks = args.tasks.split(",")
    for task in tasks:
        prog = form_program(task)
        if prog:
            with open(os.path.join(OUT, f"{task}.frm"), "w") as fh:
                fh.write(prog)
        if task.startswith("rank"):
            with open(os.path.join(OUT, f"{task}.toml"), "w") as fh:
                fh.write(moment_file(int(task[4:])))
    env = dict(os.environ, SYMBOLICA_HIDE_BANNER="1")
    samples = {(t, tool, kind): [] for t in tasks for tool in ("ours", "form", "symbolica")
               for kind in ("in", "whole")}
    failures = []

    def ours(task):
        out = subprocess.run(["cargo", "bench", "--quiet", "--bench", "bench", "--", "--task", task,
                              str(args.reps)], cwd=ROOT, capture_output=True, text=True, check=True)
        samples[(task, "ours", "in")] += [float(x) / 1e3 for x in out.stdout.split()]
        cmd = ([exe, "verify", os.path.join(OUT, f"{task}.toml")] if task.startswith("rank")
               else [exe, "check", "--only", CLAIM_OF[task]])
        t, out = wall(cmd)
        if out.returncode != 0:
            failures.append(f"cosserat-check {task}: exit {out.returncode}")
        samples[(task, "ours", "whole")].append(t)

    form_reps = {}

    def form_run(task):
        prog = os.path.join(OUT, f"{task}.frm")
        if not os.path.exists(prog):
            return
        if task not in form_reps:
            # Enough repetitions that their time (about 0.3 s) dwarfs the process's
            # start and FORM's 10 ms timer.
            t1, _ = wall([form, "-q", "-D", "REPS=1", prog])
            t21, _ = wall([form, "-q", "-D", "REPS=21", prog])
            per = max((t21 - t1) / 20, 1e-5)
            form_reps[task] = int(min(max(0.3 / per, 10), 5000))
        k = form_reps[task]
        t1, out1 = wall([form, "-q", "-D", "REPS=1", prog])
        tk, outk = wall([form, "-q", "-D", f"REPS={k + 1}", prog])
        for out in (out1, outk):
            if out.returncode != 0 or not form_verdict(out.stdout):
                failures.append(f"FORM {task}: wrong or failed\n{out.stdout}{out.stderr}")
        samples[(task, "form", "in")].append(max(tk - t1, 0.0) / k)
        samples[(task, "form", "whole")].append(t1)

    def symbolica_run(task):
        if task == "rank10":
            return
        out = subprocess.run([PY, __file__, "--symbolica", task, str(args.reps)], cwd=ROOT,
                             capture_output=True, text=True, env=env)
        lines = out.stdout.split()
        if out.returncode != 0 or not lines or lines[-1] != "ok":
            failures.append(f"Symbolica {task}: wrong or failed\n{out.stdout}{out.stderr[-2000:]}")
            return
        samples[(task, "symbolica", "in")] += [float(x) / 1e3 for x in lines[:-1]]
        t, out = wall([PY, __file__, "--symbolica", task, "1"], env=env)
        samples[(task, "symbolica", "whole")].append(t)

    runners = [ours, form_run, symbolica_run]
    for r in range(args.rounds):
        print(f"round {r + 1}/{args.rounds}", file=sys.stderr)
        for task in tasks:
            for k in range(len(runners)):
                runners[(k + r) % len(runners)](task)
    if failures:
        print("\n\n".join(failures), file=sys.stderr)
        sys.exit(1)

    def fmt(xs):
        if not xs:
            return "—"
        lo, med = min(xs) * 1e3, statistics.median(xs) * 1e3
        return f"{lo:.3g} / {med:.3g} ms"

    print("| task | cosserat-check | FORM | Symbolica | fastest peer ÷ ours (median) |")
    print("|---|---|---|---|---|")
    for kind, label in (("in", "in process"), ("whole", "whole process")):
        for task in tasks:
            ours_med = statistics.median(samples[(task, "ours", kind)])
            peers = [statistics.median(samples[(task, p, kind)]) for p in ("form", "symbolica")
                     if samples[(task, p, kind)]]
            ratio = f"{min(peers) / ours_med:.2f}" if peers else "—"
            print(f"| {task}, {label} | {fmt(samples[(task, 'ours', kind)])} | "
                  f"{fmt(samples[(task, 'form', kind)])} | {fmt(samples[(task, 'symbolica', kind)])} | {ratio} |")
    print(f"\n(min / median over {args.rounds} interleaved rounds; in process: {args.reps} "
          f"repetitions per round, FORM's by the difference of runs with 1 and 1 + k "
          f"repetitions, k = {form_reps})")


if __name__ == "__main__":
    main()
