// The -finstrument-functions hooks behind bench/open_path_count.sh. Linked into an instrumented
// wangscape (project code only: third-party headers under /usr/ are not instrumented), they keep
// every thread's stack of entered functions and, inside one window, write a line for the first
// entry of each function (any thread):
//   F <seq> <thread> <function> <stack, outermost first, comma-separated>
// Addresses are offsets from the executable's start (__executable_start), as `nm` prints them
// for a PIE. The window (environment, hex offsets from nm):
//   OPEN_PATH_ROOT  the window opens when this function is entered (ViewWorld::load)
//   OPEN_PATH_STOP  it closes when this one is entered (LdiRenderer::render); unset: when ROOT
//                   returns on the thread that entered it
//   OPEN_PATH_OUT   the file the lines go to
#define _GNU_SOURCE
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NO_TRACE __attribute__((no_instrument_function))
#define MAX_DEPTH 4096
#define LOCAL_SLOTS (1u << 16)
#define GLOBAL_SLOTS (1u << 20)

extern char __executable_start;

static uintptr_t root_fn, stop_fn;
static FILE* out;
static volatile int active, done;
static unsigned long seq;
static pthread_t root_thread;
static int root_depth = -1;
static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static uintptr_t* global_seen;  // open addressing, under `lock`
static int next_thread;

static __thread uintptr_t stack[MAX_DEPTH];
static __thread int depth;
static __thread uintptr_t* local_seen;  // functions this thread knows were already written
static __thread int thread_id = -1;

NO_TRACE static uintptr_t offset(void* fn) { return (uintptr_t)fn - (uintptr_t)&__executable_start; }

NO_TRACE static int insert(uintptr_t* set, uint32_t slots, uintptr_t key) {  // 1: was new
  uint32_t h = (uint32_t)((key * 0x9E3779B97F4A7C15ull) >> 40) & (slots - 1);
  while (set[h]) {
    if (set[h] == key) return 0;
    h = (h + 1) & (slots - 1);
  }
  set[h] = key;
  return 1;
}

NO_TRACE __attribute__((constructor)) static void start(void) {
  const char* r = getenv("OPEN_PATH_ROOT");
  const char* s = getenv("OPEN_PATH_STOP");
  const char* o = getenv("OPEN_PATH_OUT");
  if (!r || !o) return;
  root_fn = strtoull(r, 0, 16);
  stop_fn = s ? strtoull(s, 0, 16) : 0;
  out = fopen(o, "w");
  global_seen = calloc(GLOBAL_SLOTS, sizeof(uintptr_t));
}

NO_TRACE static void write_first(uintptr_t fn) {
  if (!local_seen) local_seen = calloc(LOCAL_SLOTS, sizeof(uintptr_t));
  if (!insert(local_seen, LOCAL_SLOTS, fn)) return;
  pthread_mutex_lock(&lock);
  if (active && insert(global_seen, GLOBAL_SLOTS, fn)) {
    if (thread_id < 0) thread_id = next_thread++;
    fprintf(out, "F %lu %d %lx ", seq++, thread_id, (unsigned long)fn);
    for (int i = 0; i < depth && i < MAX_DEPTH; ++i) fprintf(out, i ? ",%lx" : "%lx", (unsigned long)stack[i]);
    fputc('\n', out);
  }
  pthread_mutex_unlock(&lock);
}

NO_TRACE void __cyg_profile_func_enter(void* this_fn, void* call_site) {
  (void)call_site;
  if (!out) return;
  const uintptr_t fn = offset(this_fn);
  if (!done && fn == root_fn && !active) {
    pthread_mutex_lock(&lock);
    active = 1;
    root_thread = pthread_self();
    root_depth = depth;
    pthread_mutex_unlock(&lock);
  } else if (active && stop_fn && fn == stop_fn) {
    pthread_mutex_lock(&lock);
    active = 0;
    done = 1;
    fflush(out);
    pthread_mutex_unlock(&lock);
  }
  if (active) write_first(fn);
  if (depth < MAX_DEPTH) stack[depth] = fn;
  ++depth;
}

NO_TRACE void __cyg_profile_func_exit(void* this_fn, void* call_site) {
  (void)this_fn;
  (void)call_site;
  if (!out) return;
  --depth;
  if (active && !stop_fn && depth == root_depth && pthread_equal(pthread_self(), root_thread)) {
    pthread_mutex_lock(&lock);
    active = 0;
    done = 1;
    fflush(out);
    pthread_mutex_unlock(&lock);
  }
}
