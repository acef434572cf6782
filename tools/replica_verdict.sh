#!/usr/bin/env bash
# Does the replica's SLAM verdict transfer to the real run? Simulates N replica runs (default 20,
# seeds 42..42+N-1, config/stpere_replica.yaml, detections path) with robocentric and dead
# reckoning, then scores each run twice: against the simulation's exact truth (the Monte Carlo's
# own figures) and, like the real run, against the run's simulated GPS buoy (the dataset without
# truth/). Prints one line per run and a summary (no page in docs/ quotes it): the share of runs
# where robocentric beats dead reckoning, the 5-95 % band of the GPS-scored robocentric errors
# against the real run's mean error, how often the exit is the worst segment, and the spIC scale
# beside the real run's; writes the same figures to OUT/verdict.json (keys in the Python below).
# A run that lacks one of its four metrics.json (either method, truth or GPS) is left out of every
# figure: one line says how many of the runs were left out and which, and verdict.json counts them
# (runs_left_out).
# The real run's figures are read from DIR/metrics.json (--real DIR, default
# out/stpere/robocentric, made by tools/main.sh); without one the real St. Pere dataset
# (MSISLAB_STPERE_DIR, default ../shared/datasets/stpere) is run into OUT/real/robocentric, and
# without the dataset the real comparison is skipped (one line says so; its keys are null).
# Usage: tools/replica_verdict.sh [--runs N] [--out OUT] [--real DIR]   (after a release build)
set -euo pipefail
cd "$(dirname "$0")/.."

runs=20
out=out/verdict
real=out/stpere/robocentric
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --real) real="$2"; shift 2 ;;
    -h|--help) sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "tools/replica_verdict.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

msislab=build/release/tools/msislab
[ -x "$msislab" ] || { echo "tools/replica_verdict.sh: build first (cmake --preset release && cmake --build --preset release)" >&2; exit 2; }
source tools/run_fresh.sh
source tools/without_truth.sh

# The real run's metrics.json: --real's, else the real dataset's run here, else none (skipped).
stpere="${MSISLAB_STPERE_DIR:-../shared/datasets/stpere}"
real_metrics="$real/metrics.json"
real_skipped=""
if [ ! -f "$real_metrics" ]; then
  if [ -f "$stpere/_040825_1735_DVL.log" ]; then
    echo "== $real has no metrics.json: running the real dataset $stpere into $out/real/robocentric"
    mkdir -p "$out/real"
    "$msislab" run "$stpere" --method robocentric --config config/stpere.yaml \
      --out "$out/real/robocentric" >/dev/null
    real_metrics="$out/real/robocentric/metrics.json"
  else
    real_metrics=""
    real_skipped="no metrics.json in $real and no real dataset at $stpere"
  fi
fi

mc="$out/montecarlo"
run_fresh "$mc" "$msislab" montecarlo scenarios/stpere_replica.yaml --runs "$runs" \
  --out "$mc" --methods robocentric,deadreckoning --config config/stpere_replica.yaml \
  --keep-datasets --no-plot >/dev/null
gps="$out/gps"
# The GPS-scored runs are this script's own (the marker says so); anything else there is refused.
if [ -e "$gps" ] && [ ! -f "$gps/.replica-verdict" ]; then
  echo "tools/replica_verdict.sh: $gps exists and was not written by this script; choose another --out" >&2
  exit 2
fi
rm -rf "$gps"
mkdir -p "$gps"
touch "$gps/.replica-verdict"
for dataset in "$mc"/datasets/run_*; do
  r=$(basename "$dataset")
  copy="$gps/$r/dataset"
  copy_without_truth "$dataset" "$copy"
  for m in robocentric deadreckoning; do
    "$msislab" run "$copy" --method "$m" --out "$gps/$r/$m" --config config/stpere_replica.yaml \
      >/dev/null
  done
  rm -rf "$copy"
done

python3 - "$mc" "$gps" "$real_metrics" "$real_skipped" "$out/verdict.json" <<'EOF'
import glob, json, math, os, sys
mc, gps, real_path, real_skipped, verdict_path = sys.argv[1:6]
def metrics(path):
    with open(path) as f:
        return json.load(f)
def diag(m, key):
    return m.get("diagnostics", {}).get(key, float("nan"))
# Every run that left a folder anywhere (a dataset, either method's result or failed.json, a
# GPS-scored run) is counted; one without all four metrics.json is left out, and said so below.
run_names = sorted({os.path.basename(d) for d in
                    glob.glob(os.path.join(mc, "runs", "*", "run_*")) +
                    glob.glob(os.path.join(mc, "datasets", "run_*")) +
                    glob.glob(os.path.join(gps, "run_*"))})
