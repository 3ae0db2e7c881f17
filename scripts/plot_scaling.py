#!/usr/bin/python3
"""Pairs and plots sinew's forward-dynamics benchmarks (benchmarks/sinew_benchmarks.cpp).

Reads Google Benchmark JSON (default build/benchmarks.json; CPU time per evaluation, the fastest repetition
when there are several), prints per model sinew's time next to Simbody's and their ratio, the wire Jacobian
and wire-force times, and the log-log slopes of time against links over 30..1000 links; writes a log-log
plot of time per evaluation against links, one panel per variant (bare, loops, wires, loops and wires), one
line per engine and family, the slopes in the legend.

usage: /usr/bin/python3 scripts/plot_scaling.py [benchmarks.json] [--png build/forward_dynamics_scaling.png]
                                                 [--markdown]
Targets (docs/performance.md): sinew's slope <= 1.1, sinew >= 15x faster than Simbody on `wholebody`, and
`wholebody_bare` at or below the hand-written ABA's time.
"""
import argparse
import json
import math
import re
import sys
from collections import defaultdict

TO_US = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}
ENGINES = ["sinew", "sinew_balanced", "simbody", "simbody_fused", "mujoco", "aba"]
SINEW_ENGINES = ["sinew", "sinew_balanced"]
VARIANTS = ["bare", "loops", "wires", "loops_wires"]
VARIANT_TITLES = {"bare": "bare tree", "loops": "+ loops", "wires": "+ wires (10 per link)",
                  "loops_wires": "+ loops + wires"}
FAMILY_MODEL = re.compile(r"^(chain|tree)(\d+)(?:_(loops_wires|loops|wires))?$")
WHOLEBODY_MODEL = re.compile(r"^wholebody(?:_(bare|loops|wires))?$")
FIT_RANGE = (30, 1000)  # links: the smallest sizes are dominated by fixed costs
SLOPE_TARGET = 1.1
RATIO_TARGET = 15.0  # docs/performance.md: sinew against Simbody's lean fused element on wholebody
MUJOCO_RATIO_TARGET = 25.0  # and against MuJoCo on the same model
NOISY_CV = 0.1


def read_results(path):
    """({benchmark name: (time in us, counters)}, context, noisy). The time is the benchmark thread's CPU
    time per evaluation (every engine runs on one thread), which other processes on the machine do not
    inflate as they do wall-clock time. With --benchmark_repetitions a benchmark runs several times: its
    time is the fastest repetition, and `noisy` lists those whose repetitions vary by more than NOISY_CV
    (coefficient of variation). Skipped benchmarks (SkipWithError) are reported and left out."""
    with open(path) as f:
        document = json.load(f)
    samples, counters, noisy = defaultdict(list), {}, []
    for run in document["benchmarks"]:
        name = run.get("run_name", run["name"])
        if run.get("error_occurred"):
            print(f"skipped: {name}: {run.get('error_message', '')}", file=sys.stderr)
            continue
        if run.get("run_type") == "aggregate":
            if run.get("aggregate_name") == "cv" and run["cpu_time"] > NOISY_CV:
                noisy.append((name, run["cpu_time"]))
            continue
        # Benchmarks registered with UseRealTime (several threads) are named .../real_time: their wall time.
        time = run["real_time"] if name.endswith("/real_time") else run["cpu_time"]
        samples[name].append(time * TO_US[run["time_unit"]])
        counters.setdefault(name, run)
    return {name: (min(values), counters[name]) for name, values in samples.items()}, \
        document.get("context", {}), noisy


def describe_machine(context):
    """One line on where and when the results were measured, from the JSON's context."""
    parts = [context.get("date", "?")]
    if "cpu_model" in context:
        parts.append(context["cpu_model"])
    parts.append(f"{context.get('num_cpus', '?')} CPUs at {context.get('mhz_per_cpu', '?')} MHz")
    if "load_avg" in context:
        parts.append("load average " + " ".join(f"{x:.2f}" for x in context["load_avg"]))
    return ", ".join(parts)


