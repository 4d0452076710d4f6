/* The harness's memory: one static buffer, emptied at the start of every case. Bare-metal
 * builds have no malloc worth using for this, and a fixed arena keeps all targets alike. */
#ifndef FW_ARENA_H
#define FW_ARENA_H

#include <stddef.h>

/* `bytes` bytes aligned to 8, or NULL when the arena is full (the case then fails with
 * FW_STATUS_NO_MEMORY). `fw_alloc(0)` gives a valid non-NULL pointer. */
void *fw_alloc(size_t bytes);
void fw_arena_reset(void);

#endif
