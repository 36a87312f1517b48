# Phase timing for the project's jobs (.ci/run, verify.sh, sanitize.sh, tsan.sh, fuzz.sh): source it, then
#   phase "name" command args...
# runs the command and, when DEM2D_PHASES names a file, appends a line "start<TAB>seconds<TAB>depth<TAB>exit
# status<TAB>name" to it (a phase inside a phase is one level deeper). `phase_table FILE` prints the table
# of a job, phases in the order they started, nested ones indented, with the total of the top level.
# Without DEM2D_PHASES, phase just runs the command (and returns its status).

phase() {
  local name=$1; shift
  local start end status=0
  start=$(date +%s.%N)
  DEM2D_PHASE_DEPTH=$(( ${DEM2D_PHASE_DEPTH:-0} + 1 )) "$@" || status=$?
  end=$(date +%s.%N)
  if [ -n "${DEM2D_PHASES:-}" ]; then
    printf '%s\t%s\t%s\t%s\t%s\n' "$start" "$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')" \
      "${DEM2D_PHASE_DEPTH:-0}" "$status" "$name" >> "$DEM2D_PHASES"
  fi
  return $status
}

phase_table() {
  sort -n -k1,1 "$1" | awk -F'\t' '
    { indent = ""; for (i = 0; i < $3; i++) indent = indent "  "
      printf "| %-62s | %7.0f | %s |\n", indent $5, $2, ($4 == 0 ? "ok" : "exit " $4)
      if ($3 == 0) total += $2 }
    BEGIN { printf "| %-62s | %7s | %s |\n|%s|%s|%s|\n", "phase", "seconds", "result",
            "----------------------------------------------------------------", "---------", "--------" }
    END { printf "| %-62s | %7.0f |        |\n", "total (top level)", total }'
}
