// ref_crc8.h - the reference CRC-8 of the host tests (link_test, linkmsg_test): CRC-8/SMBUS
// (polynomial 0x07, initial 0, MSB first), written bit by bit from its definition,
// independently of hal/common/link_framer.c.
#ifndef CY_REF_CRC8_H
#define CY_REF_CRC8_H

#include <cstdint>
#include <vector>

inline uint8_t ref_crc8(const std::vector<uint8_t> &v)
{
    unsigned crc = 0;
    for (uint8_t byte : v)
        for (int i = 7; i >= 0; i--) {
            unsigned bit = ((crc >> 7) ^ (byte >> i)) & 1u;
            crc = ((crc << 1) & 0xFFu) ^ (bit ? 0x07u : 0u);
        }
    return (uint8_t)crc;
}

#endif
