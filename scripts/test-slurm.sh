#!/usr/bin/env bash
# The λ-sweep workflow on a real Slurm: starts a one-node Slurm cluster on this machine (munged,
# slurmctld and slurmd of Debian's packages munge and slurm-wlm, installed with apt-get if missing;
# no systemd, no cgroups, no accounting database), runs a tiny sweep (sphere, λ 0.06 and 0.05,
# seed 1) through the Slurm profile experiments/profiles/slurm, and checks that
#   - the per-surface job and the runs ran as Slurm jobs, the two runs in one job (group `runs`),
#     while merge and figures ran in the Snakemake process (local rules);
#   - Slurm recorded those jobs as completed;
#   - the merged lambda_sweep.csv has a plain header, one row per run with a vertex count, λ
#     written in shortest form, and its metadata lambda_sweep.csv.json counts the jobs;
#   - the figures exist as PDF and PNG.
# Everything it starts (the daemons, with their own configuration, key, socket, ports and state
# under $DELMESH_BUILD_DIR/slurm-test) it stops again; a second run starts from scratch.  Needs
# root (the daemons), snakemake and the built lambda_sweep (cmake --build build --target
# lambda_sweep).  Exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=$(realpath "${DELMESH_BUILD_DIR:-build}")
bin=$build/experiments/lambda_sweep
dir=$build/slurm-test
started=$SECONDS
say() { echo "test-slurm.sh: $*"; }
fail() { echo "test-slurm.sh: FAILED: $*" >&2; exit 1; }

[ "$(id -u)" = 0 ] || fail "needs root (it starts munged, slurmctld and slurmd)"
[ -x "$bin" ] || fail "$bin is missing (cmake --build ${DELMESH_BUILD_DIR:-build} --target lambda_sweep)"
command -v snakemake >/dev/null || fail "snakemake is missing (scripts/install-deps.sh --dev)"

# --- packages ---------------------------------------------------------------------------------
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null || ! command -v sbatch >/dev/null ||
   ! command -v munged >/dev/null; then
  say "installing slurm-wlm and munge"
  # Without systemd a package's start of its service fails; keep apt-get from trying (as Debian's
  # container images do), with a policy file of our own only where none exists.
  policy_added=
  if [ ! -e /usr/sbin/policy-rc.d ]; then
    printf '#!/bin/sh\nexit 101\n' > /usr/sbin/policy-rc.d && chmod 755 /usr/sbin/policy-rc.d && policy_added=1
  fi
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null
  [ -z "$policy_added" ] || rm -f /usr/sbin/policy-rc.d
fi

# --- stop what an earlier, interrupted run of this script left running --------------------------
stop_daemons() {
  local pidfile pid
  for pidfile in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munged.pid"; do
    [ -s "$pidfile" ] || continue
    pid=$(cat "$pidfile")
    if kill -0 "$pid" 2>/dev/null; then
      kill "$pid" 2>/dev/null || true
      for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
      kill -9 "$pid" 2>/dev/null || true
    fi
    rm -f "$pidfile"
  done
}
stop_daemons
rm -rf "$dir"
mkdir -p "$dir"/{state,spool,work}
chmod 700 "$dir"
trap 'status=$?; stop_daemons; exit $status' EXIT

# --- munge: a key and a socket of our own ------------------------------------------------------
if command -v mungekey >/dev/null; then
  mungekey --create --keyfile="$dir/munge.key" --force
else
  create-munge-key -f -k "$dir/munge.key" >/dev/null 2>&1 ||
    { dd if=/dev/urandom of="$dir/munge.key" bs=1024 count=1 status=none; }
fi
chmod 400 "$dir/munge.key"
munged --force --key-file="$dir/munge.key" --socket="$dir/munge.socket" --pid-file="$dir/munged.pid" \
  --log-file="$dir/munged.log" --seed-file="$dir/munged.seed"
for _ in $(seq 50); do [ -S "$dir/munge.socket" ] && break; sleep 0.1; done
[ -S "$dir/munge.socket" ] || fail "munged did not start (see $dir/munged.log)"

# --- slurm.conf: this host as the only node, one partition ---------------------------------------
host=$(hostname -s)
# slurmd -C prints this node as slurmd sees it (CPUs, sockets, cores, threads, RealMemory).
node=$(slurmd -C | head -n 1)
case $node in NodeName=*) ;; *) fail "slurmd -C printed '$node'" ;; esac
cat > "$dir/slurm.conf" <<EOF
ClusterName=delmeshtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/jobcomp.log
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
ReturnToService=2
MinJobAge=600
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$dir/slurm.conf
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"

