#!/usr/bin/env python3
"""rigid vs Pinocchio, side by side, in one run (see BENCHMARKS.md).

    python3 bench/compare.py                 # 7 rounds on one core, every model of bench/models.tsv
    python3 bench/compare.py --rounds 3 --models ur5,talos
    python3 bench/compare.py --json out.json # also save every raw measurement
    python3 bench/compare.py --explicit      # also the generated explicit model (rigid explicit)

Steps:
 1. builds Pinocchio's timing program (bash bench/pinocchio/run.sh --build-only: installs pin from
    PyPI, exports the robots, compiles bench/pinocchio/timings.cpp; cached after the first run)
    and rigid (cargo build --release -p rigid-cli);
 2. for each round and each model, runs rigid's benchmark
    (cargo run --release -p rigid-cli -- bench MODEL [--floating] --json) and Pinocchio's
    (every build variant), alternating which side goes first, so that machine noise hits both
    sides alike;
 3. prints the machine, then Markdown tables: ratios rigid / Pinocchio per model and algorithm,
    and the raw ns per call of both sides. Each side's raw number is the median over rounds of the
    median it reports; Pinocchio's is, per algorithm, the fastest of its build variants. A ratio is
    the median over rounds of the ratio within each round (the two sides ran back to back);
    the spread table gives the smallest and largest of those per-round ratios.

The interleaved runs are pinned to one core (`os.sched_setaffinity`, inherited by both sides'
processes; `--cpu auto`, the default, picks the core that was idlest over half a second, so a
background job keeps to the other one), so that neither side is migrated between cores mid-pass.

If rigid's side fails (no `bench` subcommand yet, or no JSON), it says so and still prints
Pinocchio's table.

--explicit: in each round also runs the generated explicit model of the PUMA 560 and the UR5
(`EXPLICIT_JSON=1 cargo bench -p rigid --bench explicit`, which times the generated
`mass_matrix`, `gravity`, `c + g` and `M a + c + g` beside rigid's CRBA, gravity, nle and RNEA in
one process) and prints their ratios to Pinocchio's CRBA, gravity, nle and RNEA of the same round.
"""
import argparse
import json
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
PIN_DIR = os.path.join(HERE, "pinocchio")
PIN_BUILD = os.path.join(PIN_DIR, "build")

# the schema both sides print; extra keys are shown in the raw tables only. rnea_derivatives and
# aba_derivatives: computeRNEADerivatives / computeABADerivatives (bench/pinocchio/timings-deriv.cpp).
ALGOS = ["forward_kinematics", "jacobians", "rnea", "gravity", "nonlinear_effects", "crba", "aba", "minverse",
         "rnea_derivatives", "aba_derivatives"]
SHORT = {
    "forward_kinematics": "FK",
    "jacobians": "Jac",
    "rnea": "RNEA",
    "gravity": "g(q)",
    "nonlinear_effects": "nle",
    "crba": "CRBA",
    "aba": "ABA",
    "minverse": "M⁻¹",
    "rnea_derivatives": "∂RNEA",
    "aba_derivatives": "∂ABA",
}
# bars: ratio rigid / Pinocchio at most this (issue 16: RNEA 0.6, CRBA and ABA 0.7; issue 5: FK
# and Jacobians 1.2; issue 12: the derivatives 1.0), and no single round of RNEA, CRBA, ABA above
# ROUND_MAX (issue 16)
TARGET = {"rnea": 0.6, "crba": 0.7, "aba": 0.7, "forward_kinematics": 1.2, "jacobians": 1.2,
          "rnea_derivatives": 1.0, "aba_derivatives": 1.0}
ROUND_MAX = {"rnea": 0.9, "crba": 0.9, "aba": 0.9}
# issue 12's other bar: rigid's derivatives at most this many times its own RNEA / ABA (on Talos)
OWN = {"rnea_derivatives": ("rnea", 4.0), "aba_derivatives": ("aba", 4.0)}


def log(*a):
    print(*a, file=sys.stderr, flush=True)


