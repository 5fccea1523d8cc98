# Run-time options of the sanitizer builds (FINFLEX_SANITIZE), sourced by .ci/run;
# source it before running a sanitizer build's tests by hand too. README.md says why.
sanitizers_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
export ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:check_initialization_order=1:detect_stack_use_after_return=1
export LSAN_OPTIONS=suppressions=$sanitizers_dir/lsan.supp:print_suppressions=0:use_tls=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export TSAN_OPTIONS=suppressions=$sanitizers_dir/tsan.supp:halt_on_error=1:second_deadlock_stack=1
unset sanitizers_dir
