#!/usr/bin/env bash
# Checks the shape of the tracked C++ sources (*.cpp, *.hpp under src/ and tests/): no file over
# 400 lines and no function over 60 lines. Lists the offenders and exits 1; exits 0 when none.
#   scripts/check_shape.sh [FILE...]     (default: every tracked file under src/ and tests/)
#
# The rule for functions (a heuristic, not a C++ parser): comments, string and character literals
# (raw strings included) and preprocessor lines are skipped, and braces are counted. An opening
# brace outside any function starts a function body when the text before it (since the last `;`,
# `{` or `}`) contains a `(` or ends with `]` (a lambda), does not start with namespace, class,
# struct, union or enum (after an optional template <...>) and does not end with `=` (an
# initialiser). So free functions, member functions defined in a class, constructors and gtest
# TEST/TEST_F/TEST_P bodies all count; lambdas and tables inside a function count as part of it.
# A function's length runs from the first line of its signature (template line included) to the
# line of its closing brace, both included. MAX_FILE_LINES and MAX_FUNCTION_LINES override the
# limits.
set -euo pipefail

max_file=${MAX_FILE_LINES:-400}
max_func=${MAX_FUNCTION_LINES:-60}

cd "$(dirname "$0")/.."
files=()
if [ $# -gt 0 ]; then
  files=("$@")
else
  while IFS= read -r -d '' f; do
    [ -f "$f" ] && files+=("$f")
  done < <(git ls-files -z -- 'src/*.cpp' 'src/*.hpp' 'tests/*.cpp' 'tests/*.hpp')
fi
if [ ${#files[@]} -eq 0 ]; then
  echo "check_shape.sh: no tracked C++ files found" >&2
  exit 2
fi

# One line per offender: FILE: N lines (limit L), or FILE:LINE: NAME is N lines (limit L).
offenders=$(awk -v max_file="$max_file" -v max_func="$max_func" '
function trim(s) { gsub(/[ \t]+/, " ", s); sub(/^ /, "", s); sub(/ $/, "", s); return s }
function reset_header() { header = ""; header_line = 0 }
function add_header(c) {
  if (header_line == 0 && c !~ /[ \t]/) header_line = FNR
  header = header c
}
# The text after a leading template <...> (angle brackets matched), trimmed.
function strip_template(t, k, nest, ch) {
  t = trim(t)
  if (t !~ /^template ?</) return t
  nest = 0
  for (k = 1; k <= length(t); k++) {
    ch = substr(t, k, 1)
    if (ch == "<") nest++
    else if (ch == ">" && --nest == 0) return trim(substr(t, k + 1))
  }
  return t
}
function is_function(h, t) {
  t = trim(h)
  if (t ~ /=$/) return 0
  t = strip_template(t)
  if (t ~ /^(namespace|class|struct|union|enum)([^A-Za-z0-9_]|$)/) return 0
  if (t ~ /^(typedef|using|extern)([^A-Za-z0-9_]|$)/) return 0
  return index(t, "(") > 0 || t ~ /\]$/
}
# A brace that initialises a member in a constructor initialiser list: "...) : a_{...}".
function is_member_init(h, t) {
  t = trim(h)
  return t ~ /\) ?(noexcept ?)?:[^:]/ && t ~ /[A-Za-z0-9_>]$/
}
function function_name(h, t, p) {
  t = strip_template(h)
  if (t ~ /^(TEST|TEST_F|TEST_P|TYPED_TEST)\(/) { sub(/\).*$/, ")", t); return t }
  p = index(t, "(")
  if (p > 0) t = substr(t, 1, p - 1)
  sub(/^.*[ *&]/, "", t)
  return t == "" ? "lambda" : t
}
function finish_file() {
  if (file != "" && lines > max_file) printf "%s: %d lines (limit %d)\n", file, lines, max_file
}
FNR == 1 {
  finish_file()
  file = FILENAME; lines = 0
  depth = 0; func_depth = -1; init_depth = -1
  in_block = 0; in_raw = 0; in_pp = 0
  reset_header()
}
{
  lines = FNR
  line = $0
  if (in_pp) { in_pp = (line ~ /\\$/); next }
  if (!in_block && !in_raw && line ~ /^[ \t]*#/) { in_pp = (line ~ /\\$/); next }
  n = length(line)
  i = 1
  while (i <= n) {
    c = substr(line, i, 1)
    if (in_block) {
      if (substr(line, i, 2) == "*/") { in_block = 0; i += 2 } else i++
      continue
    }
    if (in_raw) {
      p = index(substr(line, i), raw_end)
      if (p == 0) { i = n + 1 } else { in_raw = 0; i += p - 1 + length(raw_end) }
      continue
    }
    two = substr(line, i, 2)
    if (two == "//") break
    if (two == "/*") { in_block = 1; i += 2; continue }
    if (c == "\"") {
      prev = i > 1 ? substr(line, i - 1, 1) : ""
      if (prev == "R") {  # raw string R"delim( ... )delim"
        rest = substr(line, i + 1)
        p = index(rest, "(")
        raw_end = ")" substr(rest, 1, p - 1) "\""
        in_raw = 1
        i += p + 1
        add_header("\"")
        continue
      }
      j = i + 1
      while (j <= n) {
        d = substr(line, j, 1)
        if (d == "\\") { j += 2; continue }
        if (d == "\"") break
        j++
      }
      add_header("\"\"")
      i = j + 1
      continue
    }
    if (c == "'\''") {
      prev = i > 1 ? substr(line, i - 1, 1) : ""
      if (prev ~ /[0-9A-Za-z_]/) { i++; continue }  # digit separator
      j = i + 1
      while (j <= n) {
        d = substr(line, j, 1)
        if (d == "\\") { j += 2; continue }
        if (d == "'\''") break
        j++
      }
      add_header("0")
      i = j + 1
      continue
    }
    if (c == "{") {
      if (func_depth < 0 && init_depth < 0 && is_member_init(header)) {
        init_depth = depth
      } else if (func_depth < 0 && init_depth < 0 && is_function(header)) {
        func_depth = depth
        func_line = header_line > 0 ? header_line : FNR
        func_name = function_name(header)
        reset_header()
      } else if (init_depth < 0) {
        reset_header()
      }
      depth++
    } else if (c == "}") {
      depth--
      if (depth == init_depth) {
        init_depth = -1
        add_header("}")
      } else {
        if (depth == func_depth) {
          func_depth = -1
          len = FNR - func_line + 1
          if (len > max_func)
            printf "%s:%d: %s is %d lines (limit %d)\n", file, func_line, func_name, len, max_func
        }
        reset_header()
      }
    } else if (c == ";" && init_depth < 0) {
      reset_header()
    } else if (c == ":" && substr(line, i + 1, 1) != ":" && substr(line, i - 1, 1) != ":" &&
               trim(header) ~ /^(public|private|protected)$/) {
      reset_header()
    } else if (func_depth < 0) {
      add_header(c)
    }
    i++
  }
  if (func_depth < 0) add_header(" ")
}
END { finish_file() }
' "${files[@]}")

if [ -z "$offenders" ]; then
  echo "check_shape.sh: all ${#files[@]} files within $max_file lines, functions within $max_func"
  exit 0
fi
printf '%s\n' "$offenders"
echo "check_shape.sh: $(printf '%s\n' "$offenders" | wc -l) offenders in ${#files[@]} files" >&2
exit 1
