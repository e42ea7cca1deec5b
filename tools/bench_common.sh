# Sourced by the tools/bench_*.sh scripts (after they cd to the repository root): the
# helpers each of them needs to read --stats-json files and take medians.
# num FIELD FILE: the first number of field FIELD in a --stats-json file.
num() { sed -n "s/.*\"$1\":[[:space:]]*\([-0-9.e+]*\).*/\1/p" "$2" | head -1; }
# median: of the numbers on stdin, one a line (the mean of the middle two for an even count).
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
# as_the_tests: run on lavapipe (unless VK_DRIVER_FILES names another driver) with the
# Khronos validation layer and synchronization validation on, as every test does.
as_the_tests() {
  export VK_DRIVER_FILES=${VK_DRIVER_FILES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json}
  export VK_ICD_FILENAMES=$VK_DRIVER_FILES XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp} VKRAYCAST_VALIDATION=1
  export VK_LAYER_ENABLES=VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT
}
