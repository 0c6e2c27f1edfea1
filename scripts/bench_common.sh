# Shell functions shared by scripts/bench_rounds.sh and scripts/bench_pinned.sh (sourced, not run).

# The median of the numbers on stdin, one per line.
median() { sort -g | awk '{ v[NR] = $1 } END { if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# The wall time in a `vrsph bench --json` file.
wall_of() { python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['wall_seconds'])" "$1"; }

# split_config CONF DEFAULT_BIN: a configuration's binary and bench arguments, in the globals
# config_bin and config_args: CONF is 'ARGS', or '@BIN ARGS' for another binary.
split_config() {
  config_args=$1 config_bin=$2
  if [[ "$config_args" == @* ]]; then
    config_bin=${config_args%% *}; config_bin=${config_bin#@}; config_args=${config_args#* }
  fi
}
