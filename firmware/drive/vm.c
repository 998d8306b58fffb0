/*
 * vm.c - the drive module's arithmetic helpers and the interpreter of drive_internal.h.
 */
#include "drive_internal.h"

/* clang-format off */
const int32_t drive_vm_k[DRIVE_K_COUNT] = {
    1686629713l,            /* round(pi / 2 * 2^30) */
    843314857l,             /* round(pi / 4 * 2^30) */
    431210l,                /* round(pi^2 / 24576 * 2^30) */
    586777454l,             /* round((8 / pi - 2) * 2^30) */
    178956971l, 20878313l, 2201455l,   /* 1/6, 7/360, 31/15120: x / sin x, error < 1e-9 */
    536870912l, 223696213l, 90969793l, /* 1/2, 5/24, 61/720: 1 / cos x, error < 1e-7 */
    -178956971l, 8947849l, -213044l,   /* -1/6, 1/120, -1/5040: sin x / x, error < 1e-9 */
};
/* clang-format on */

#ifndef DRIVE_ASM /* MSP430: msp430/vm.S */
void drive_rot(int32_t out[2], const int32_t xy[2], fx_angle_t a)
{
    fx_q30_t s, c;
    fx_sincos(a, &s, &c);
    out[0] = fx_mul_q30(xy[0], c) + fx_mul_q30(xy[1], s);
    out[1] = fx_mul_q30(xy[1], c) - fx_mul_q30(xy[0], s);
}

int32_t drive_poly(int32_t x, const int32_t *k)
{
    int32_t x2 = fx_mul_q30(x, x);
    int32_t t = fx_mul_q30(x2, k[2]);
    t = fx_mul_q30(x2, k[1] + t);
    t = fx_mul_q30(x2, k[0] + t);
    return (int32_t)(FX_Q30_ONE + t);
}

void drive_vm_run(int32_t *v, const uint8_t *prog)
{
    for (; *prog != DRIVE_OP_END; prog += 4) {
        int32_t *d = &v[prog[1] / 4];
        const int32_t *pa = &v[prog[2] / 4];
        int32_t a = *pa;
        uint8_t b = prog[3]; /* a slot's or a constant's byte offset, or a count */
        switch (prog[0]) {
        case DRIVE_OP_ADD:
            *d = (int32_t)((uint32_t)a + (uint32_t)v[b / 4]);
            break;
        case DRIVE_OP_SUB:
            *d = (int32_t)((uint32_t)a - (uint32_t)v[b / 4]);
            break;
        case DRIVE_OP_NEG:
            *d = (int32_t)(0u - (uint32_t)a);
            break;
        case DRIVE_OP_ABS:
            *d = (int32_t)drive_abs32(a);
            break;
        case DRIVE_OP_HALF:
            *d = a / 2;
            break;
        case DRIVE_OP_SHL:
            *d = (int32_t)((uint32_t)a << b);
            break;
        case DRIVE_OP_MUL:
            *d = fx_mul_q30(a, v[b / 4]);
            break;
        case DRIVE_OP_MULK:
            *d = fx_mul_q30(a, drive_vm_k[b / 4]);
            break;
        case DRIVE_OP_POLY:
            *d = drive_poly(a, &drive_vm_k[b / 4]);
            break;
        case DRIVE_OP_ATAN2:
            *d = (int32_t)fx_atan2(a, v[b / 4]);
            break;
        case DRIVE_OP_SINCOS:
            fx_sincos((fx_angle_t)a, &d[0], &d[1]);
            break;
        default: /* DRIVE_OP_ROT */
            drive_rot(d, pa, (fx_angle_t)v[b / 4]);
            break;
        }
    }
}
#endif
