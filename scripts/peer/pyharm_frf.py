"""The same frequency response in pyHarm, the peer harmonic-balance code.

Reads the harmonic-balance problem that `gearshock frf` solves on the
default compound set (`gearshock bench --hbm-problem`: scaled modal
coordinates x, time tau = omega_ref t, phase theta = Omega tau)

    x'' + C x' + K x + sum_j n_j d_j k_j(theta) g_j(d_j . x - e_j(theta))
        = f0 + Omega sum_j n_j c_j d_j e_j'(theta)

and continues its periodic branch in Omega with pyHarm (the Python package
`pyharm-os`): its own arclength continuation, step control and nonlinear
solver (all its defaults), with the meshes as one pyHarm element evaluated
by the alternating frequency-time scheme on `--nti` samples a period.

Each run times `gearshock frf` on the same sweep (a child process: its CPU
and wall time, start-up included) twice, at its defaults (with the Floquet
stability of every point) and with `--no-stability` (the branch alone:
the same work as pyHarm, which computes no stability), and then pyHarm's
continuation (its `operate()` alone), and prints one JSON line: the
times, both CPU ratios, the points, and the largest distance of pyHarm's
branch from gearshock's in peak-to-peak deflection x = delta - e of the
chosen mesh, relative to the branch's largest. A last line gives the
medians.

Run by scripts/bench-pyharm.sh; see docs/performance.md.
"""

import argparse
import contextlib
import importlib.metadata
import io
import json
import resource
import subprocess
import sys
import time

import numpy as np
from pyHarm.BaseUtilFuncs import pyHarm_plugin
from pyHarm.DynamicOperator import compute_DFT
from pyHarm.Elements.ABCElement import ABCElement
from pyHarm.Maestro import Maestro


class GearMeshes(ABCElement):
    """Every mesh channel of the problem as one element acting on all dofs.

    Residual: the harmonics of sum_j n_j d_j k_j(theta) g_j(u_j - e_j)
    minus the load f0 and the dampers' TE-rate forcing; its Jacobian from
    the contact slopes sample by sample (AFT).
    """

    factory_keyword = "GearMeshes"

    def __post_init__(self):
        p = self.data["problem"]
        self.m = int(p["m"])
        self.ch = p["channels"]
        self.d = np.array([c["d"] for c in self.ch])  # channels x m
        self.n = np.array([c["multiplicity"] for c in self.ch])
        law = [c["law"] for c in self.ch]
        theta = 2.0 * np.pi * np.arange(self.nti) / self.nti
        ph = theta[:, None] + np.array([l["phase_rad"] for l in law])[None, :]
        c, s = np.cos(ph), np.sin(ph)
        arr = lambda key: np.array([l[key] for l in law])[None, :]
        self.kt = arr("k") * (1.0 + arr("variation") * c)  # nti x channels
        self.e = arr("te_mean_um") + arr("te_cos_um") * c + arr("te_sin_um") * s
        de = -arr("te_cos_um") * s + arr("te_sin_um") * c  # de/dtheta
        self.b = arr("backlash_um")
        damp = np.array([ch["damping"] for ch in self.ch])[None, :]
        # The TE-rate forcing per unit Omega, in time then in harmonics.
        f_te = (self.n[None, :] * damp * de) @ self.d  # nti x m
        self.f_te = (self.D["tf"].T @ f_te).reshape(-1)
        load = np.zeros((self.D["ft"].shape[0], self.m))
        load[0, :] = np.array(p["load"])
        self.load = load.reshape(-1)

    def __flag_update__(self):
        self.flag_nonlinear = True
        self.flag_AFT = True

    def __init_data__(self, name, data, CS):
        self.name = name
        self.data = data
        self.CS = CS
        self.indices = []

    def generateIndices(self, expl_dofs):
        # The problem's only substructure: every dof, harmonic-major.
        self.indices = np.arange(len(expl_dofs))

    def adim(self, lc, wc):
        pass

    def __str__(self):
        return f"GearMeshes: {len(self.ch)} channels on {self.m} modal coordinates"

    def _time(self, xg):
        X = xg[self.indices].reshape(-1, self.m)  # (2H+1) x m
        Xt = self.D["ft"].T @ X  # nti x m
        r = Xt @ self.d.T - self.e  # nti x channels
        closed_up = r > self.b
        closed_down = r < -self.b
        g = np.where(closed_up, r - self.b, np.where(closed_down, r + self.b, 0.0))
        slope = np.where(closed_up | closed_down, 1.0, 0.0)
        return g, slope

    def evalResidual(self, xg, om):
        g, _ = self._time(xg)
        F = (self.n[None, :] * self.kt * g) @ self.d  # nti x m
        R = (self.D["tf"].T @ F).reshape(-1)
        self.R = R - self.load - om * self.f_te
        return self.R

    def evalJacobian(self, xg, om):
        _, slope = self._time(xg)
        w = self.n[None, :] * self.kt * slope  # nti x channels
        A = np.einsum("kj,jp,jq->kpq", w, self.d, self.d)  # nti x m x m
        J = np.einsum("ka,kpq,bk->apbq", self.D["tf"], A, self.D["ft"])
        N = len(self.indices)
        self.J = J.reshape(N, N)
        self.dJdom = -self.f_te.copy()
        return self.J, self.dJdom


