#!/usr/bin/env python3
"""Floating-point operations per call of rigid's algorithms, counted in the running code.

    python3 bench/flops.py                         # RNEA, CRBA, ABA, M⁻¹, both derivatives; ur5, talos, puma560
    python3 bench/flops.py --models ur5 --algos rnea,crba --json out.json
    python3 bench/flops.py --pinocchio             # also Pinocchio's compiled library, same method
    python3 bench/flops.py --no-build --times run.json   # + ns per call from `compare.py --json run.json`
    python3 bench/flops.py --batch                 # the SIMD batch kernels per state, against the single call

Method (no hardware counters needed): `rigid bench MODEL --only ALGO --states N --repetitions 1`
runs under Valgrind's callgrind with collection switched on only inside the timing loop
(`--toggle-collect=rigid::timing::pass`: one call of the algorithm per state, in a warm-up pass
and one timed pass, so `2 N` calls; the public function itself may be inlined there) and one
execution count per machine instruction (`--dump-instr=yes`). Each executed instruction is looked up in
`objdump -d` of the same binary and classified: `mulsd` = 1 multiplication, `mulpd` on an xmm
register = 2 (one per lane), `vmulpd` on ymm = 4, `add`/`sub` likewise are additions, a fused
multiply-add is one of each; `div` and `sqrt` are counted apart; negation (`xorpd`), `abs`
(`andpd`), compares and moves are not arithmetic and are not counted. Dividing by the number of
calls gives the operations of one call *of the code as
compiled*: everything the public function does (argument checks such as the quaternion norm,
sine and cosine, the joint transforms, the recursion), nothing outside it but the loop's clock reads (integer) and one division per pass (amortised
over the `N` calls of the pass, so not counted in the `div` column's integer part).

--pinocchio: the same count on Pinocchio's timing program (`bench/pinocchio`, the `lib` build:
the wheel's `libpinocchio_default.so`, built by `python3 bench/compare.py` or
`bash bench/pinocchio/run.sh --build-only`), collection switched on inside `pinocchio::rnea<double…`
(`crba`, `aba`, `computeMinverse`, `computeRNEADerivatives`, `computeABADerivatives`) wherever it is
called, callees included, divided by the number of calls into it read from callgrind's call graph.
Its CRBA and ABA figures average the LOCAL and WORLD conventions (the program times both; CRBA is
also called inside its `cholesky_fd`). Callgrind's `--toggle-collect` flips collection on entry and
again on exit, so a toggled function calling another toggled one would switch it off for the
callee: the derivatives' public functions call `impl::` overloads of the same name, some inlined
into the timing program, some not. So a first run with collection on throughout gives the call
graph, and only the outermost functions of the family (those called from outside it) are toggled.

--batch: the SIMD batch kernels (`rigid::multibody::batch`, `rnea`, `aba`, `crba`, `crba_lower`,
`rnea_derivatives`),
per state. `rigid bench MODEL --batch --only ALGO --threads 1 --states N --repetitions 1` runs
under callgrind with collection on inside `rigid::multibody::batch::simd::Lanes::run` (one call
per thread's block of states: the transposition into the lanes, the pack kernels, the
transposition out; not the input checks before it), in an untimed and a timed pass, so `2 N`
states (N a multiple of 8, so that no pack has idle lanes). Valgrind runs AVX2 but not AVX-512,
so the counted code is the 4-lane (AVX2) kernel; the table says which width ran. The single
call's count (`crba` for both CRBA rows) sits beside it, and each is timed natively in the same
run (`rigid bench --batch --threads 1`, pinned to one core: the loop of single calls and the
batch on one thread, median of the passes) for flops per ns and the fraction of the core's peak.

Self-checks: the per-call count must not depend on how many calls were made (N and 2N states give
the same count up to the data-dependent branches of sin/cos range reduction, < 1 %), for rigid and
for Pinocchio; and Pinocchio's counting run must collect the instructions per call that the first
run's call graph gives as the outermost functions' inclusive cost (a wrongly nested toggle collects
a few instructions per call). The script prints both counts and fails when a check is off by more
than 1 %.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import compare  # noqa: E402  (model manifest, rigid's model argument)

EXE = os.path.join(ROOT, "target", "release", "rigid")
LOOP = "rigid::timing::pass"
BATCH_RUN = "rigid::multibody::batch::simd::Lanes::run"
INSN = re.compile(r"^\s*([0-9a-f]+):\s+(\S+)\s*(.*)$")


def classify(mnemonic, operands):
    """(multiplications, additions, divisions, square roots) of one double-precision instruction."""
    m = mnemonic
    if m.startswith("v"):
        m = m[1:]
    lanes = 1
    if m.endswith("pd"):
        lanes = 4 if "ymm" in operands else 8 if "zmm" in operands else 2
    elif not m.endswith("sd"):
        return None  # integer, single precision or not arithmetic
    base = m[:-2]
    if base in ("mul",):
        return (lanes, 0, 0, 0)
    if base in ("add", "sub", "hadd", "hsub", "addsub"):
        return (0, lanes, 0, 0)
    if re.match(r"^f(n)?m(add|sub)(132|213|231)$", base):
        return (lanes, lanes, 0, 0)
    if base == "div":
        return (0, 0, lanes, 0)
    if base == "sqrt":
        return (0, 0, 0, lanes)
    return None


def disassemble(exe):
    ops = {}
    out = subprocess.run(["objdump", "-d", "--no-show-raw-insn", exe], capture_output=True, text=True,
                         check=True).stdout
    for line in out.splitlines():
        mt = INSN.match(line)
        if not mt:
            continue
        c = classify(mt.group(2), mt.group(3))
        if c:
            ops[int(mt.group(1), 16)] = c
    return ops


def parse_callgrind(path):
    """Execution count per (object, instruction address), self cost only; and the call graph:
    {(caller, callee): [calls, inclusive instructions]}."""
    counts, edges, names = {}, {}, {}
    ob = fn = cfn = None
    last = 0
    edge = None  # the call whose inclusive cost is on the next line
    with open(path) as f:
        for line in f:
            line = line.rstrip("\n")
            if not line or line.startswith("#"):
                continue
            key, eq, val = line.partition("=")
            if eq and key in ("ob", "cob", "fn", "cfn", "fl", "fi", "fe", "cfi", "cfl"):
                mt = re.match(r"\((\d+)\)(?: (.*))?$", val)
                kind = "ob" if key in ("ob", "cob") else "fn" if key in ("fn", "cfn") else "fl"
                name = val
                if mt:
                    if mt.group(2) is not None:
                        names[(kind, mt.group(1))] = mt.group(2)
                    name = names.get((kind, mt.group(1)), val)
                if key == "ob":
                    ob = name
                elif key == "fn":
                    fn = name
                elif key == "cfn":
                    cfn = name
                continue
            if line.startswith("calls="):
                edge = edges.setdefault((fn, cfn), [0, 0])
                edge[0] += int(line.split("=")[1].split()[0])
                continue
            if eq:
                continue
            parts = line.split()
            pos = parts[0]
            if pos.startswith("0x"):
                addr = int(pos, 16)
            elif pos.startswith("+"):
                addr = last + int(pos[1:])
            elif pos.startswith("-"):
                addr = last - int(pos[1:])
            elif pos == "*":
                addr = last
            else:
                continue
            last = addr
            cost = int(parts[-1]) if len(parts) >= 3 else 0
            if edge is not None:  # the call's inclusive cost, not an instruction of `fn`
                edge[1] += cost
                edge = None
                continue
            counts[(ob, addr)] = counts.get((ob, addr), 0) + cost
    return counts, edges


def outermost(edges, family):
    """The functions of `family` (a regular expression) called from outside it, the number of
    those calls and their inclusive instructions. Fails if one of them is also called from inside
    the family: toggling collection on both would switch it off in the nested call."""
    def inside(name):
        return re.search(family, name or "") is not None
    outer, calls, incl = set(), 0, 0
    for (fn, cfn), (n, ir) in edges.items():
        if inside(cfn) and not inside(fn):
            outer.add(cfn)
            calls += n
            incl += ir
    nested = {cfn for (fn, cfn) in edges if inside(cfn) and inside(fn)} & outer
    if nested:
        raise RuntimeError("called both from outside and inside /%s/: %s" % (family, sorted(nested)))
    return sorted(outer), calls, incl


def tally(counts, calls):
    """Operations per call from instruction execution counts (objects disassembled on demand)."""
    tot = [0, 0, 0, 0]
    for (ob, addr), n in counts.items():
        if ob not in DISASSEMBLY:
            DISASSEMBLY[ob] = disassemble(ob) if ob and os.path.exists(ob) else {}
        c = DISASSEMBLY[ob].get(addr)
        if c:
            for k in range(4):
                tot[k] += c[k] * n
    return {"calls": calls, "mul": tot[0] / calls, "add": tot[1] / calls, "div": tot[2] / calls,
            "sqrt": tot[3] / calls, "instructions": sum(counts.values()) / calls}


DISASSEMBLY = {}


def count(model, algo, states):
    """rigid: one call of `algo` per state in a warm-up and a timed pass."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "cg.out")
        cmd = ["valgrind", "--tool=callgrind", "--dump-instr=yes", "--toggle-collect=" + LOOP,
               "--callgrind-out-file=" + out, EXE, "bench", compare.rigid_model_arg(model)]
        if model["floating"]:
            cmd.append("--floating")
        cmd += ["--only", algo, "--states", str(states), "--repetitions", "1", "--json"]
        subprocess.run(cmd, cwd=ROOT, capture_output=True, check=True)
        counts, _ = parse_callgrind(out)
    return tally(counts, 2 * states)  # warm-up pass + one timed pass


