#!/usr/bin/env bash
# The sweep's CSV is byte-identical for any number of MPI ranks and threads
# (docs/gem-metrics.md, "Sweep"): a small sweep (12 cuts, one of them impossible, few rays)
# with 1 and 3 ranks and 1 and 2 threads, and without mpirun, compared byte for byte.
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
echo "sweep CSVs byte-identical for 1 and 3 ranks, 1 and 2 threads ($rows lines)"
