# Sourced by the benchmark scripts: wait until the machine is quiet before a timed run.
# Other builds steal cycles from the OpenMP threads and stall them at the colour barriers.
# Uses idle_min (percent), wait_max (seconds) and bench_name (for messages) of the caller.

# Percentage of CPU time idle over a 2-second sample (all CPUs, from /proc/stat).
idle_percent() {
  local a b
  read -r -a a < <(head -n 1 /proc/stat)
  sleep 2
  read -r -a b < <(head -n 1 /proc/stat)
  local total=0 i
  for i in 1 2 3 4 5 6 7 8; do total=$((total + b[i] - a[i])); done
  local idle=$((b[4] - a[4] + b[5] - a[5]))
  echo $((total > 0 ? 100 * idle / total : 100))
}

# Wait until the CPUs are quiet; prints a line for the log.
wait_quiet() {
  local waited=0 idle
  while :; do
    idle="$(idle_percent)"
    if ((idle >= idle_min)); then
      echo "bench: cpu idle ${idle}% after waiting ${waited} s; loadavg $(cut -d' ' -f1-3 /proc/loadavg)"
      return
    fi
    if ((waited >= wait_max)); then
      echo "bench: WARNING cpu only ${idle}% idle after waiting ${waited} s; running anyway" \
        "(loadavg $(cut -d' ' -f1-3 /proc/loadavg))"
      echo "$bench_name: machine busy (${idle}% idle), running anyway" >&2
      return
    fi
    sleep 28
    waited=$((waited + 30))
  done
}