def count_batch(model, algo, states):
    """rigid's batch kernel `algo`, per state: an untimed and a timed pass of `states` states
    on one thread; also the number of lanes the run used."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "cg.out")
        cmd = ["valgrind", "--tool=callgrind", "--dump-instr=yes", "--toggle-collect=" + BATCH_RUN,
               "--callgrind-out-file=" + out, EXE, "bench", compare.rigid_model_arg(model)]
        if model["floating"]:
            cmd.append("--floating")
        cmd += ["--batch", "--only", algo, "--threads", "1", "--states", str(states), "--repetitions", "1",
                "--json"]
        p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, check=True)
        counts, _ = parse_callgrind(out)
    result = tally(counts, 2 * states)
    result["lanes"] = json.loads(p.stdout)["lanes"]
    return result


def time_batch(model, states=1000, reps=21):
    """Native states per second, one thread: {algo: (loop of single calls, batch)}."""
    cmd = [EXE, "bench", compare.rigid_model_arg(model), "--batch", "--threads", "1", "--json",
           "--states", str(states), "--repetitions", str(reps)]
    if model["floating"]:
        cmd.insert(3, "--floating")
    rates = json.loads(subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, check=True).stdout)
    return {a: (r["loop"], r["threads_1"]) for a, r in rates["states_per_second"].items()}, rates["lanes"]


def main_batch(args, models):
    """--batch: flops per state of the batch kernels and of the single call, and their rates."""
    states = -(-args.states // 8) * 8
    pinned = compare.pin_to_core(args.cpu)
    rows, bad = [], []
    print("| model | nv | algorithm | single call mul + add | batch mul + add per state (lanes) | check (2N) "
          "| batch instructions per state | single instructions |")
    print("|---|---:|---|---:|---:|---|---:|---:|")
    for m in models:
        single = {}
        for algo in args.algos.split(","):
            key = "crba" if algo == "crba_lower" else algo
            if key not in single:
                single[key] = count(m, key, args.states)
            s = single[key]
            a = count_batch(m, algo, states)
            b = count_batch(m, algo, 2 * states)
            fa, fb = a["mul"] + a["add"], b["mul"] + b["add"]
            ok = fa > 0 and abs(fa - fb) <= 0.01 * fa
            if not ok:
                bad.append("%s %s batch: %.0f vs %.0f" % (m["name"], algo, fa, fb))
            rows.append((m, algo, s, a))
            print("| %s | %d | %s | %.0f | %.0f (%d) | %s | %.0f | %.0f |" % (
                m["name"], m["nv"], algo, s["mul"] + s["add"], fa, a["lanes"],
                "%.0f ok" % fb if ok else "**%.0f**" % fb, a["instructions"], s["instructions"]))
            sys.stdout.flush()
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"%s/%s" % (m["name"], algo): {"single": s, "batch": a} for m, algo, s, a in rows}, f, indent=1)
    if not args.no_time:
        timed, lanes = {}, set()
        for m, _, _, _ in rows:
            if m["name"] not in timed:
                timed[m["name"]], w = time_batch(m)
                lanes.add(w)
        print()
        print("Rates: `rigid bench --batch --threads 1` (1000 states, 21 passes, median, %s lanes), %s, "
              "load %s; peak of one core at %.2f GHz: %s" % (
                  "/".join(map(str, sorted(lanes))), pinned, " ".join("%.2f" % x for x in os.getloadavg()), args.ghz,
                  ", ".join("%s %.1f flops/ns" % (k, args.ghz * c) for k, c in PEAK_PER_CYCLE.items())))
        print()
        print("| model | algorithm | single ns | single flops/ns | %% of peak (%s) | batch ns per state "
              "| batch flops/ns | %% of peak (%s) |" % (PEAKS, PEAKS))
        print("|---|---|---:|---:|---:|---:|---:|---:|")
        for m, algo, s, a in rows:
            loop, batch = timed[m["name"]][algo]
            cells = []
            for flops, rate in ((s["mul"] + s["add"], loop), (a["mul"] + a["add"], batch)):
                ns = 1e9 / rate
                r = flops / ns
                cells += ["%.0f" % ns, "%.2f" % r, " / ".join("%.1f" % (100 * r / (args.ghz * c))
                                                             for c in PEAK_PER_CYCLE.values())]
            print("| %s | %s | %s |" % (m["name"], algo, " | ".join(cells)))
    if bad:
        sys.exit("self-check failed: " + "; ".join(bad))


# Pinocchio's functions, regular expressions over callgrind's demangled names (which start with the
# return type). The derivatives' public overloads forward to `impl::` overloads of the same name
# (`computeABADerivatives(model, data, q, v, tau)` -> `impl::…(…, q, v, tau)` -> `impl::…(…, q, v,
# tau, ddq_dq, ddq_dv, Minv)`), some inlined into the timing program, some not: their family takes
# both namespaces, and only its outermost members switch collection on (see `outermost`).
PIN_FAMILY = {"rnea": r"pinocchio::rnea<double", "crba": r"pinocchio::crba<double",
              "aba": r"pinocchio::aba<double", "minverse": r"pinocchio::computeMinverse<double",
              "rnea_derivatives": r"pinocchio::(impl::)?computeRNEADerivatives<double",
              "aba_derivatives": r"pinocchio::(impl::)?computeABADerivatives<double"}
PIN_GRAPH = {}  # (model, states) -> call graph of the timing program with collection on throughout


def run_pinocchio(model, states, toggles=(), variant="lib"):
    """Pinocchio's timing program under callgrind: (instruction counts, call graph)."""
    exe = os.path.join(compare.PIN_BUILD, "timings-" + variant)
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "cg.out")
        cmd = ["valgrind", "--tool=callgrind", "--dump-instr=yes", "--callgrind-out-file=" + out]
        cmd += ["--toggle-collect=" + name for name in toggles]
        cmd += [exe, "--build", variant, "--reps", "1", "--states", str(states),
                "%s=%s" % (model["name"], model["file"])]
        subprocess.run(cmd, capture_output=True, check=True)
        return parse_callgrind(out)