def parse_model(model):
    """(family, variant, links-from-name) for a family or wholebody model, else None."""
    m = FAMILY_MODEL.match(model)
    if m:
        return m.group(1), m.group(3) or "bare", int(m.group(2))
    m = WHOLEBODY_MODEL.match(model)
    if m:
        return "wholebody", m.group(1) or "loops_wires", None
    return None


def fit_slope(points):
    """Least-squares slope of log(time) against log(links) over FIT_RANGE; None with fewer than 2 points."""
    xs, ys = [], []
    for links, time in points:
        if FIT_RANGE[0] <= links <= FIT_RANGE[1]:
            xs.append(math.log(links))
            ys.append(math.log(time))
    if len(xs) < 2:
        return None
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else None


def fmt(value, digits=1):
    return "-" if value is None else f"{value:.{digits}f}"


def print_table(header, rows, markdown):
    if markdown:
        print("| " + " | ".join(header) + " |")
        print("|" + "|".join("---" if i == 0 else "---:" for i in range(len(header))) + "|")
        for row in rows:
            print("| " + " | ".join(row) + " |")
    else:
        widths = [max(len(header[i]), *(len(r[i]) for r in rows)) if rows else len(header[i])
                  for i in range(len(header))]
        print("  ".join(h.ljust(w) if i == 0 else h.rjust(w) for i, (h, w) in enumerate(zip(header, widths))))
        for row in rows:
            print("  ".join(c.ljust(w) if i == 0 else c.rjust(w) for i, (c, w) in enumerate(zip(row, widths))))
    print()


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("json", nargs="?", default="build/benchmarks.json")
    parser.add_argument("--png", default="build/forward_dynamics_scaling.png")
    parser.add_argument("--markdown", action="store_true", help="print the tables as Markdown")
    args = parser.parse_args()
    results, context, noisy = read_results(args.json)
    print(f"{args.json}: {describe_machine(context)}")
    print()

    # Forward dynamics, paired per model, in the order the benchmarks ran.
    models, fd = [], defaultdict(dict)  # fd[model][engine] = (time, counters)
    for name, value in results.items():
        parts = name.split("/")
        if len(parts) == 3 and parts[0] == "ForwardDynamics" and parts[1] in ENGINES:
            fd[parts[2]][parts[1]] = value
            if parts[2] not in models:
                models.append(parts[2])
    rows = []
    for model in models:
        engines = fd[model]
        counters = next(iter(engines.values()))[1]
        t = {e: engines[e][0] if e in engines else None for e in ENGINES}
        ratio = t["simbody"] / t["sinew"] if t["sinew"] and t["simbody"] else None
        fused_ratio = t["simbody_fused"] / t["sinew"] if t["sinew"] and t["simbody_fused"] else None
        mujoco_ratio = t["mujoco"] / t["sinew"] if t["sinew"] and t["mujoco"] else None
        rows.append([model] + [str(int(counters.get(c, 0))) for c in ("links", "dof", "loops", "wires")] +
                    [fmt(t[e]) for e in ENGINES] + [fmt(ratio, 2), fmt(fused_ratio, 2), fmt(mujoco_ratio, 2)])
    print("Forward dynamics, one evaluation (us); ratio = peer time / sinew time (default schedule)")
    print_table(["model", "links", "dof", "loops", "wires"] + [f"{e} us" for e in ENGINES] +
                ["simbody/sinew", "fused/sinew", "mujoco/sinew"], rows, args.markdown)

    # The wire benchmarks.
    wire_rows = []
    for model in models + [m for m in (n.split("/", 1)[1] for n in results if n.startswith("WireJacobian/"))
                           if m not in models]:
        jac, sparse, forces = (results.get(kind + model) for kind in ("WireJacobian/", "WireJacobianSparse/", "WireForces/"))
        if not jac and not forces:
            continue
        counters = (jac or forces)[1]
        ratio = sparse[0] / forces[0] if sparse and forces else None
        wire_rows.append([model] + [str(int(counters.get(c, 0))) for c in ("links", "dof", "wires", "wire_points")] +
                         [str(int(sparse[1].get("nonzeros", 0))) if sparse else "-"] +
                         [fmt(x[0] if x else None, 2) for x in (jac, sparse, forces)] + [fmt(ratio, 2)])
    if wire_rows:
        print("Wires on the sinew side (us): the dense Jacobian J (wires x dof), the sparse J^T the tension problems "
              "take, or the generalized forces -J^T f (target: sparse <= 2x forces)")
        print_table(["model", "links", "dof", "wires", "wire points", "J nonzeros", "WireJacobian us",
                     "WireJacobianSparse us", "WireForces us", "sparse/forces"], wire_rows, args.markdown)

    # The Balanced schedule on one thread against the same on every core (wall-clock).
    parallel_rows, speedups = [], []
    for model in models:
        serial, parallel = results.get(f"ForwardDynamics/sinew_balanced/{model}"), \
            results.get(f"ForwardDynamics/sinew_parallel/{model}/real_time")
        if serial and parallel:
            speedups.append((serial[0] / parallel[0], model))
            parallel_rows.append([model, str(int(parallel[1].get("links", 0))), str(int(parallel[1].get("threads", 0))),
                                  fmt(serial[0]), fmt(parallel[0]), fmt(serial[0] / parallel[0], 2)])
    if parallel_rows:
        print("The parallel schedule: Balanced on one thread (CPU time) and on every core (wall-clock), us")
        print_table(["model", "links", "threads", "balanced us", "parallel us", "speed-up"], parallel_rows, args.markdown)
        best = max(speedups)
        print(f"parallel schedule: best speed-up {best[0]:.2f} ({best[1]}); faster than one thread on "
              f"{sum(1 for x, _ in speedups if x > 1)} of {len(speedups)} models")

    # Series per (variant, family, engine): [(links, time)], and the slopes.
    series = defaultdict(list)
    wholebody = defaultdict(dict)  # wholebody[variant][engine] = (links, time)
    for model in models:
        parsed = parse_model(model)
        if not parsed:
            continue
        family, variant, _ = parsed
        for engine, (time, counters) in fd[model].items():
            links = int(counters["links"])
            if family == "wholebody":
                wholebody[variant][engine] = (links, time)
            else:
                series[(variant, family, engine)].append((links, time))
    slopes = {key: fit_slope(points) for key, points in series.items()}
    slope_rows = []
    for variant in VARIANTS:
        for family in ("chain", "tree"):
            row = [f"{family} {variant}"] + [fmt(slopes.get((variant, family, e)), 2) for e in ENGINES]
            if any(c != "-" for c in row[1:]):
                slope_rows.append(row)
    if slope_rows:
        print(f"Log-log slopes of time against links, fitted over {FIT_RANGE[0]}..{FIT_RANGE[1]} links "
              f"(target for sinew: <= {SLOPE_TARGET})")
        print_table(["family variant"] + [f"{e} slope" for e in ENGINES], slope_rows, args.markdown)

    # MuJoCo's model differs where loops (soft connects) or slack wires (bilateral tendon springs) are: its
    # udot is checked only on the others.
    def same_dynamics(engine, counters):
        return engine != "mujoco" or (counters.get("loops", 0) == 0 and counters.get("slack_wires", 1) == 0)

    for checked in (True, False):
        differences = [(engines[e][1].get("udot_rel_diff", 0), f"{e}/{model}") for model, engines in fd.items()
                       for e in engines if same_dynamics(e, engines[e][1]) == checked]
        if differences and checked:
            worst = max(differences)
            print(f"largest udot difference from Simbody (relative, checked <= 1e-6 before timing): {worst[0]:.1e} "
                  f"({worst[1]})")
        elif differences:
            worst = max(differences)
            print(f"MuJoCo where its model differs (soft connects, tendon springs that push when slack; not "
                  f"checked): udot differs by up to {worst[0]:.1e} ({worst[1]})")
    for engine in SINEW_ENGINES:
        engine_slopes = {k: s for k, s in slopes.items() if k[2] == engine and s is not None}
        if engine_slopes:
            worst = max(engine_slopes, key=engine_slopes.get)
            print(f"{engine}'s largest slope: {engine_slopes[worst]:.2f} ({worst[1]} {worst[0]}): "
                  f"{'meets' if engine_slopes[worst] <= SLOPE_TARGET else 'misses'} the <= {SLOPE_TARGET} target")
    t = {e: value[0] for e, value in fd.get("wholebody", {}).items()}
    for engine in SINEW_ENGINES:
        for peer, target in (("simbody", RATIO_TARGET), ("simbody_fused", RATIO_TARGET), ("mujoco", MUJOCO_RATIO_TARGET)):
            if engine in t and peer in t:
                ratio = t[peer] / t[engine]
                print(f"wholebody: {engine} {t[engine]:.1f} us, {peer} {t[peer]:.1f} us, ratio {ratio:.2f}: "
                      f"{'meets' if ratio >= target else 'misses'} the >= {target:g}x target")

    bare = {e: value[0] for e, value in fd.get("wholebody_bare", {}).items()}
    if "sinew" in bare and "aba" in bare:
        ratio = bare["sinew"] / bare["aba"]
        print(f"wholebody_bare: sinew {bare['sinew']:.1f} us, hand-written ABA {bare['aba']:.1f} us, ratio {ratio:.2f}: "
              f"{'meets' if ratio <= 1.0 else 'misses'} the <= 1.0x target")

    for name, cv in noisy:
        print(f"noisy: {name}: repetitions vary by {100 * cv:.0f}% (coefficient of variation); "
              f"the fastest is used")
    if args.png:
        plot(series, slopes, wholebody, args.png)
        print(f"wrote {args.png}")


