# Sourced by the tools/bench_*.sh scripts (after they cd to the repository root): the
# helpers each of them needs to read --stats-json files and take medians.
# num FIELD FILE: the first number of field FIELD in a --stats-json file.
num() { sed -n "s/.*\"$1\":[[:space:]]*\([-0-9.e+]*\).*/\1/p" "$2" | head -1; }
# median: of the numbers on stdin, one a line (the mean of the middle two for an even count).
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
