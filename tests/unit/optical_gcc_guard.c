/*
 * optical_gcc_guard.c - regression guard for a GCC 12 miscompilation that changed the host
 * results of the moving optical fixes (docs/optical.md "Host compiler: GCC 12 drops stores").
 *
 * At -O1 and above, GCC 12.2's ivopts address w.ang[i] from the induction variable of the
 * byte array w.pos[] as MEM[0B + K + &w * -3 + iv * 4]: a TARGET_MEM_REF with a literal 0
 * base. Local pure-const analysis takes that for a NULL dereference (undefined behaviour),
 * stops scanning the block, never sees the store, and declares rotate() pure; the caller then
 * deletes the call as one without effect. fix.c's heading rotation (gather()) has this shape.
 * Built with the project's compile options (CY_GCC_WORKAROUNDS), this program must see the
 * store.
 */
#include <stdint.h>
#include <stdio.h>

/* The shape of optical_work_t: byte arrays and a 32-bit array indexed by the same counter. */
struct work {
    uint8_t m;
    uint8_t pos[15];
    uint8_t ord[15];
    uint32_t ang[15];
};

static struct work w;

/* fix.c's rotation split out of gather(): the only effect is the store to w.ang. */
__attribute__((noinline)) static void rotate(const uint32_t *lat, uint32_t head)
{
    if (lat != NULL)
        for (uint8_t i = 0; i < w.m; i++)
            w.ang[i] += lat[w.ord[w.pos[i]]] - head;
}

int main(void)
{
    static const uint32_t lat[2] = {5u, 9u};
    w.m = 2;
    w.pos[0] = 1; /* ang[0] += lat[ord[1]] - 2 = 9 - 2 */
    w.ord[1] = 1;
    w.ang[1] = 100u; /* ang[1] += lat[ord[0]] - 2 = 5 - 2 */
    rotate(lat, 2u);
    printf("ang %lu %lu (expected 7 103)\n", (unsigned long)w.ang[0], (unsigned long)w.ang[1]);
    if (w.ang[0] != 7u || w.ang[1] != 103u) {
        printf("FAIL: the compiler deleted the call to rotate()\n");
        return 1;
    }
    return 0;
}
