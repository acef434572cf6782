#!/usr/bin/env bash
# The statistical tests' bounds that do not say what they bound (project issue "Guards that can
# fail", item 12): a bound on a statistic fails at its false-alarm rate on some random stream, so
# it should name the statistic and the rate. Lists every EXPECT_/ASSERT_ LT, GT, LE, GE or NEAR
# under tests/ (all of it, tests/app included) that compares against a bare numeric literal (the
# tolerance, for NEAR) inside code that draws random numbers, without a comment on the same or
# the 3 lines before that names a statistic or a false-alarm rate (chi-square, false-alarm,
# bound, quantile, %, sigma, standard error or deviation, sd, Student's t, binomial, NEES, ...),
# or that says the literal is "not a statistic" and why (a geometric or counting check in code
# that happens to draw: metres a wrong start leaves, a row of a projection, a count of restarts).
# Code that draws: a top-level block (a TEST or a function: from a line at column 0 to the next
# "}" at column 0) that calls testing::seed(, seeds a generator with a literal or a seed variable
# (std::mt19937 rng(3), Rng rng(1), make_rng(42, ...)) or passes a literal seed to the tests'
# seeded helpers (make_loop, clock_offset_loop, simulate_dvl/mru/gps, random_*), every block of the
# same file that calls such a block (up to the tests), and every block those call (down to their
# helpers). Literals of 1e-4 or less in magnitude (numerical tolerances), 0 (sign checks) and
# unsigned ones (sizes) are not bounds on a statistic here.
# A heuristic (grep and awk, no parsing): it reads one file at a time and not what a helper in
# another file does with its arguments. Prints FILE:LINE: the check, then the count. Each finding
# says whether its code draws from testing::seed (a statistical test tools/seed_offsets.sh runs on
# other streams) or from a fixed seed only.
# --at-most N makes it a ratchet (the ctest Tests.StatisticalBoundsNameTheirStatistic): exit 1
# when more than N bounds name nothing, so a new bare bound fails the suite while the old ones
# are worked off; lower N as they are.
# Usage: tools/check_stat_bounds.sh [--at-most N] [ROOT]   (ROOT defaults to the checkout; takes
# seconds). Exit status: 0, or 1 past N; 2 on bad arguments.
set -euo pipefail
at_most=""
if [ "${1:-}" = "--at-most" ]; then
  [[ "${2:-}" =~ ^[0-9]+$ ]] || { echo "check_stat_bounds: --at-most needs a whole number" >&2; exit 2; }
  at_most="$2"
  shift 2