def machine():
    info = {}
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
        for line in out.splitlines():
            k, _, v = line.partition(":")
            info[k.strip()] = v.strip()
    except OSError:
        pass
    flags = set(info.get("Flags", "").split())
    simd = [f for f in ("sse4_2", "avx", "avx2", "fma", "bmi2", "avx512f", "avx512vl", "amx_tile") if f in flags]

    def ver(cmd):
        try:
            return subprocess.run(cmd, capture_output=True, text=True).stdout.splitlines()[0]
        except (OSError, IndexError):
            return "?"

    return {
        "cpu": info.get("Model name", platform.processor() or "?"),
        "vendor": info.get("Vendor ID", "?"),
        "family/model": "%s/%s" % (info.get("CPU family", "?"), info.get("Model", "?")),
        "cpus": info.get("CPU(s)", str(os.cpu_count())),
        "hypervisor": info.get("Hypervisor vendor", "none"),
        "l2/l3": "%s / %s" % (info.get("L2 cache", "?"), info.get("L3 cache", "?")),
        "simd flags": " ".join(simd),
        "load average": " ".join("%.2f" % x for x in os.getloadavg()),
        "c++": ver([os.environ.get("CXX", "g++"), "--version"]),
        "rustc": ver(["rustc", "--version"]),
    }


def read_manifest(wanted):
    rows = []
    with open(os.path.join(PIN_BUILD, "models", "manifest.tsv")) as f:
        for line in f:
            name, nq, nv, floating, src, file = line.rstrip("\n").split("\t")
            if wanted and name not in wanted:
                continue
            rows.append({"name": name, "nq": int(nq), "nv": int(nv), "floating": floating == "1",
                         "src": src, "file": file})
    return rows


def parse_json_lines(text):
    out = []
    for line in text.splitlines():
        line = line.strip()
        if not line:
            continue
        try:
            obj = json.loads(line)
        except json.JSONDecodeError:
            continue
        if isinstance(obj, list):
            out += [o for o in obj if isinstance(o, dict)]
        elif isinstance(obj, dict):
            out.append(obj)
    return [o for o in out if "ns_per_call" in o]


def run_pinocchio(variant, model, reps, states):
    exe = os.path.join(PIN_BUILD, "timings-" + variant)
    cmd = [exe, "--build", variant, "--reps", str(reps), "--states", str(states),
           "%s=%s" % (model["name"], model["file"])]
    p = subprocess.run(cmd, capture_output=True, text=True)
    res = parse_json_lines(p.stdout)
    if p.returncode != 0 or not res:
        log("Pinocchio (%s) failed on %s: %s" % (variant, model["name"], p.stderr.strip()[-500:]))
        return None
    return res[0]


def rigid_model_arg(model):
    # builtin models (puma560) by name, the rest by URDF path
    return model["src"].split(":", 1)[1] if model["src"].startswith("builtin:") else model["src"]


def run_rigid(model):
    cmd = ["cargo", "run", "--quiet", "--release", "-p", "rigid-cli", "--", "bench", rigid_model_arg(model)]
    if model["floating"]:
        cmd.append("--floating")
    cmd.append("--json")
    p = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
    res = parse_json_lines(p.stdout)
    if p.returncode != 0 or not res:
        return None, "`%s` exited %d%s" % (" ".join(cmd), p.returncode,
                                           (": " + p.stderr.strip().splitlines()[-1]) if p.stderr.strip() else
                                           " and printed no JSON with ns_per_call")
    return res[0], None


EXPLICIT_KEYS = [("explicit_mass_matrix", "crba", "M(q) / CRBA"), ("explicit_gravity", "gravity", "g(q) / g"),
                 ("explicit_nle", "nonlinear_effects", "c + g / nle"),
                 ("explicit_inverse_dynamics", "rnea", "M a + c + g / RNEA")]


def run_explicit():
    """The generated explicit model's timings (and rigid's recursive ones, same process), by model."""
    env = dict(os.environ, EXPLICIT_JSON="1")
    p = subprocess.run(["cargo", "bench", "--quiet", "-p", "rigid", "--bench", "explicit"], capture_output=True,
                       text=True, cwd=ROOT, env=env)
    res = parse_json_lines(p.stdout)
    if p.returncode != 0 or not res:
        log("explicit bench failed: " + p.stderr.strip()[-500:])
    return {r["model"]: r for r in res}


