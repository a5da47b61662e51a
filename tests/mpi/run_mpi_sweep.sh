#!/usr/bin/env bash
# The MPI path of `topomill sweep`: 3 ranks on this machine share 8 cases and rank 0 gathers one
# table. Checks that every case ran once, on every rank, with one result file; then that a rerun
# under MPI resumes (runs nothing) and gives the same table.
# usage: run_mpi_sweep.sh TOPOMILL SOURCE_DIR WORK_DIR
set -euo pipefail
topomill="$1" src="$2" work="$3"
fail() { echo "mpi sweep: $*" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
cd "$src"
# Root in CI containers; more ranks than cores.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
sweep=(mpirun -n 3 "$topomill" sweep tests/stability/base.toml --vary region.lambda=10,20,30,40
       --vary cutting.feed_per_tooth=0.05,0.1 --out "$work/out")
"${sweep[@]}" >"$work/first.txt" 2>"$work/first.err" || fail "exit $? $(cat "$work/first.err")"
csv="$work/out/sweep.csv"
[ -f "$csv" ] || fail "no sweep.csv"
rows=$(($(wc -l <"$csv") - 1))
[ "$rows" -eq 8 ] || fail "$rows rows, expected 8"
[ "$(grep -c ',ok,' "$csv")" -eq 8 ] || fail "not every case ok: $(cat "$csv")"
head -1 "$csv" | grep -q ',rank$' || fail "no rank column: $(head -1 "$csv")"
ranks=$(tail -n +2 "$csv" | awk -F, '{print $NF}' | sort -u | tr '\n' ' ')
[ "$ranks" = "0 1 2 " ] || fail "cases ran on ranks '$ranks', expected 0 1 2"
[ "$(find "$work/out" -name sweep.csv | wc -l)" -eq 1 ] || fail "more than one sweep.csv"
[ "$(find "$work/out/cases" -name summary.json | wc -l)" -eq 8 ] || fail "not 8 case summaries"
grep -q "rank 2" "$work/first.err" || fail "no progress from rank 2"

cp "$csv" "$work/first.csv"
"${sweep[@]}" >"$work/second.txt" 2>"$work/second.err" || fail "rerun: exit $?"
# Counted as words, not lines: mpirun forwards the ranks' output in chunks of its own.
[ "$(grep -o 'done earlier' "$work/second.err" | wc -l)" -eq 8 ] ||
  fail "the rerun ran cases again: $(cat "$work/second.err")"
cmp -s <(cut -d, -f1-11 "$csv") <(cut -d, -f1-11 "$work/first.csv") || fail "the rerun's table differs"
echo "mpi sweep: ok (8 cases on ranks $ranks)"
