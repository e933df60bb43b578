#!/usr/bin/env bash
# The sweep's CSV is byte-identical for any number of MPI ranks and threads
# (docs/gem-metrics.md, "Sweep"): a small sweep (12 cuts, one of them impossible, few rays)
# with 1 and 3 ranks and 1 and 2 threads, and without mpirun, compared byte for byte; and a
# sweep interrupted, then resumed under 3 ranks, into the same bytes.
# Usage: sweep_ranks.sh REFRACT MPIEXEC WORKDIR
set -euo pipefail
refract=$1 mpiexec=$2 dir=$3
rm -rf "$dir" && mkdir -p "$dir"
# As root, Open MPI asks for consent; 3 ranks may exceed the cores.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
sweep=(sweep brilliant --crown-angle 30:36:3 --pavilion-angle 40:44:1 --rays 32 --wavelengths 3 --quiet)
"$refract" "${sweep[@]}" --threads 1 -o "$dir/plain-1.csv" >/dev/null
"$refract" "${sweep[@]}" --threads 2 -o "$dir/plain-2.csv" >/dev/null
for np in 1 3; do
    for t in 1 2; do
        "$mpiexec" --oversubscribe -np "$np" "$refract" "${sweep[@]}" --threads "$t" -o "$dir/np$np-t$t.csv" >/dev/null
    done
done
rows=$(grep -c '' "$dir/plain-1.csv")
[ "$rows" -eq 16 ] || { echo "expected a header and 15 rows, got $rows lines"; exit 1; }
grep -q ',impossible,' "$dir/plain-1.csv" || { echo "no impossible cut recorded"; exit 1; }
for f in plain-2 np1-t1 np1-t2 np3-t1 np3-t2; do
    cmp "$dir/plain-1.csv" "$dir/$f.csv" || { echo "$f.csv differs from plain-1.csv"; exit 1; }
done
ls "$dir" | grep -q journal && { echo "a journal was left behind"; exit 1; }

# Resume under 3 ranks: an interrupted run's journal (its fingerprint line, rows 0 to 3 and a
# torn fifth line) and rank 2's part journal (rows 7 and 8) are merged and only the rest
# computed; the CSV is the same byte for byte.
"$refract" "${sweep[@]}" --threads 1 -o "$dir/resume.csv" >/dev/null &
pid=$!
for _ in $(seq 1 2000); do [ -s "$dir/resume.csv.journal" ] && break; sleep 0.005; done
kill -9 "$pid" 2>/dev/null || true
wait "$pid" 2>/dev/null || true
[ -s "$dir/resume.csv.journal" ] || { echo "the interrupted sweep wrote no journal"; exit 1; }
head -n 1 "$dir/resume.csv.journal" > "$dir/fingerprint"
{ cat "$dir/fingerprint"; sed -n 2,5p "$dir/plain-1.csv"; sed -n 6p "$dir/plain-1.csv" | head -c 15; } > "$dir/resume.csv.journal"
{ cat "$dir/fingerprint"; sed -n 9,10p "$dir/plain-1.csv"; } > "$dir/resume.csv.journal.2"
rm -f "$dir/resume.csv"
out=$("$mpiexec" --oversubscribe -np 3 "$refract" "${sweep[@]}" --threads 1 -o "$dir/resume.csv")
echo "$out"
echo "$out" | grep -q "6 resumed from the journal, 9 computed" || { echo "expected 6 rows resumed and 9 computed"; exit 1; }
cmp "$dir/plain-1.csv" "$dir/resume.csv" || { echo "the resumed CSV differs"; exit 1; }
ls "$dir" | grep -q journal && { echo "a journal was left behind after the resume"; exit 1; }
echo "sweep CSVs byte-identical for 1 and 3 ranks, 1 and 2 threads ($rows lines)"
