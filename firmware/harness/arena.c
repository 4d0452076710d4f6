#include <stdint.h>

#include "arena.h"

/* 1 MiB: the largest case (two levels of Möbius Catmull–Clark on the mixed star, with the
 * scratch of the plan) needs far less; RAM on the MPS2 boards is 4 MiB. */
#define FW_ARENA_BYTES (1u << 20)

static uint64_t arena[FW_ARENA_BYTES / 8];
static size_t used; /* in 8-byte words */

void fw_arena_reset(void) { used = 0; }

void *fw_alloc(size_t bytes) {
    size_t words = (bytes + 7) / 8;
    void *p;
    if (words > FW_ARENA_BYTES / 8 - used) return NULL;
    p = &arena[used];
    used += words;
    return p;
}