rows, left_out = [], []
for r in run_names:
    try:
        rc, dr = (metrics(os.path.join(mc, "runs", m, r, "metrics.json")) for m in ("robocentric", "deadreckoning"))
        rg, dg = (metrics(os.path.join(gps, r, m, "metrics.json")) for m in ("robocentric", "deadreckoning"))
    except FileNotFoundError:
        left_out.append(r)
        continue
    seg = rc["segments"]
    rows.append(dict(run=r, rc=rc["mean_error_m"], dr=dr["mean_error_m"], rc_gps=rg["mean_error_m"],
                     dr_gps=dg["mean_error_m"], worst=max(seg, key=seg.get),
                     worst_gps=max(rg["segments"], key=rg["segments"].get),
                     scale=diag(rc, "consecutive_match_scale"),
                     scale_gps=diag(rg, "consecutive_match_scale")))
print("run       robocentric  dead reckoning  robocentric(GPS)  dead reckoning(GPS)  worst segment (truth/GPS)  spIC scale (truth/GPS)")
for x in rows:
    print(f"{x['run']}  {x['rc']:11.2f}  {x['dr']:14.2f}  {x['rc_gps']:16.2f}  {x['dr_gps']:19.2f}  "
          f"{x['worst']:>12s}/{x['worst_gps']:<12s}  {x['scale']:.3f}/{x['scale_gps']:.3f}")
n = len(rows)
print(f"replica_verdict: {len(left_out)} of {len(run_names)} runs left out (no metrics.json)"
      + (": " + ", ".join(left_out) if left_out else ""))
if n == 0:
    sys.exit("tools/replica_verdict.sh: no finished run")
def quantile(values, q):  # linear interpolation between order statistics (numpy's default)
    v = sorted(values); h = (len(v) - 1) * q; i = int(h)
    return v[i] + (v[min(i + 1, len(v) - 1)] - v[i]) * (h - i)
better = sum(x["rc"] < x["dr"] for x in rows)
better_gps = sum(x["rc_gps"] < x["dr_gps"] for x in rows)
lo, hi = quantile([x["rc_gps"] for x in rows], 0.05), quantile([x["rc_gps"] for x in rows], 0.95)
exit_worst = sum(x["worst"] == "exit" for x in rows)
mean = lambda k: sum(x[k] for x in rows) / n
# The real run is scored against its GPS: the real dataset has no other truth.
real_error = real_scale = inside = None
if real_path:
    real = metrics(real_path)
    real_error = real.get("mean_error_m")
    if real_error is None:
        sys.exit(f"tools/replica_verdict.sh: {real_path}: no mean_error_m (a run without GPS?)")
    real_scale = diag(real, "consecutive_match_scale")
    inside = lo <= real_error <= hi
print(f"\nruns: {n}")
print(f"robocentric below dead reckoning: {better}/{n} ({100 * better / n:.0f} %) against the truth, "
      f"{better_gps}/{n} ({100 * better_gps / n:.0f} %) against the simulated GPS")
band = (f"robocentric against the simulated GPS: mean {mean('rc_gps'):.2f} m, 5-95 % band "
        f"{lo:.2f}-{hi:.2f} m")
if real_path:
    band += f"; the real run's {real_error:.2f} m is {'inside' if inside else 'outside'}"
print(band)
print(f"exit the worst segment: {exit_worst}/{n} runs (truth)")
scale = f"spIC scale: {mean('scale'):.3f} against the truth, {mean('scale_gps'):.3f} against the GPS"
if real_path:
    scale += f" (real run {real_scale:.3f} against its GPS)"
print(scale)
print(f"real run: {real_path}" if real_path else f"real run: comparison skipped ({real_skipped})")

def number(x):  # JSON has no NaN: a diagnostic a run lacks is null
    return x if x is not None and math.isfinite(x) else None
verdict = {
    "runs": n,
    "runs_left_out": len(left_out),
    "robocentric_below_dr_truth": better,
    "robocentric_below_dr_gps": better_gps,
    "rc_gps_mean_m": number(mean("rc_gps")),
    "rc_gps_p05_m": number(lo),
    "rc_gps_p95_m": number(hi),
    "real_metrics": real_path or None,
    "real_error_m": number(real_error),
    "real_inside_band": inside,
    "exit_worst_runs": exit_worst,
    "scale_truth": number(mean("scale")),
    "scale_gps": number(mean("scale_gps")),
    "real_scale": number(real_scale),
}
with open(verdict_path + ".tmp", "w") as f:
    json.dump(verdict, f, indent=2)
    f.write("\n")
os.replace(verdict_path + ".tmp", verdict_path)
print(f"wrote {verdict_path}")
EOF