def plot(series, slopes, wholebody, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    colors = {"sinew": "tab:blue", "sinew_balanced": "tab:green", "simbody": "tab:red", "simbody_fused": "tab:orange",
              "mujoco": "tab:purple", "aba": "black"}
    styles = {"chain": ("-", "o"), "tree": ("--", "s")}
    fig, axes = plt.subplots(2, 2, figsize=(13, 10), sharex=True, sharey=True)
    for ax, variant in zip(axes.flat, VARIANTS):
        for family in ("chain", "tree"):
            for engine in ENGINES:
                points = sorted(series.get((variant, family, engine), []))
                if not points:
                    continue
                slope = slopes.get((variant, family, engine))
                linestyle, marker = styles[family]
                ax.plot([p[0] for p in points], [p[1] for p in points], linestyle=linestyle, marker=marker,
                        color=colors[engine], markersize=4,
                        label=f"{engine} {family} (slope {fmt(slope, 2)})")
        for engine, (links, time) in wholebody.get(variant, {}).items():
            ax.plot([links], [time], marker="*", markersize=13, color=colors[engine], linestyle="none",
                    markeredgecolor="black", label=f"{engine} wholebody ({time:.0f} us)")
        # A slope-1 guide through sinew's chain at 100 links, where there is one.
        anchor = dict(series.get((variant, "chain", "sinew"), [])).get(100)
        if anchor:
            xs = [10, 1000]
            ax.plot(xs, [anchor * x / 100 for x in xs], color="gray", linestyle=":", linewidth=1, label="slope 1")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(VARIANT_TITLES[variant])
        ax.grid(True, which="both", alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7, loc="upper left")
    for ax in axes[1]:
        ax.set_xlabel("links (free root, ball joints: dof = 3 links + 3)")
    for ax in axes[:, 0]:
        ax.set_ylabel("one forward-dynamics evaluation (us of CPU time)")
    fig.suptitle(f"sinew vs Simbody forward dynamics; slopes fitted over {FIT_RANGE[0]}..{FIT_RANGE[1]} links")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
