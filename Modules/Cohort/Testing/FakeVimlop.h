#ifndef vimlop_FakeVimlop_h
#define vimlop_FakeVimlop_h

// A stand-in for the `vimlop` program in the cohort's tests: a shell script
// that takes a row's command line as vimlop would and writes a result the
// way `vimlop register` does (atomically), so the runner is tested without
// the minutes a real registration takes. The real program runs in the CLI
// tests (Testing/Cohort).

#include "TestFolders.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>

namespace vimlop::fixtures
{

/**
 * @brief Writes the stand-in into `folder` and returns its path. It reads
 * --out (the row's folder), --ct (refused with vimlop's message when the
 * file does not exist), --sleep S, --flag-it (exit code 3, a flagged
 * result) and --threads; it writes <out>/result.json with what it was given
 * and the folder it ran in, and appends its row's --ct to <folder>/calls.txt.
 */
inline std::string writeFakeVimlop(const std::filesystem::path& folder)
{
  const std::filesystem::path path = folder / "fake-vimlop";
  std::ofstream(path) << R"SH(#!/bin/sh
out=; fail=; wait=0; flagged=false; threads=0; ct=
words="$1"; shift
if [ "$1" = synthetic ]; then words="$words $1"; shift; fi
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out=$2; shift ;;
    --ct) ct=$2; [ -e "$2" ] || fail="'$2': no such file or folder"; shift ;;
    --sleep) wait=$2; shift ;;
    --threads) threads=$2; shift ;;
    --flag-it) flagged=true ;;
    --force) ;;
    --*) [ $# -gt 1 ] && case "$2" in --*) ;; *) shift ;; esac ;;
  esac
  shift
done
echo "$ct" >> ')SH" +
      (folder / "calls.txt").string() +
      R"SH('
echo "fake vimlop: $words in $(pwd)"
sleep "$wait"
if [ -n "$fail" ]; then echo "vimlop: error: $fail" >&2; exit 1; fi
if [ "$words" = "evaluate synthetic" ]; then
  mkdir -p "$(dirname "$out")"
  printf '{"protocol": "P1", "seed": 4, "methods": {"vimlop": {"tre_mm": {"median": 0.07}, "runtime_s": {"median": 0.2}}}}\n' > "$out.tmp"
  mv "$out.tmp" "$out"
  exit 0
fi
mkdir -p "$out.partial"
printf '{"format": "vimlop-registration-result", "contour_error_px": 1.5, "runtime_s": 0.25,
 "transform": {"scale": 0.5}, "confidence": {"failure": %s, "failure_reason": "%s"},
 "ground_truth": {"camera_position_error_mm": [0.1, 0.3]},
 "parameters": {"threads": %s, "kappa": 200},
 "inputs": [{"role": "ct", "path": "%s", "sha256": "abc"}], "cwd": "%s"}\n' \
  "$flagged" "$([ "$flagged" = true ] && echo 'contour error too high')" "$threads" "$ct" "$(pwd)" \
  > "$out.partial/result.json"
rm -rf "$out"; mv "$out.partial" "$out"
[ "$flagged" = true ] && exit 3
exit 0
)SH";
  ::chmod(path.c_str(), 0755);
  return path.string();
}

} // namespace vimlop::fixtures

#endif