def count_pinocchio(model, algo, states):
    """Pinocchio 4.1 (the `lib` build: the wheel's compiled library): every call of the function
    during its timing program (its LOCAL and WORLD conventions alike, and the calls inside
    `cholesky_fd`), per call, callees included (the derivatives' passes, Eigen's products).

    Two runs: one with collection on throughout gives the call graph, hence the outermost
    functions of the family and their inclusive instructions per call; the counting run toggles
    collection on exactly those, and must collect the same instructions per call (within 1 %,
    `inclusive` in the result), which a wrongly nested toggle would not."""
    key = (model["name"], states)
    if key not in PIN_GRAPH:
        PIN_GRAPH[key] = run_pinocchio(model, states)[1]
    outer, calls, incl = outermost(PIN_GRAPH[key], PIN_FAMILY[algo])
    if calls == 0:
        return None
    counts, edges = run_pinocchio(model, states, outer)
    if outermost(edges, PIN_FAMILY[algo])[1] != calls:
        raise RuntimeError("%s %s: the counting run made a different number of calls" % (model["name"], algo))
    result = tally(counts, calls)
    result["inclusive"] = incl / calls
    return result


def cpu_ghz():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("cpu MHz"):
                    return float(line.split(":")[1]) / 1000
    except OSError:
        pass
    return 0.0