def explicit_section(models, explicit_runs, pin_runs, variants):
    """Markdown: the explicit model's ratios to Pinocchio and to rigid's recursive algorithms."""
    out = ["### The explicit model (generated Rust, `rigid explicit MODEL --lang rust`): ratios\n",
           "Per algorithm: explicit / Pinocchio (fastest build) and explicit / rigid's recursive algorithm, "
           "each the median over rounds of the ratio within a round.\n",
           "| model | " + " | ".join("%s vs Pinocchio | vs rigid" % label for _, _, label in EXPLICIT_KEYS) + " |",
           "|---|" + "---:|---:|" * len(EXPLICIT_KEYS)]
    raw = ["", "explicit, ns per call (median over rounds): ",
           "| model | " + " | ".join(k for k, _, _ in EXPLICIT_KEYS) + " |", "|---|" + "---:|" * len(EXPLICIT_KEYS)]
    for m in models:
        n = m["name"]
        runs = explicit_runs.get(n, [])
        if not runs:
            continue
        cells = []
        for key, base, _ in EXPLICIT_KEYS:
            vs_pin = paired_ratio([{"ns_per_call": {base: r["ns_per_call"].get(key)}} for r in runs],
                                  pin_runs[n], variants, base)
            vs_rigid = [r["ns_per_call"][key] / r["ns_per_call"][base] for r in runs
                        if r["ns_per_call"].get(key) and r["ns_per_call"].get(base)]
            cells.append("%s | %s" % ("%.2f" % vs_pin if vs_pin else "–",
                                      "%.2f" % statistics.median(vs_rigid) if vs_rigid else "–"))
        out.append("| %s | %s |" % (n, " | ".join(cells)))
        raw.append("| %s | %s |" % (n, " | ".join(
            fmt_ns(statistics.median([r["ns_per_call"][k] for r in runs])) for k, _, _ in EXPLICIT_KEYS)))
    return out + raw + [""]


def ns(run, key):
    x = run["ns_per_call"].get(key)
    return x if isinstance(x, (int, float)) and x > 0 else None


def paired_ratio(rigid_runs, pin_runs_by_variant, variants, key):
    """Median over rounds of rigid's time / Pinocchio's (fastest build) in the same round: the two
    sides of one round ran back to back, so a slow spell of the machine largely cancels out."""
    ratios = round_ratios(rigid_runs, pin_runs_by_variant, variants, key)
    return statistics.median(ratios) if ratios else None


def round_ratios(rigid_runs, pin_runs_by_variant, variants, key):
    """rigid's time / Pinocchio's (fastest build) within each round."""
    ratios = []
    for i, rr in enumerate(rigid_runs):
        a = ns(rr, key)
        bs = [ns(runs[i], key) for runs in (pin_runs_by_variant[v] for v in variants) if i < len(runs)]
        bs = [b for b in bs if b]
        if a and bs:
            ratios.append(a / min(bs))
    return ratios


