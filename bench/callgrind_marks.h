#pragma once
// Marks for callgrind (`valgrind --tool=callgrind`): a benchmark zeroes the counters before
// the steps it times and dumps them after, so each timed part is a profile file of its own
// (`.1`, `.2`, ...). Without valgrind's headers, or outside valgrind, they do nothing.
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define UPGRAIN_ON_VALGRIND() (RUNNING_ON_VALGRIND != 0)
#define UPGRAIN_ZERO_STATS() CALLGRIND_ZERO_STATS
#define UPGRAIN_DUMP_STATS(what) CALLGRIND_DUMP_STATS_AT(what)
#else
#define UPGRAIN_ON_VALGRIND() false
#define UPGRAIN_ZERO_STATS()
#define UPGRAIN_DUMP_STATS(what)
#endif