def cpu_info():
    """The first processor's fields of /proc/cpuinfo (empty where there is none)."""
    info = {}
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if not line.strip():
                    break
                key, _, value = line.partition(":")
                info[key.strip()] = value.strip()
    except OSError:
        pass
    return info


def zen5_or_later(info):
    """An AMD core of family 26 (0x1A, Zen 5) or later with AVX-512F: its FP pipes are 512 bits
    wide (two FMA pipes: 32 double-precision operations per cycle). Zen 4 (family 25) runs
    AVX-512 on 256-bit pipes, and Intel cores have one or two 512-bit FMA units by model, so no
    AVX-512 peak is assumed for them."""
    try:
        family = int(info.get("cpu family", "0"))
    except ValueError:
        return False
    return info.get("vendor_id") == "AuthenticAMD" and family >= 26 and "avx512f" in info.get("flags", "").split()


# double-precision operations per cycle and core: two 256-bit FMA pipes (AVX2: 2 x 4 lanes x 2) for
# the hardware's peak; on a Zen 5, two 512-bit FMA pipes (2 x 8 x 2); what a generic x86-64 build
# can issue (SSE2, no FMA): two 128-bit multiplies and two 128-bit additions per cycle
PEAK_PER_CYCLE = {"AVX2 FMA": 16, "SSE2": 8}
if zen5_or_later(cpu_info()):
    PEAK_PER_CYCLE = {"AVX-512 FMA": 32, **PEAK_PER_CYCLE}