def quasi_static_start(problem, harmonics, samples=256):
    """The harmonics of the quasi-static solution (Omega -> 0, every mesh on
    its drive flank): at each phase, (K + sum n k(theta) d d^T) x =
    f0 + sum n k(theta) (b + e(theta)) d. Close to the branch at a low first
    Omega, which pyHarm's first corrector then solves; started from the
    static solution alone (TE left out) it stalls or diverges."""
    m = problem["m"]
    theta = 2.0 * np.pi * np.arange(samples) / samples
    X = np.zeros((samples, m))
    for k, th in enumerate(theta):
        A = np.array(problem["stiffness"], dtype=float)
        rhs = np.array(problem["load"], dtype=float)
        for c in problem["channels"]:
            d = np.array(c["d"])
            law = c["law"]
            ph = th + law["phase_rad"]
            kt = c["multiplicity"] * law["k"] * (1.0 + law["variation"] * np.cos(ph))
            e = law["te_mean_um"] + law["te_cos_um"] * np.cos(ph) + law["te_sin_um"] * np.sin(ph)
            A = A + kt * np.outer(d, d)
            rhs = rhs + kt * (law["backlash_um"] + e) * d
        X[k] = np.linalg.solve(A, rhs)
    return (compute_DFT(samples, harmonics)["tf"].T @ X).reshape(-1)


def peak_to_peak_um(problem, channel, coeffs, harmonics, samples=1024):
    """Peak-to-peak of x = u - e (um) of one channel from its harmonics."""
    D = compute_DFT(samples, harmonics)
    m = problem["m"]
    X = coeffs.reshape(-1, m)
    c = problem["channels"][channel]
    law = c["law"]
    theta = 2.0 * np.pi * np.arange(samples) / samples + law["phase_rad"]
    e = law["te_mean_um"] + law["te_cos_um"] * np.cos(theta) + law["te_sin_um"] * np.sin(theta)
    x = (D["ft"].T @ X) @ np.array(c["d"]) - e
    return float(x.max() - x.min())


