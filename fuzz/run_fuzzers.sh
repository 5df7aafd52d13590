#!/usr/bin/env bash
# Runs each libFuzzer target for SECONDS on a scratch copy of its seed corpus
# (datasets/fuzz/TARGET/), so that the repository is never modified, and fails
# if any target finds anything (a crash, a sanitizer report, a broken contract,
# a hang past -timeout, a leak). Prints per target: executions, exec/s,
# coverage (cov: edges, ft: features) and the corpus size at the end.
#
#   fuzz/run_fuzzers.sh SECONDS [BUILD_DIR] [CORPUS_ROOT]
#
# BUILD_DIR: where the targets are (default build/fuzz: `cmake --preset fuzz &&
# cmake --build --preset fuzz -j2`). A finding's input is copied to
# BUILD_DIR/fuzz-findings/TARGET/; reproduce it with `BUILD_DIR/TARGET FILE`.
# FUZZ_TARGETS (environment) picks targets, e.g. FUZZ_TARGETS=fuzz_scene.
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
seconds="${1:?usage: run_fuzzers.sh SECONDS [BUILD_DIR] [CORPUS_ROOT]}"
build="${2:-$here/../build/fuzz}"
corpus_root="${3:-$here/../datasets/fuzz}"
targets=(${FUZZ_TARGETS:-fuzz_scene fuzz_toi_query fuzz_run_file})

# Per target: the seed folder, the input size limit, a dictionary if any.
declare -A seeds=([fuzz_scene]=scene [fuzz_toi_query]=toi_query [fuzz_run_file]=run_file)
declare -A max_len=([fuzz_scene]=8192 [fuzz_toi_query]=4096 [fuzz_run_file]=4096)
declare -A dict=([fuzz_scene]="$here/json.dict" [fuzz_toi_query]="$here/json.dict" [fuzz_run_file]="")
# fuzz_run_file runs about 30 inputs a second (each writes and reads HDF5
# files, slow under ASan): libFuzzer's slowly growing length limit would keep
# its inputs a few bytes long for the whole run, so the limit is lifted.
declare -A extra=([fuzz_scene]="" [fuzz_toi_query]="" [fuzz_run_file]="-len_control=0")

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$here/lsan.supp}"

work="$(mktemp -d "${TMPDIR:-/tmp}/collide2d-fuzz-run.XXXXXX")"
trap 'rm -rf "$work"' EXIT
failed=0
printf '%-15s %10s %8s %6s %6s %8s %10s  %s\n' target executions exec/s cov ft corpus bytes result
for t in "${targets[@]}"; do
  exe="$build/$t"
  if [[ ! -x "$exe" ]]; then
    echo "$t: not built ($exe); build with: cmake --preset fuzz && cmake --build --preset fuzz -j2" >&2
    failed=1
    continue
  fi
  corpus="$work/$t/corpus"
  mkdir -p "$corpus" "$work/$t/artifacts"
  cp -r "$corpus_root/${seeds[$t]}/." "$corpus/" 2>/dev/null
  rm -f "$corpus/README.md"
  args=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len="${max_len[$t]}"
        -print_final_stats=1 -artifact_prefix="$work/$t/artifacts/")
  [[ -n "${dict[$t]}" ]] && args+=(-dict="${dict[$t]}")
  [[ -n "${extra[$t]}" ]] && args+=(${extra[$t]})
  log="$work/$t/log"
  "$exe" "${args[@]}" "$corpus" >"$log" 2>&1
  code=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  status_line=$(grep -E '^#[0-9]+[[:space:]]' "$log" | grep -E 'cov: ' | tail -1)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$status_line")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$status_line")
  entries=$(find "$corpus" -type f | wc -l)
  bytes=$(find "$corpus" -type f -printf '%s\n' | awk '{s += $1} END {print s + 0}')
  result=ok
  if ((code != 0)) || compgen -G "$work/$t/artifacts/*" >/dev/null; then
    result="FINDING (exit $code)"
    failed=1
    keep="$build/fuzz-findings/$t"
    mkdir -p "$keep"
    cp "$work/$t/artifacts/"* "$keep/" 2>/dev/null
  fi
  printf '%-15s %10s %8s %6s %6s %8s %10s  %s\n' "$t" "${execs:-?}" "${rate:-?}" "${cov:-?}" "${ft:-?}" \
    "$entries" "$bytes" "$result"
  grep -E '^fuzz_run_file: [0-9]+ inputs' "$log" | tail -1 | sed 's/^/    /'
  if [[ "$result" != ok ]]; then
    echo "---- $t: the end of its log; the input is in $keep/" >&2
    grep -v -E '^#[0-9]+[[:space:]]' "$log" | tail -40 >&2
  fi
done
exit $failed