def fmt_ns(x):
    if x is None:
        return "–"
    return "%.0f" % x if x >= 100 else "%.1f" % x


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rounds", type=int, default=7, help="interleaved rounds (default 7)")
    ap.add_argument("--cpu", default="auto",
                    help="pin the timed runs to this core ('auto': the idlest one; 'none': no pinning)")
    ap.add_argument("--reps", type=int, default=21, help="Pinocchio: passes over the states per round (default 21)")
    ap.add_argument("--states", type=int, default=1000, help="Pinocchio: random states (default 1000)")
    ap.add_argument("--models", default="", help="comma-separated subset of bench/models.tsv")
    ap.add_argument("--variants", default=os.environ.get("VARIANTS", "header lib"),
                    help="Pinocchio builds to time (header, lib, native; default 'header lib')")
    ap.add_argument("--no-rigid", action="store_true", help="time Pinocchio only")
    ap.add_argument("--json", help="save all raw measurements to this file")
    ap.add_argument("--explicit", action="store_true",
                    help="also time the generated explicit model of puma560 and ur5 in each round")
    args = ap.parse_args()
    t_start = time.time()
    variants = args.variants.split()

    # 1. builds
    env = dict(os.environ, VARIANTS=" ".join(variants))
    t0 = time.time()
    if subprocess.run(["bash", os.path.join(PIN_DIR, "run.sh"), "--build-only"], env=env).returncode != 0:
        sys.exit("building Pinocchio's timing program failed")
    t_pin_build = time.time() - t0
    models = read_manifest(set(filter(None, args.models.split(","))))

    rigid_note = None
    t_rigid_build = 0.0
    if args.no_rigid:
        rigid_note = "rigid not run (--no-rigid)"
    elif shutil.which("cargo") is None:
        rigid_note = "cargo not found: rigid's side is missing"
    else:
        t0 = time.time()
        log("[compare] cargo build --release -p rigid-cli")
        p = subprocess.run(["cargo", "build", "--release", "-p", "rigid-cli"], cwd=ROOT,
                           capture_output=True, text=True)
        t_rigid_build = time.time() - t0
        if p.returncode != 0:
            rigid_note = "rigid-cli does not build: rigid's side is missing\n" + p.stderr.strip()[-1500:]

    # 2. interleaved rounds, on one core
    pinned = pin_to_core(args.cpu)
    pin_runs = {m["name"]: {v: [] for v in variants} for m in models}
    rigid_runs = {m["name"]: [] for m in models}
    explicit_runs = {m["name"]: [] for m in models}
    t_run0 = time.time()
    for r in range(args.rounds):
        if args.explicit:
            log("[compare] round %d/%d  explicit model" % (r + 1, args.rounds))
            for name, res in run_explicit().items():
                if name in explicit_runs:
                    explicit_runs[name].append(res)
        for m in models:
            log("[compare] round %d/%d  %s" % (r + 1, args.rounds, m["name"]))
            order = ["rigid", "pinocchio"] if (r % 2 == 0) else ["pinocchio", "rigid"]
            for side in order:
                if side == "pinocchio":
                    for v in variants:
                        res = run_pinocchio(v, m, args.reps, args.states)
                        if res:
                            pin_runs[m["name"]][v].append(res)
                elif rigid_note is None:
                    res, err = run_rigid(m)
                    if res is None:
                        rigid_note = "rigid's side is missing: " + err
                    else:
                        rigid_runs[m["name"]].append(res)
    t_runs = time.time() - t_run0

    # 3. aggregate: median over rounds; Pinocchio: fastest variant per algorithm
    def med_over(runs, key):
        xs = [run["ns_per_call"][key] for run in runs if isinstance(run["ns_per_call"].get(key), (int, float))]
        return statistics.median(xs) if xs else None

    pin_best, pin_from, pin_all, rigid_best = {}, {}, {}, {}
    extra_keys = []
    for m in models:
        n = m["name"]
        pin_best[n], pin_from[n], pin_all[n], rigid_best[n] = {}, {}, {}, {}
        keys = list(ALGOS)
        for v in variants:
            for run in pin_runs[n][v]:
                for k in run["ns_per_call"]:
                    if k not in keys:
                        keys.append(k)
                    if k not in ALGOS and k not in extra_keys:
                        extra_keys.append(k)
        for k in keys:
            per_v = {v: med_over(pin_runs[n][v], k) for v in variants}
            pin_all[n][k] = per_v
            avail = {v: x for v, x in per_v.items() if x is not None}
            if avail:
                v = min(avail, key=avail.get)
                pin_best[n][k], pin_from[n][k] = avail[v], v
        for k in ALGOS:
            rigid_best[n][k] = med_over(rigid_runs[n], k)

    mach = machine()
    out = []
    out.append("## Machine\n")
    for k, v in mach.items():
        out.append("- %s: %s" % (k, v))
    out.append("")
    out.append("Pinocchio builds timed: %s; each time is the median over %d round(s) of the median over "
               "%d passes through %d random states; a ratio is the median over rounds of the ratio within "
               "each round; Pinocchio's figure is the fastest build per algorithm "
               "(h = header, l = lib, n = native). CRBA: Pinocchio fills the upper triangle only, fastest of "
               "its LOCAL and WORLD conventions; ABA likewise." % (" ".join(variants), args.rounds, args.reps,
                                                                    args.states))
    out.append("Timed runs pinned to: %s." % pinned)
    out.append("")
    have_rigid = any(rigid_runs[m["name"]] for m in models)
    if rigid_note:
        out.append("**Note: %s**\n" % rigid_note.replace("\n", "\n> "))
    # both sides must time the same model: same number of position and velocity coordinates
    for m in models:
        for run in rigid_runs[m["name"]][:1]:
            if (run.get("nq"), run.get("nv")) != (m["nq"], m["nv"]):
                out.append("**Warning: %s: rigid reports nq=%s nv=%s, Pinocchio nq=%d nv=%d: not the same "
                           "model, its ratios mean nothing.**\n" % (m["name"], run.get("nq"), run.get("nv"),
                                                                   m["nq"], m["nv"]))
    # anything else rigid states (e.g. its CRBA convention), once
    said = {}
    for m in models:
        for run in rigid_runs[m["name"]][:1]:
            for k, v in run.items():
                if k not in ("model", "nq", "nv", "ns_per_call") and k not in said:
                    said[k] = v
    for k, v in said.items():
        out.append("- rigid: %s: %s" % (k, json.dumps(v) if not isinstance(v, str) else v))
    if said:
        out.append("")

    hdr = "| model | nq | nv | " + " | ".join(SHORT[k] for k in ALGOS) + " |"
    sep = "|---|---:|---:|" + "---:|" * len(ALGOS)
    if have_rigid:
        out.append("### Ratio rigid / Pinocchio (lower is better for rigid; bars: RNEA ≤ 0.6, CRBA, ABA ≤ 0.7, "
                   "∂RNEA, ∂ABA ≤ 1.0, FK, Jac ≤ 1.2)\n")
        out.append(hdr)
        out.append(sep)
        misses = []
        for m in models:
            n = m["name"]
            cells = []
            for k in ALGOS:
                ratio = paired_ratio(rigid_runs[n], pin_runs[n], variants, k)
                if ratio is None:
                    cells.append("–")
                    continue
                bad = k in TARGET and ratio > TARGET[k]
                if bad:
                    misses.append("%s %s %.2f" % (n, SHORT[k], ratio))
                cells.append(("**%.2f**" if bad else "%.2f") % ratio)
            out.append("| %s | %d | %d | %s |" % (n, m["nq"], m["nv"], " | ".join(cells)))
        out.append("")
        out.append("Bars missed (bold): " + (", ".join(misses) if misses else "none") + "\n")
        spread = [k for k in ALGOS if k in TARGET]
        out.append("Spread of the per-round ratios behind those medians (min–max over %d rounds; bar: no "
                   "round of RNEA, CRBA, ABA above 0.9):\n"
                   % args.rounds)
        out.append("| model | " + " | ".join(SHORT[k] for k in spread) + " |")
        out.append("|---|" + "---:|" * len(spread))
        for m in models:
            n = m["name"]
            cells = []
            for k in spread:
                r = round_ratios(rigid_runs[n], pin_runs[n], variants, k)
                if not r:
                    cells.append("–")
                    continue
                bad = k in ROUND_MAX and max(r) > ROUND_MAX[k]
                if bad:
                    misses.append("%s %s round max %.2f" % (n, SHORT[k], max(r)))
                cells.append(("%.2f–**%.2f**" if bad else "%.2f–%.2f") % (min(r), max(r)))
            out.append("| %s | %s |" % (n, " | ".join(cells)))
        out.append("")
        out.append("rigid's derivatives over its own algorithm (median over rounds of the ratio within each "
                   "run; bar ≤ %.0f on talos):\n" % max(b for _, b in OWN.values()))
        out.append("| model | " + " | ".join("%s / %s" % (SHORT[k], SHORT[base]) for k, (base, _) in OWN.items())
                   + " |")
        out.append("|---|" + "---:|" * len(OWN))
        for m in models:
            n = m["name"]
            cells = []
            for k, (base, bar) in OWN.items():
                r = [ns(run, k) / ns(run, base) for run in rigid_runs[n] if ns(run, k) and ns(run, base)]
                if not r:
                    cells.append("–")
                    continue
                x = statistics.median(r)
                bad = n == "talos" and x > bar
                if bad:
                    misses.append("%s %s/%s %.2f" % (n, SHORT[k], SHORT[base], x))
                cells.append(("**%.2f**" if bad else "%.2f") % x)
            out.append("| %s | %s |" % (n, " | ".join(cells)))
        out.append("")
        out.append("Bars missed, all (bold): " + (", ".join(misses) if misses else "none") + "\n")
        out.append("### rigid, ns per call\n")
        out.append(hdr)
        out.append(sep)
        for m in models:
            n = m["name"]
            out.append("| %s | %d | %d | %s |" % (n, m["nq"], m["nv"],
                                                  " | ".join(fmt_ns(rigid_best[n].get(k)) for k in ALGOS)))
        out.append("")
    if args.explicit:
        out += explicit_section(models, explicit_runs, pin_runs, variants)
    out.append("### Pinocchio %s, ns per call (fastest build per algorithm)\n" % pin_version())
    out.append(hdr)
    out.append(sep)
    for m in models:
        n = m["name"]
        cells = ["%s %s" % (fmt_ns(pin_best[n].get(k)), pin_from[n].get(k, "?")[0]) if pin_best[n].get(k) else "–"
                 for k in ALGOS]
        out.append("| %s | %d | %d | %s |" % (n, m["nq"], m["nv"], " | ".join(cells)))
    out.append("")
    if extra_keys:
        out.append("### Pinocchio, other timings (ns per call, fastest build)\n")
        out.append("| model | " + " | ".join(extra_keys) + " |")
        out.append("|---|" + "---:|" * len(extra_keys))
        for m in models:
            n = m["name"]
            out.append("| %s | %s |" % (n, " | ".join(fmt_ns(pin_best[n].get(k)) for k in extra_keys)))
        out.append("")
    if len(variants) > 1:
        out.append("### Pinocchio per build (ns per call: %s)\n" % " / ".join(variants))
        out.append(hdr)
        out.append(sep)
        for m in models:
            n = m["name"]
            cells = [" / ".join(fmt_ns(pin_all[n].get(k, {}).get(v)) for v in variants) for k in ALGOS]
            out.append("| %s | %d | %d | %s |" % (n, m["nq"], m["nv"], " | ".join(cells)))
        out.append("")
    out.append("Times: Pinocchio build %.0f s, rigid build %.0f s, interleaved runs %.0f s, total %.0f s." % (
        t_pin_build, t_rigid_build, t_runs, time.time() - t_start))
    print("\n".join(out))

    if args.json:
        with open(args.json, "w") as f:
            json.dump({"machine": mach, "variants": variants, "rounds": args.rounds, "rigid_note": rigid_note,
                       "pinocchio": pin_runs, "rigid": rigid_runs, "pinocchio_best": pin_best,
                       "pinocchio_best_from": pin_from, "rigid_median": rigid_best,
                       "explicit": explicit_runs}, f, indent=1)


