/*
 * mcp2515_spi.c - hal/spi.h over the MCP2515 model (mcp2515_spi.h).
 */
#include "mcp2515_spi.h"

#include <stddef.h>

#include "cy_test.h"

static mcp2515_model_t *model;
static uint8_t ready;
static int8_t held = -1;
static mcp2515_spi_stats_t stats;

void mcp2515_spi_attach(mcp2515_model_t *m)
{
    model = m;
    ready = 0u;
    held = -1;
    stats = (mcp2515_spi_stats_t){HAL_SPI_MODE_0, 0u, 0u, 0u, 0u};
}

const mcp2515_spi_stats_t *mcp2515_spi_stats(void)
{
    return &stats;
}

int hal_spi_init(hal_spi_bus_t bus, uint32_t rate_hz, hal_spi_mode_t mode)
{
    if ((unsigned)bus >= HAL_SPI_BUS_COUNT || (unsigned)mode >= HAL_SPI_MODE_COUNT || rate_hz == 0u)
        return HAL_SPI_ERR_ARG;
    stats.mode = mode;
    stats.rate_hz = rate_hz;
    ready = 1u;
    held = -1;
    return HAL_SPI_OK;
}

uint32_t hal_spi_rate(hal_spi_bus_t bus)
{
    return (unsigned)bus < HAL_SPI_BUS_COUNT && ready ? stats.rate_hz : 0u;
}

int hal_spi_transfer(hal_spi_bus_t bus, hal_spi_cs_t cs, const uint8_t *tx, uint8_t *rx, uint16_t n,
                     uint8_t flags)
{
    if ((unsigned)bus >= HAL_SPI_BUS_COUNT || (unsigned)cs >= HAL_SPI_CS_COUNT ||
        (flags & (uint8_t)~HAL_SPI_HOLD) != 0u)
        return HAL_SPI_ERR_ARG;
    if (!ready || (held >= 0 && held != (int8_t)cs))
        return HAL_SPI_ERR_STATE;
    uint16_t t0 = cy_bench_now();
    if (held < 0) {
        stats.frames++;
        if (model != NULL)
            mcp2515_model_select(model);
    }
    for (uint16_t i = 0; i < n; i++) {
        uint8_t out = tx != NULL ? tx[i] : 0u;
        uint8_t in = model != NULL ? mcp2515_model_exchange(model, out) : 0xFFu;
        if (rx != NULL)
            rx[i] = in;
    }
    stats.bytes += n;
    if (flags & HAL_SPI_HOLD) {
        held = (int8_t)cs;
    } else {
        held = -1;
        if (model != NULL)
            mcp2515_model_deselect(model);
    }
    stats.cycles += (uint16_t)(cy_bench_now() - t0);
    return HAL_SPI_OK;
}
