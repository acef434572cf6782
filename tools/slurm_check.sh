#!/usr/bin/env bash
# Checks docs/cluster.md on a real SLURM. Brings up a one-node cluster on localhost (munged,
# slurmctld, slurmd; installs Debian's slurm-wlm and munge with apt-get when missing), then runs
# the page's two sbatch scripts and its submit lines exactly as it writes them (read from its code
# blocks) in a job directory holding scenarios/small_basin.yaml as scenario.yaml and
# config/default.yaml as slam.yaml: the 4-task array and the dependent merge; task 3 is cancelled
# part-way, so the merge must count its runs as missing, and resubmitted with the page's lines.
# The final merged directory must equal one `msislab montecarlo` of the same runs on one machine
# (summary.json apart from its runtime_s lines, the CSV files, every run directory). Last, one run
# of task 3 is made to fail (MSISLAB_MONTECARLO_FAULTS) and the task and merge resubmitted: both
# must end FAILED with exit code 3 (the merge still runs), the merge counting the failed run.
# Prints a PASS or FAIL line per check and the logs of failed jobs; exits 1 on a failure, 2 when
# it cannot run. About 75 s on 2 cores (2 minutes when they are busy with other work), the failed
# run's stage adding about a tenth, plus 5-30 s the first time for the packages (apt-get update and
# install).
# Root only (apt-get, SLURM's daemons run as root). Everything it writes lives in a mktemp -d
# directory (about 360 MB at its largest), removed at the end once the jobs and daemons it started
# are stopped (SLURM_CHECK_KEEP=1 keeps the directory); installed packages stay. The daemons
# listen on the first two free ports from 16817 and authenticate with their own munge key and
# socket, so a SLURM or munge already on the machine is left alone.
# Usage: tools/slurm_check.sh [BUILD_DIR]   (default build/release, else build/ci)
set -euo pipefail
cd "$(dirname "$0")/.."
doc=docs/cluster.md
scenario=scenarios/small_basin.yaml
slam_config=config/default.yaml
start=$SECONDS

refuse() {
  echo "slurm_check: $*" >&2
  exit 2
}

if [ $# -gt 0 ]; then
  build=$1
elif [ -x build/release/tools/msislab ]; then
  build=build/release
else
  build=build/ci
fi
[ -x "$build/tools/msislab" ] ||
  refuse "no msislab binary at $build/tools/msislab; build it first" \
    "(cmake --preset release && cmake --build --preset release) or name its build directory"
[ "$(id -u)" -eq 0 ] || refuse "run it as root: it installs packages and starts SLURM's daemons"
[ -f "$doc" ] || refuse "no $doc"
keep=${SLURM_CHECK_KEEP:-0}
# Only this check's settings reach sbatch and the jobs (SLURM_CONF is set below).
# shellcheck disable=SC2046 # variable names
unset MSISLAB_MONTECARLO_FAULTS $(compgen -e | grep -E '^(SLURM|SBATCH|SQUEUE|SINFO)_' || true)

# --- the page's scripts and submit lines, from its code blocks ------------------------------------
# The fenced code block of the page with a line containing $1, without the fence's indent.
doc_block() {
  awk -v want="$1" '
    /^ *```/ {
      if (!inside) { inside = 1; indent = index($0, "`") - 1; text = ""; found = 0; next }
      inside = 0
      if (found) { printf "%s", text; exit }
      next
    }
    inside {
      line = substr($0, indent + 1)
      text = text line "\n"
      if (index(line, want)) found = 1
    }
  ' "$doc"
}
# Every block or refuse: the page no longer has what this check runs.
doc_block_or_refuse() {
  local text
  text=$(doc_block "$1")
  [ -n "$text" ] || refuse "$doc has no code block with a line containing '$1'"
  printf '%s\n' "$text"
}
array_script=$(doc_block_or_refuse "# montecarlo.sbatch")
merge_script=$(doc_block_or_refuse "# merge.sbatch")
# shellcheck disable=SC2016 # the page's text, not to expand
submit_lines=$(doc_block_or_refuse 'array=$(sbatch --parsable montecarlo.sbatch)')
resubmit_lines=$(doc_block_or_refuse 'sbatch --parsable --array=')
again=$(printf '%s\n' "$resubmit_lines" | sed -n 's/.*--array=\([0-9]*\) .*/\1/p' | head -1)
[ -n "$again" ] || refuse "no --array=TASK in the resubmit block of $doc"