fi
root="${1:-$(dirname "$0")/..}"
cd "$root"
[ -d tests ] || { echo "check_stat_bounds: no tests/ under $root" >&2; exit 2; }
# The checks' own fixtures (tests/*_fixture) hold bare bounds on purpose.
mapfile -t files < <(find tests -type d -name '*_fixture' -prune -o \( -name '*.cpp' -o -name '*.hpp' \) -print | sort)
out=$(mktemp)
trap 'rm -f "$out"' EXIT
for f in "${files[@]}"; do
  grep -qE 'EXPECT_|ASSERT_' "$f" || continue
  awk -v file="$f" '
    function block_name(line,   m) {
      if (match(line, /^(TEST|TEST_F|TEST_P)\([ ]*[A-Za-z0-9_]+[ ]*,[ ]*[A-Za-z0-9_]+/)) {
        m = substr(line, RSTART, RLENGTH); sub(/^TEST(_F|_P)?\([ ]*/, "", m); gsub(/[ ]*,[ ]*/, ".", m)
        return m
      }
      if (match(line, /[A-Za-z_][A-Za-z0-9_]*\(/)) return substr(line, RSTART, RLENGTH - 1)
      return ""
    }
    function draws(line) {
      return line ~ /testing::seed\(/ ||
             line ~ /(mt19937(_64)?|minstd_rand0?|default_random_engine|ranlux[a-z0-9_]*|knuth_b|Rng|Xoshiro256)[ ]+[A-Za-z_][A-Za-z0-9_]*[({][ ]*([0-9]+|[A-Za-z_]*seed[A-Za-z_0-9]*)/ ||
             line ~ /make_rng\([ ]*[0-9]/ ||
             line ~ /(make_loop|clock_offset_loop|random_[a-z_]+)\([ ]*[0-9]/ ||
             line ~ /simulate_(dvl|mru|gps)\(.*,[ ]*[0-9]+[ ]*\)/
    }
    function calls(i, j) {
      return i != j && name[j] != "" && name[j] !~ /\./ && index(text[i], name[j] "(") > 0
    }
    function top_level(line) {
      return line ~ /^[A-Za-z_]/ && line !~ /^(namespace|using|template|#|extern)/
    }
    # Pass 1: the blocks, which of them draw, and their text (to see who calls whom).
    NR == FNR {
      if (top_level($0)) { b = ++blocks; name[b] = block_name($0); direct[b] = 0; text[b] = "" }
      else if ($0 ~ /^}/) { b = 0 }
      owner[FNR] = b
      if (b) {
        text[b] = text[b] " " $0
        if (draws($0)) direct[b] = 1
        if ($0 ~ /testing::seed\(/) seeded[b] = 1
      }
      next
    }
    FNR == 1 {
      # Who calls whom inside the file: a block that calls a marked block is marked (up to the
      # tests), and so is a block a marked block calls (down to their helpers), not a sibling that
      # merely shares a helper with one.
      for (i = 1; i <= blocks; ++i) { up[i] = direct[i]; wired_up[i] = seeded[i] }
      for (changed = 1; changed;) {
        changed = 0
        for (i = 1; i <= blocks; ++i) for (j = 1; j <= blocks; ++j) {
          if (!calls(i, j)) continue
          if (up[j] && !up[i]) { up[i] = 1; changed = 1 }
          if (wired_up[j] && !wired_up[i]) { wired_up[i] = 1; changed = 1 }
        }
      }
      for (i = 1; i <= blocks; ++i) { marked[i] = up[i]; wired[i] = wired_up[i] }
      for (changed = 1; changed;) {
        changed = 0
        for (i = 1; i <= blocks; ++i) for (j = 1; j <= blocks; ++j) {
          if (!calls(i, j)) continue
          if (marked[i] && !marked[j]) { marked[j] = 1; changed = 1 }
          if (wired[i] && !wired[j]) { wired[j] = 1; changed = 1 }
        }
      }
      stmt = ""; depth = 0
    }
    {
      line = $0; comment = ""
      if ((c = index(line, "//")) > 0) { comment = substr(line, c); line = substr(line, 1, c - 1) }
      if (line ~ /^[ ]*\/?\*/) comment = line
      # The comments of the 3 lines before a check and of its own lines.
      if (stmt == "") {
        if (!marked[owner[FNR]] || line !~ /(EXPECT|ASSERT)_(LT|GT|LE|GE|NEAR)\(/) {
          c3 = c2; c2 = c1; c1 = comment; next
        }
        start = FNR; stmt_comment = c1 " " c2 " " c3 " " comment
        match(line, /(EXPECT|ASSERT)_(LT|GT|LE|GE|NEAR)\(/); stmt = substr(line, RSTART)
      } else {
        stmt = stmt " " line; stmt_comment = stmt_comment " " comment
      }
      c3 = c2; c2 = c1; c1 = comment
      # The check ends where its parentheses close.
      n_open = gsub(/\(/, "(", stmt); n_close = gsub(/\)/, ")", stmt)
      if (n_open > n_close) next
      check(stmt, stmt_comment, start)
      stmt = ""
    }
    function check(s, comments, at,   kind, args, n, i, d, ch, cur, arg, lits, bare, v) {
      match(s, /(EXPECT|ASSERT)_(LT|GT|LE|GE|NEAR)\(/)
      kind = substr(s, RSTART, RLENGTH - 1)
      s = substr(s, RSTART + RLENGTH)
      n = 0; d = 0; cur = ""
      for (i = 1; i <= length(s); ++i) {
        ch = substr(s, i, 1)
        if (ch == "(" || ch == "[" || ch == "{") d++
        if (ch == ")" || ch == "]" || ch == "}") { if (d == 0) break; d-- }
        if (ch == "," && d == 0) { args[++n] = cur; cur = ""; continue }
        cur = cur ch
      }
      args[++n] = cur
      lits = ""
      for (i = 1; i <= n; ++i) {
        if (kind ~ /NEAR/ && i != 3) continue
        arg = args[i]; gsub(/^[ ]+|[ ]+$/, "", arg)
        if (arg !~ /^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?[fFuUlL]*$/) continue
        v = arg; gsub(/[fFuUlL]+$/, "", v); v = v + 0; if (v < 0) v = -v
        if (v == 0 || v <= 1e-4 || arg ~ /[uU]/) continue
        lits = lits (lits == "" ? "" : ", ") arg
      }
      if (lits == "") return
      if (tolower(comments) ~ /chi-?squared?|chi2|false[- ]alarm|bound|quantile|%|sigma|standard (error|deviation)|(^|[^a-z])sd([^a-z]|$)|student|(^|[^a-z])t[- ](test|quantile|distribution)|binomial|nees|p-value|confidence|sampling|probability|not a statistic/) return
      name_at = name[owner[at]]
      printf "%s:%d: %s against %s in %s (%s): no comment names its statistic or false-alarm " \
             "rate\n", file, at, kind, lits, (name_at == "" ? "?" : name_at), \
             (wired[owner[at]] ? "draws from testing::seed" : "fixed seed")
    }
  ' "$f" "$f" >>"$out"
done
cat "$out"
count=$(wc -l <"$out")
seeded=$(grep -c 'draws from testing::seed' "$out" || true)
echo "check_stat_bounds: $count bounds in code that draws random numbers name no statistic or" \
  "false-alarm rate ($seeded of them in code that draws from testing::seed, $((count - seeded))" \
  "with a fixed seed; $(cut -d: -f1 "$out" | sort -u | wc -l) files of ${#files[@]} scanned)"
if [ -n "$at_most" ] && [ "$count" -gt "$at_most" ]; then
  echo "check_stat_bounds: $count is more than the $at_most allowed: a bound added without its" \
    "statistic? Name the statistic and its false-alarm rate beside it (docs/reliability.md)" >&2
  exit 1
fi
