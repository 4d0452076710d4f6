/* FNV-1a over a little-endian byte stream: a stable, dependency-free fingerprint of the
 * exact output bits (not a cryptographic hash: the comparison is between our own builds). */
#include <string.h>

#include "harness.h"

#define FNV_PRIME 0x00000100000001B3ull

static void byte(fw_hash *h, unsigned b) {
    h->h ^= (uint64_t)(b & 0xFFu);
    h->h *= FNV_PRIME;
}

void fw_hash_u64(fw_hash *h, uint64_t v) {
    int i;
    for (i = 0; i < 8; i++) byte(h, (unsigned)(v >> (8 * i)));
}

void fw_hash_u32(fw_hash *h, uint32_t v) {
    int i;
    for (i = 0; i < 4; i++) byte(h, (unsigned)(v >> (8 * i)));
}

void fw_hash_f64s(fw_hash *h, const double *v, size_t n) {
    size_t i;
    for (i = 0; i < n; i++) {
        uint64_t bits;
        memcpy(&bits, &v[i], sizeof bits);
        fw_hash_u64(h, bits);
    }
}

void fw_hash_u32s(fw_hash *h, const uint32_t *v, size_t n) {
    size_t i;
    for (i = 0; i < n; i++) fw_hash_u32(h, v[i]);
}

int fw_same_bits(const double *a, const double *b, size_t n) {
    return memcmp(a, b, n * sizeof(double)) == 0;
}