PEAKS = " / ".join(PEAK_PER_CYCLE)


def rate_table(result, times_file, ghz):
    """Markdown: flops, ns per call (median over compare.py's rounds), flops per ns, % of peak."""
    with open(times_file) as f:
        times = json.load(f)
    rows = [("| model | algorithm | rigid mul + add | rigid ns | flops/ns | %% of peak (" + PEAKS + " at %.2f GHz) "
             "| Pinocchio mul + add | Pinocchio ns | flops/ns |") % ghz,
            "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for model, algos in result.items():
        for algo, a in algos.items():
            if algo.endswith("_pinocchio"):
                continue
            flops = a["mul"] + a["add"]
            ns = (times.get("rigid_median", {}).get(model) or {}).get(algo)
            p = algos.get(algo + "_pinocchio")
            pns = (times.get("pinocchio_best", {}).get(model) or {}).get(algo)
            rate = flops / ns if ns else None
            peak = ["%.1f" % (100 * rate / (ghz * c)) if rate and ghz else "–" for c in PEAK_PER_CYCLE.values()]
            rows.append("| %s | %s | %.0f | %s | %s | %s | %s | %s | %s |" % (
                model, algo, flops, "%.0f" % ns if ns else "–", "%.2f" % rate if rate else "–", " / ".join(peak),
                "%.0f" % (p["mul"] + p["add"]) if p else "–", "%.0f" % pns if pns else "–",
                "%.2f" % ((p["mul"] + p["add"]) / pns) if p and pns else "–"))
    return "\n".join(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--models", default="ur5,talos,puma560")
    ap.add_argument("--algos", default="rnea,crba,aba,minverse,rnea_derivatives,aba_derivatives")
    ap.add_argument("--states", type=int, default=50)
    ap.add_argument("--json", help="save the counts to this file")
    ap.add_argument("--no-build", action="store_true", help="use target/release/rigid as it is")
    ap.add_argument("--times", help="a `bench/compare.py --json` file: add ns per call, flops per ns and the "
                    "fraction of the core's peak double-precision rate")
    ap.add_argument("--ghz", type=float, default=cpu_ghz(),
                    help="clock for the peak rate (default: /proc/cpuinfo's, which under a VM may be the nominal "
                         "clock, not the one the core runs at: BENCHMARKS.md measures it)")
    ap.add_argument("--pinocchio", action="store_true",
                    help="also count Pinocchio's compiled library (bench/pinocchio's timing program, lib build)")
    ap.add_argument("--batch", action="store_true",
                    help="count the SIMD batch kernels per state (algorithms rnea,aba,crba,crba_lower,rnea_derivatives) and time them")
    ap.add_argument("--no-time", action="store_true", help="--batch: count only")
    ap.add_argument("--cpu", default="auto", help="--batch timing: the core to pin to (see compare.py)")
    args = ap.parse_args()
    if args.batch and args.algos == ap.get_default("algos"):
        args.algos = "rnea,aba,crba,crba_lower,rnea_derivatives"
    if args.batch and args.models == ap.get_default("models"):
        args.models = "ur5,panda,solo12,talos"
    if shutil.which("valgrind") is None or shutil.which("objdump") is None:
        sys.exit("needs valgrind (callgrind) and objdump")
    if not args.no_build:
        subprocess.run(["cargo", "build", "--release", "-p", "rigid-cli"], cwd=ROOT, check=True)
    models = compare.read_manifest(set(args.models.split(",")))
    if args.batch:
        return main_batch(args, models)
    result = {}
    print("| model | nv | algorithm | code | mul | add | mul + add | div | sqrt | instructions | check (2N states) |")
    print("|---|---:|---|---|---:|---:|---:|---:|---:|---:|---|")
    bad = []
    for m in models:
        for algo in args.algos.split(","):
            a = count(m, algo, args.states)
            b = count(m, algo, 2 * args.states)
            flops_a, flops_b = a["mul"] + a["add"], b["mul"] + b["add"]
            ok = flops_a > 0 and abs(flops_a - flops_b) <= 0.01 * flops_a
            if not ok:
                bad.append("%s %s: %.0f vs %.0f" % (m["name"], algo, flops_a, flops_b))
            result.setdefault(m["name"], {})[algo] = a
            print("| %s | %d | %s | rigid | %.0f | %.0f | %.0f | %.1f | %.1f | %.0f | %s |" % (
                m["name"], m["nv"], algo, a["mul"], a["add"], flops_a, a["div"], a["sqrt"], a["instructions"],
                "%.0f ok" % flops_b if ok else "**%.0f**" % flops_b))
            if args.pinocchio:
                p = count_pinocchio(m, algo, args.states)
                result[m["name"]][algo + "_pinocchio"] = p
                if p:
                    q = count_pinocchio(m, algo, 2 * args.states)
                    flops_p, flops_q = p["mul"] + p["add"], q["mul"] + q["add"]
                    ok = abs(flops_p - flops_q) <= 0.01 * flops_p
                    if not ok:
                        bad.append("%s %s (Pinocchio): %.0f vs %.0f" % (m["name"], algo, flops_p, flops_q))
                    whole = abs(p["instructions"] - p["inclusive"]) <= 0.01 * p["inclusive"]
                    if not whole:
                        bad.append("%s %s (Pinocchio): %.0f instructions collected per call, %.0f executed" % (
                            m["name"], algo, p["instructions"], p["inclusive"]))
                    print("| %s | %d | %s | Pinocchio (lib) | %.0f | %.0f | %.0f | %.1f | %.1f | %.0f | %s, %d calls |" % (
                        m["name"], m["nv"], algo, p["mul"], p["add"], flops_p, p["div"], p["sqrt"],
                        p["instructions"], "%.0f ok" % flops_q if ok else "**%.0f**" % flops_q, p["calls"]))
            sys.stdout.flush()
    if args.json:
        with open(args.json, "w") as f:
            json.dump(result, f, indent=1)
    if args.times:
        print()
        print(rate_table(result, args.times, args.ghz))
    if bad:
        sys.exit("self-check failed: " + "; ".join(bad))


if __name__ == "__main__":
    main()