# --- wait for the node -------------------------------------------------------------------------
state=
for _ in $(seq 60); do
  state=$(sinfo -h -n "$host" -o %T 2>/dev/null || true)
  [ "$state" = idle ] && break
  sleep 0.5
done
[ "$state" = idle ] || fail "node $host is '${state:-unknown}', not idle (see $dir/slurmctld.log, $dir/slurmd.log)"
say "Slurm up: node $host idle ($((SECONDS - started)) s)"

# --- the sweep through the profile --------------------------------------------------------------
# Snakemake's Slurm executor reads USER (to guess an account); a CI shell may not set it.
export USER=${USER:-$(id -un)}
out=$dir/work/out
(cd "$dir/work" &&
  snakemake -s "$root/experiments/Snakefile" --profile "$root/experiments/profiles/slurm" --latency-wait 10 \
    --config surfaces=sphere lambdas=0.06,0.05 seeds=1 time_limit=60 out="$out" bin="$bin" \
    > "$dir/snakemake.log" 2>&1) || { tail -n 40 "$dir/snakemake.log" >&2; fail "snakemake failed (log: $dir/snakemake.log)"; }
say "snakemake finished ($((SECONDS - started)) s)"

# --- the jobs went through Slurm, the runs in one job, the merge here --------------------------
slurm_job() { sed -n '1s/^host=.* slurm_job_id=\([0-9]*\)$/\1/p' "$1"; }
eps_job=$(slurm_job "$out/logs/eps_sphere.log")
run1=$(slurm_job "$out/logs/run_sphere_l0.06_s1.log")
run2=$(slurm_job "$out/logs/run_sphere_l0.05_s1.log")
[ -n "$eps_job" ] || fail "eps_reference did not run in a Slurm job ($out/logs/eps_sphere.log)"
[ -n "$run1" ] && [ -n "$run2" ] || fail "a run did not run in a Slurm job ($out/logs/run_*.log)"
[ "$run1" = "$run2" ] || fail "the two runs ran in Slurm jobs $run1 and $run2, not in one group job"
[ "$eps_job" != "$run1" ] || fail "eps_reference and the runs share Slurm job $eps_job"
for job in "$eps_job" "$run1"; do
  grep -q "JobId=$job .*JobState=COMPLETED" "$dir/jobcomp.log" ||
    fail "Slurm has no record of job $job as completed ($dir/jobcomp.log)"
done
[ "$(ls "$dir/work/.snakemake/slurm_logs/group_runs" | wc -l)" = 1 ] ||
  fail "expected one Slurm log of group runs in $dir/work/.snakemake/slurm_logs/group_runs"
say "Slurm jobs: eps_reference $eps_job, both runs in $run1; Slurm recorded them completed"

# --- the merged CSV and its metadata ------------------------------------------------------------
/usr/bin/python3 - "$out" <<'EOF' || fail "merged output check"
import csv, json, os, sys
out = sys.argv[1]
path = os.path.join(out, "lambda_sweep.csv")
with open(path) as f:
    first = f.readline()
    assert first.startswith("surface,lambda,status,"), f"header line is {first!r}"
    f.seek(0)
    rows = list(csv.DictReader(f))
assert len(rows) == 2, f"{len(rows)} rows, want 2 (one per run)"
assert sorted(r["lambda"] for r in rows) == ["0.05", "0.06"], [r["lambda"] for r in rows]
for r in rows:
    assert r["surface"] == "sphere" and r["status"] == "complete", r
    assert int(r["vertices"]) > 0 and float(r["min_angle_deg"]) > 0, r
    assert r["topology_correct"] == "1", r
with open(path + ".json") as f:
    meta = json.load(f)
assert meta["program"] == "lambda_sweep" and meta["jobs"] == 2, meta
assert meta["parameters"]["lambdas"] == ["0.06", "0.05"], meta["parameters"]
assert meta["merge_slurm_job_id"] is None, "merge ran inside a Slurm job"
for name in ("lambda_bounds", "lambda_size", "size_ratio", "lfs_estimate"):
    for kind in ("pdf", "png"):
        figure = os.path.join(out, "figures", f"{name}.{kind}")
        assert os.path.getsize(figure) > 1000, figure
print("test-slurm.sh: merged lambda_sweep.csv: 2 rows, plain header, shortest λ; metadata jobs=2; "
      "figures as PDF and PNG")
EOF

stop_daemons
trap - EXIT
say "passed in $((SECONDS - started)) s"