failures=0
checks=0
pass() {
  checks=$((checks + 1))
  echo "PASS $*"
}
fail() {
  checks=$((checks + 1))
  failures=$((failures + 1))
  echo "FAIL $*"
}
stage_start=$SECONDS
stamp() {
  echo "slurm_check: $1 took $((SECONDS - stage_start)) s ($((SECONDS - start)) s in all)"
  stage_start=$SECONDS
}

# --- scratch directory, and what stops everything at the end --------------------------------------
work=$(mktemp -d "${TMPDIR:-/tmp}/slurm_check.XXXXXX")
chmod 711 "$work" # munged wants every folder above its socket searchable by all
daemon_pids=()    # munged, slurmctld, slurmd, in start order

stop_pid() {
  local pid=$1 i
  kill -TERM "$pid" 2>/dev/null || return 0
  for i in $(seq 50); do
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.2
  done
  kill -KILL "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
}

cleanup() {
  local status=$? i left stop_start=$SECONDS
  trap - EXIT INT TERM
  if [ ${#daemon_pids[@]} -ge 2 ]; then
    # The jobs first: their slurmstepd processes would outlive slurmd.
    left=$(timeout 20 squeue -h -o %A 2>/dev/null | sort -u | tr '\n' ' ' || true)
    if [ -n "${left// /}" ]; then
      echo "slurm_check: cancelling jobs still queued: $left"
      # shellcheck disable=SC2086 # job ids
      scancel $left 2>/dev/null || true
      for i in $(seq 60); do
        [ -z "$(timeout 20 squeue -h 2>/dev/null)" ] && break
        sleep 0.5
      done
    fi
  fi
  for ((i = ${#daemon_pids[@]} - 1; i >= 0; i--)); do stop_pid "${daemon_pids[i]}"; done
  echo "slurm_check: daemons stopped in $((SECONDS - stop_start)) s"
  if [ "$keep" = 1 ]; then
    echo "slurm_check: kept $work"
  else
    rm -rf "$work"
  fi
  echo "slurm_check: $((SECONDS - start)) s in all"
  exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

print_file() { # FILE [TITLE]: a log, indented
  echo "---- ${2:-$1}"
  if [ -f "$1" ]; then sed 's/^/    /' "$1"; else echo "    (no such file)"; fi
}

daemon_logs() {
  print_file "$work/log/munged.log" "munged log"
  print_file "$work/log/slurmctld.stderr" "slurmctld stderr (what it says before its log opens)"
  print_file "$work/log/slurmctld.log" "slurmctld log"
  print_file "$work/log/slurmd.stderr" "slurmd stderr"
  print_file "$work/log/slurmd.log" "slurmd log"
}

# --- packages -------------------------------------------------------------------------------------
missing=()
for p in slurm-wlm munge; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "slurm_check: installing ${missing[*]} (apt-get)"
  if ! { DEBIAN_FRONTEND=noninteractive apt-get update -qq &&
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
      "${missing[@]}"; } >"$work/apt.log" 2>&1; then
    print_file "$work/apt.log" "apt-get"
    refuse "could not install ${missing[*]}"
  fi
fi
stamp "packages"

# --- a one-node SLURM on localhost ----------------------------------------------------------------
mkdir -p "$work/log" "$work/state" "$work/spool" "$work/etc"
mkdir -m 700 "$work/munge"
mkdir -m 755 "$work/munge_run"
socket=$work/munge_run/munge.socket
mungekey --create --keyfile="$work/munge/munge.key"
munged -F --key-file="$work/munge/munge.key" --socket="$socket" \
  --pid-file="$work/munge_run/munged.pid" --seed-file="$work/munge/munged.seed" \
  --log-file="$work/log/munged.log" 2>>"$work/log/munged.log" &
daemon_pids+=($!)
for i in $(seq 50); do
  munge -S "$socket" -n 2>/dev/null | unmunge -S "$socket" >/dev/null 2>&1 && break
  [ "$i" -lt 50 ] || {
    fail "munged did not start"
    daemon_logs
    exit 1
  }
  sleep 0.2
done

port_in_use() { (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
ctld_port=
for p in $(seq 16817 2 16917); do
  if ! port_in_use "$p" && ! port_in_use $((p + 1)); then
    ctld_port=$p
    break
  fi
done
[ -n "$ctld_port" ] || refuse "no two free ports between 16817 and 16918"

node=$(hostname -s)
cpus=$(nproc)
memory_mb=$(awk '/^MemTotal:/ { print int($2 / 1024) }' /proc/meminfo)
export SLURM_CONF=$work/etc/slurm.conf
cat >"$SLURM_CONF" <<EOF
# One node on localhost for tools/slurm_check.sh; all state under $work.
ClusterName=msislabcheck
SlurmctldHost=localhost
SlurmctldPort=$ctld_port
SlurmdPort=$((ctld_port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
MinJobAge=3600
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=check Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -D -f "$SLURM_CONF" >"$work/log/slurmctld.stderr" 2>&1 &
daemon_pids+=($!)
slurmd -D -N "$node" -f "$SLURM_CONF" >"$work/log/slurmd.stderr" 2>&1 &
daemon_pids+=($!)
state=
for i in $(seq 120); do
  state=$(sinfo -h -n "$node" -o %t 2>/dev/null || true)
  [ "$state" = idle ] && break
  sleep 0.5
done
if [ "$state" != idle ]; then
  fail "node $node not idle after 60 s (sinfo: '$state')"
  daemon_logs
  exit 1
fi
pass "one-node SLURM up: node $node, $cpus CPUs, $memory_mb MB, ports $ctld_port-$((ctld_port + 1))"
stamp "SLURM start"

# --- the job directory ----------------------------------------------------------------------------
mkdir "$work/bin"
cp "$build/tools/msislab" "$work/bin/" # a fixed copy: a rebuild meanwhile changes nothing here
export PATH="$work/bin:$PATH"
job=$work/job
mkdir "$job"
printf '%s\n' "$array_script" >"$job/montecarlo.sbatch"
printf '%s\n' "$merge_script" >"$job/merge.sbatch"
cp "$scenario" "$job/scenario.yaml"
cp "$slam_config" "$job/slam.yaml"
mesh=$(sed -n 's/^ *mesh: *\([^ #]*\).*/\1/p' "$scenario" | head -1)
case $mesh in
  /*) ;; # absolute: every task sees it where it is
  *)
    mkdir -p "$(dirname "$job/$mesh")"
    cp "$(dirname "$scenario")/$mesh" "$job/$mesh"
    ;;
esac
echo "slurm_check: job directory $job: montecarlo.sbatch, merge.sbatch from $doc;" \
  "scenario.yaml = $scenario (mesh $mesh), slam.yaml = $slam_config; msislab from $build"

# Runs a block of the page's submit lines in the job directory; sets first_job to the job its
# `$(sbatch --parsable ...)` line submitted and merge_job to the merge job.
submit() {
  local out
  out=$(cd "$job" && bash -euo pipefail -c "$1"$'\n''echo "first job ${array:-${task:-}}"') || {
    fail "the submit lines failed:"
    printf '%s\n' "$1" "$out" | sed 's/^/    /'
    exit 1
  }
  printf '%s\n' "$1" | sed 's/^/    $ /'
  first_job=$(printf '%s\n' "$out" | sed -n 's/^first job //p')
  merge_job=$(printf '%s\n' "$out" | sed -n 's/^Submitted batch job \([0-9]*\)$/\1/p')
  if [ -z "$first_job" ] || [ -z "$merge_job" ]; then
    fail "no job ids from the submit lines: $out"
    exit 1
  fi
}

# Waits until no job is left in the queue (this cluster runs no other).
wait_for_queue() {
  local deadline=$((SECONDS + 1200))
  while [ -n "$(squeue -h 2>/dev/null)" ]; do
    if [ $SECONDS -ge $deadline ]; then
      fail "jobs still queued after 20 minutes"
      squeue
      exit 1
    fi
    sleep 1
  done
}

# "task state exit-code log" for each task of job $1 (task - for a job that is not an array).
job_states() {
  scontrol -o show job "$1" | awk '{
    delete v
    for (i = 1; i <= NF; ++i) { k = $i; sub(/=.*/, "", k); v[k] = substr($i, length(k) + 2) }
    task = v["ArrayTaskId"] == "" ? "-" : v["ArrayTaskId"]
    print task, v["JobState"], v["ExitCode"], v["StdOut"]
  }' | sort -n
}

# PASS when every task of job $1 ($2 says what it is) completed with exit 0; else FAIL and its
# log. Task $3, if given, may instead be CANCELLED.
check_job() {
  local task state code log bad=0
  [ -n "$(job_states "$1")" ] || {
    fail "$2: SLURM knows no job $1"
    return
  }
  while read -r task state code log; do
    [ "$state" = COMPLETED ] && [ "$code" = 0:0 ] && continue
    [ "$task" = "${3:-none}" ] && [ "$state" = CANCELLED ] && continue
    bad=1
    fail "$2: job $1 task $task ended $state, exit code $code"
    print_file "$log" "its log $log"
  done < <(job_states "$1")
  [ $bad = 1 ] || pass "$2: job $1 ended as expected ($(job_states "$1" | awk '{ print $2 }' |
    sort | uniq -c | awk '{ printf "%s%d %s", (NR > 1 ? ", " : ""), $1, $2 }'))"
}

# Progress lines "montecarlo: k/n runs done, ..." in a task's log.
progress_lines() { grep -cE '^montecarlo: [0-9]+/[0-9]+ runs done, ' "$1" || true; }

# "runs failed missing" summed over the methods of a Monte Carlo directory's summary.json.
summary_counts() {
  awk -F'[:,]' '/^    "(runs|failed|missing)":/ { gsub(/[" ]/, "", $1); n[$1] += $2 }
    END { print n["runs"] + 0, n["failed"] + 0, n["missing"] + 0 }' "$1/summary.json"
}

# --- the array and its merge, task $again cancelled part-way --------------------------------------
submit "$submit_lines"
array=$first_job
merge=$merge_job
echo "slurm_check: array job $array, merge job $merge; waiting for task $again to run"
log_again=$job/mc_${array}_${again}.log
cancelled_at=
deadline=$((SECONDS + 1200))
while [ $SECONDS -lt $deadline ]; do
  if [ -f "$log_again" ] && [ "$(progress_lines "$log_again")" -ge 1 ]; then
    scancel "${array}_${again}"
    cancelled_at=$(progress_lines "$log_again")
    break
  fi
  [ -n "$(squeue -h -j "$array" -t pending,running 2>/dev/null)" ] || break
  sleep 0.1
done
wait_for_queue
stamp "array and merge"
check_job "$array" "array (montecarlo.sbatch)" "$again"
check_job "$merge" "merge (merge.sbatch)"
state_again=$(job_states "$array" | awk -v t="$again" '$1 == t { print $2 }')
if [ -n "$cancelled_at" ] && [ "$state_again" = CANCELLED ]; then
  pass "task $again cancelled with $cancelled_at of its runs done; its log ends:"
  tail -n 3 "$log_again" | sed 's/^/    /'
else
  fail "task $again could not be cancelled part-way (it ended before, or never ran)"
fi

merged=$job/$(awk '/^msislab montecarlo merge/ { print $4 }' "$job/merge.sbatch")
[ -f "$merged/summary.json" ] || {
  fail "no $merged/summary.json after the merge"
  exit 1
}
shards=$(sed -n 's/.*--shard [^ ]*\/\([0-9]*\).*/\1/p' "$job/montecarlo.sbatch" | head -1)
for ((i = 0; i < shards; i++)); do
  [ "$i" = "$again" ] && continue
  log=$job/mc_${array}_$i.log
  [ -f "$job/shard_$i/seeds.csv" ] || {
    fail "task $i wrote no shard_$i/seeds.csv"
    continue
  }
  n=$(($(wc -l <"$job/shard_$i/seeds.csv") - 1))
  lines=$(progress_lines "$log")
  if [ "$lines" = "$n" ] && grep -q "^montecarlo: $n/$n runs done" "$log"; then
    pass "task $i's log: one progress line per run of its shard ($n)"
  else
    fail "task $i's log: $lines progress lines for $n runs"
    print_file "$log"
  fi
done

read -r runs failed missing < <(summary_counts "$merged")
total=$(sed -n 's/^ *"runs": \([0-9]*\),$/\1/p' "$merged/montecarlo.json")
methods=$(sed -n 's/^ *"methods": \[\(.*\)\],$/\1/p' "$merged/montecarlo.json" | tr -d '" ')
n_methods=$(printf '%s\n' "$methods" | tr ',' '\n' | wc -l)
if [ "$missing" -gt 0 ] && [ $((runs + failed + missing)) = $((total * n_methods)) ]; then
  pass "first merge: $missing of $((total * n_methods)) method runs missing (task $again cancelled)"
else
  fail "first merge: runs $runs, failed $failed, missing $missing of $((total * n_methods))"
fi

# --- the page's resubmission of the task, and the merge again -------------------------------------
submit "$resubmit_lines"
task=$first_job
merge2=$merge_job
wait_for_queue
stamp "resubmitted task and merge"
check_job "$task" "resubmitted task $again"
check_job "$merge2" "merge again"
log=$job/mc_${task}_$again.log
n=$(($(wc -l <"$job/shard_$again/seeds.csv") - 1))
done_before=$(sed -n 's/.*(\([0-9]*\) run now, \([0-9]*\) already done).*/\2/p' "$log")
if [ "${done_before:-0}" -gt 0 ] && [ "$(progress_lines "$log")" = $((n - done_before)) ] &&
  grep -q "^montecarlo: $n/$n runs done" "$log"; then
  pass "resubmitted task $again skipped its $done_before finished runs," \
    "ran the other $((n - done_before))"
else
  fail "resubmitted task $again: ${done_before:-?} runs found done; its log:"
  print_file "$log"
fi
leftovers=$(find "$job" -maxdepth 4 \( -name scratch -o -name datasets -o -name '*.partial' \
  -o -name '*.tmp-merge' \) |
  sed "s|^$job/||" | tr '\n' ' ')
if [ -z "$leftovers" ]; then
  pass "no scratch/, datasets/ or .partial left in the shard or merged directories"
else
  fail "left behind: $leftovers"
fi
read -r runs failed missing < <(summary_counts "$merged")
if [ "$missing" = 0 ] && [ "$failed" = 0 ] && [ "$runs" = $((total * n_methods)) ]; then
  pass "merge again: all $total runs of $methods finished"
else
  fail "merge again: runs $runs, failed $failed, missing $missing"
fi

# --- the same runs on one machine -----------------------------------------------------------------
one=$work/one_machine
if ! (cd "$job" && msislab montecarlo scenario.yaml --runs "$total" --methods "$methods" \
  --config slam.yaml --out "$one" --no-plot) >"$work/one_machine.log" 2>&1; then
  fail "msislab montecarlo on one machine"
  print_file "$work/one_machine.log"
  exit 1
fi
stamp "one machine ($total runs)"
for f in montecarlo.json scenario.yaml config.yaml seeds.csv nees.csv errors.csv \
  error_histogram.csv; do
  if cmp -s "$merged/$f" "$one/$f"; then
    pass "$f: the same bytes merged and on one machine"
  else
    fail "$f differs between $merged and one machine"
  fi
done
if diff <(grep -v '"runtime_s"' "$merged/summary.json") \
  <(grep -v '"runtime_s"' "$one/summary.json") >"$work/summary.diff" &&
  [ "$(grep -c '"runtime_s"' "$merged/summary.json")" = "$n_methods" ]; then
  pass "summary.json: the same bytes merged and on one machine apart from the runtime_s lines"
else
  fail "summary.json differs between $merged and one machine"
  print_file "$work/summary.diff" "diff"
fi
run_files() { # every run file of Monte Carlo directory $1, prefixed by its path; no runtime_s
  (cd "$1" && find runs -type f | sort | xargs grep -H -v '"runtime_s"')
}
if cmp -s <(run_files "$merged") <(run_files "$one"); then
  pass "runs/: every run directory the same merged and on one machine" \
    "($(find "$one/runs" -mindepth 2 -maxdepth 2 -type d | wc -l), runtime_s apart)"
else
  fail "runs/ differs between $merged and one machine"
  diff <(run_files "$merged") <(run_files "$one") | head -20
fi

# --- a failed run: its task exits 3, the merge still runs and exits 3 -----------------------------
# Run $again is in shard $again (r % shards); its first method's result removed, then made to fail.
first_method=${methods%%,*}
rm -rf "$job/shard_$again/runs/$first_method/$(printf 'run_%04d' "$again")"
export MSISLAB_MONTECARLO_FAULTS="$again:$first_method:throw"
submit "$resubmit_lines"
unset MSISLAB_MONTECARLO_FAULTS
task=$first_job
merge3=$merge_job
wait_for_queue
stamp "a failed run: task and merge"
# PASS when job $1 ($2 says what it is) ended FAILED with exit code 3:0 and $3 in its log.
check_exit_3() {
  local task state code log
  read -r task state code log < <(job_states "$1")
  if [ "${state:-}" = FAILED ] && [ "${code:-}" = 3:0 ] && grep -qF "$3" "$log"; then
    pass "$2: job $1 ended FAILED, exit code 3:0, its log saying '$3'"
  else
    fail "$2: job $1 ended ${state:-?}, exit code ${code:-?}, or its log lacks '$3'"
    print_file "${log:-none}" "its log ${log:-}"
  fi
}
n=$(($(wc -l <"$job/shard_$again/seeds.csv") - 1))
check_exit_3 "$task" "task $again with a failed run" \
  "montecarlo: finished, but 1 of $n runs have a failed method (exit status 3)"
check_exit_3 "$merge3" "the merge after it" \
  "montecarlo merge: finished, but 1 of $total runs have a failed method (exit status 3)"
read -r runs failed missing < <(summary_counts "$merged")
failed_json=$merged/runs/$first_method/$(printf 'run_%04d' "$again")/failed.json
if [ "$failed" = 1 ] && [ "$missing" = 0 ] && [ "$runs" = $((total * n_methods - 1)) ] &&
  grep -q "injected failure" "$failed_json"; then
  pass "the merge counts the failed run of $first_method (runs $runs, failed 1, missing 0)"
else
  fail "the merge after a failed run: runs $runs, failed $failed, missing $missing"
fi

echo "slurm_check: $((checks - failures)) of $checks checks passed in $((SECONDS - start)) s"
[ "$failures" = 0 ] || exit 1