def idlest_cpu(allowed, seconds=0.5):
    """The core of `allowed` with the most idle time over `seconds` (from /proc/stat)."""
    def idle():
        out = {}
        with open("/proc/stat") as f:
            for line in f:
                parts = line.split()
                if parts[0].startswith("cpu") and parts[0] != "cpu":
                    out[int(parts[0][3:])] = int(parts[4]) + int(parts[5])  # idle + iowait
        return out
    a = idle()
    time.sleep(seconds)
    b = idle()
    return max(sorted(allowed), key=lambda c: b.get(c, 0) - a.get(c, 0))


def pin_to_core(cpu):
    """Pin this process (and so every benchmark it starts) to one core; returns what was done."""
    if cpu == "none" or not hasattr(os, "sched_setaffinity"):
        return "not pinned"
    allowed = os.sched_getaffinity(0)
    c = idlest_cpu(allowed) if cpu == "auto" else int(cpu)
    if c not in allowed:
        sys.exit("--cpu %s: not one of this process's cores %s" % (cpu, sorted(allowed)))
    os.sched_setaffinity(0, {c})
    log("[compare] timed runs pinned to core %d" % c)
    return "core %d (of %s)" % (c, ", ".join(map(str, sorted(allowed))))


def pin_version():
    try:
        import importlib.metadata as md
        return md.version("pin")
    except Exception:
        return ""


if __name__ == "__main__":
    main()