def distance_to_branch(points, ref):
    """Largest distance of `points` (Omega, p2p) from the polyline `ref`, in
    p2p units with Omega scaled by the p2p range over the Omega range."""
    ref = np.asarray(ref)
    pts = np.asarray(points)
    span_o = ref[:, 0].max() - ref[:, 0].min()
    span_p = ref[:, 1].max() - ref[:, 1].min()
    scale = np.array([span_p / span_o, 1.0])
    a = ref[:-1] * scale
    b = ref[1:] * scale
    worst, at = 0.0, None
    for p, raw in zip(pts * scale, pts):
        ab = b - a
        t = np.clip(np.einsum("ij,ij->i", p - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0, 1)
        dist = np.linalg.norm(a + t[:, None] * ab - p, axis=1).min()
        if dist > worst:
            worst, at = dist, raw
    return worst, at


def run_gearshock(binary, a):
    """One `gearshock frf` run of the sweep: its branch as (Omega, p2p um)
    and the child's CPU (user + system) and wall time."""
    cmd = [
        binary, "frf", "--omega-from", str(a.omega_from), "--omega-to", str(a.omega_to),
        "--harmonics", str(a.harmonics), "--mesh", a.mesh, "--format", "json",
    ] + a.gearshock_args.split()
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    wall0 = time.perf_counter()
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    wall = time.perf_counter() - wall0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    gs = json.loads(out)
    ref = [(p["omega"], (p["x_max_m"] - p["x_min_m"]) * 1e6) for p in gs["branch"]]
    return ref, cpu, wall, " ".join(cmd[1:])


def run_pyharm(problem, channel, a):
    """One pyHarm continuation of the sweep: its branch as (Omega, p2p um)
    and the CPU and wall time of `operate()` alone (the system is built
    and numba's kernels compiled before the clock starts)."""
    m = problem["m"]
    frf = {
        "study": "frf",
        "puls_inf": a.omega_from,
        "puls_sup": a.omega_to,
        "puls_start": a.omega_from,
        "verbose": False,
    }
    if a.ds_max is not None:
        frf["ds_max"] = a.ds_max
    data = {
        "analysis": {"frf": frf},
        "system": {"type": "Base", "nh": a.harmonics, "nti": a.nti},
        "substructures": {
            "gear": {
                "matrix": {
                    "M": np.eye(m),
                    "C": np.array(problem["damping"]),
                    "K": np.array(problem["stiffness"]),
                    "G": np.zeros((m, m)),
                },
                "ndofs": m,
            }
        },
        "connectors": {
            "meshes": {"type": "GearMeshes", "connect": {"gear": [0]}, "dirs": [0], "problem": problem}
        },
    }
    log = io.StringIO()  # pyHarm's banner and log, shown only on failure
    try:
        with contextlib.redirect_stderr(log), contextlib.redirect_stdout(log):
            M = Maestro(data)
            x0 = quasi_static_start(problem, a.harmonics)
            cpu0, wall0 = time.process_time(), time.perf_counter()
            M.operate(x0=x0)
            cpu, wall = time.process_time() - cpu0, time.perf_counter() - wall0
    except Exception:
        sys.stderr.write(log.getvalue()[-4000:])
        raise
    sols = [s for s in M.nls["frf"].SolList if s.flag_accepted]
    pts = [(float(s.x[-1]), peak_to_peak_um(problem, channel, s.x[:-1], a.harmonics)) for s in sols]
    return pts, cpu, wall


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--problem", required=True, help="gearshock bench --hbm-problem output")
    ap.add_argument("--gearshock-bin", required=True, help="the gearshock binary (release)")
    ap.add_argument("--gearshock-args", default="", help="more options of gearshock frf")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--mesh", default="s2b1")
    ap.add_argument("--harmonics", type=int, default=7)
    ap.add_argument("--nti", type=int, default=128, help="pyHarm's time samples a period")
    ap.add_argument("--omega-from", type=float, default=0.1)
    ap.add_argument("--omega-to", type=float, default=0.5)
    ap.add_argument("--ds-max", type=float, default=None, help="pyHarm's largest arclength step (default: its own)")
    a = ap.parse_args()

    problem = json.load(open(a.problem))
    channel = next(i for i, c in enumerate(problem["channels"]) if a.mesh in c["meshes"])
    pyHarm_plugin(GearMeshes)
    # pyHarm's kernels are numba-compiled (and cached) at first use: one
    # short untimed run first.
    warm = argparse.Namespace(**{**vars(a), "omega_to": a.omega_from + 0.01})
    run_pyharm(problem, channel, warm)
    # And gearshock's one short untimed run: its binary's pages read in
    # once, as pyHarm's modules were by its warm-up.
    run_gearshock(a.gearshock_bin, warm)

    rows = []
    for k in range(a.runs):
        ref, g_cpu, g_wall, cmd = run_gearshock(a.gearshock_bin, a)
        # The branch alone: what pyHarm computes (it has no stability).
        alone = argparse.Namespace(**{**vars(a), "gearshock_args": a.gearshock_args + " --no-stability"})
        if "--no-stability" in a.gearshock_args.split():
            alone = a
        _, b_cpu, _, _ = run_gearshock(a.gearshock_bin, alone)
        pts, p_cpu, p_wall = run_pyharm(problem, channel, a)
        peak = max(p[1] for p in ref)
        # pyHarm's last step ends past the range; gearshock's at its end.
        inside = [p for p in pts if a.omega_from <= p[0] <= a.omega_to]
        worst, at = distance_to_branch(inside, ref)
        # And the other way: a coarse branch that cuts a peak or a fold
        # short lies far from the fine one's points there.
        back, back_at = distance_to_branch(ref, pts)
        row = {
            "run": k + 1,
            "gearshock_cpu_s": round(g_cpu, 4),
            "gearshock_wall_s": round(g_wall, 4),
            "gearshock_points": len(ref),
            "pyharm_cpu_s": round(p_cpu, 3),
            "pyharm_wall_s": round(p_wall, 3),
            "pyharm_points": len(pts),
            "pyharm_omega_reached": round(max(p[0] for p in pts), 5),
            "cpu_ratio": round(p_cpu / g_cpu, 1),
            "gearshock_branch_alone_cpu_s": round(b_cpu, 4),
            "cpu_ratio_branch_alone": round(p_cpu / b_cpu, 1),
            "distance_rel": float(f"{worst / peak:.3g}"),
            "farthest_at_omega": round(at[0], 5),
            "distance_back_rel": float(f"{back / peak:.3g}"),
            "farthest_back_at_omega": round(back_at[0], 5),
        }
        rows.append(row)
        print(json.dumps(row), flush=True)
    med = lambda key: float(np.median([r[key] for r in rows]))
    print(json.dumps({
        "sweep": cmd,
        "pyharm": {"version": importlib.metadata.version("pyharm-os"), "harmonics": a.harmonics, "nti": a.nti,
                   "ds_max": a.ds_max if a.ds_max is not None else "default"},
        "runs": a.runs,
        "median_gearshock_cpu_s": med("gearshock_cpu_s"),
        "median_pyharm_cpu_s": med("pyharm_cpu_s"),
        "median_cpu_ratio": med("cpu_ratio"),
        "ratios": [r["cpu_ratio"] for r in rows],
        "median_gearshock_branch_alone_cpu_s": med("gearshock_branch_alone_cpu_s"),
        "median_cpu_ratio_branch_alone": med("cpu_ratio_branch_alone"),
        "ratios_branch_alone": [r["cpu_ratio_branch_alone"] for r in rows],
        "largest_distance_rel": max(max(r["distance_rel"], r["distance_back_rel"]) for r in rows),
    }))
    return 0


if __name__ == "__main__":
    sys.exit(main())
