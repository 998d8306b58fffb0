// The MCP2515 driver (firmware/can) against the register model (tests/support) behind
// hal/spi.h (tests/support/mcp2515_spi.c). Expected register values are typed from the data
// sheet DS20001801 (register map Table 11-1, register descriptions, the bit timing formulas
// of section 5), not taken from the driver; the model's own semantics are checked by
// mcp2515_model_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

extern "C" {
#include "can/mcp2515.h"
#include "mcp2515_model.h"
#include "mcp2515_spi.h"
}

namespace
{

// DS20001801 Table 11-1
constexpr uint8_t RXF0SIDH = 0x00, CANSTAT = 0x0E, CANCTRL = 0x0F, TEC = 0x1C, RXM0SIDH = 0x20,
                  CNF3 = 0x28, CNF2 = 0x29, CNF1 = 0x2A, CANINTE = 0x2B, CANINTF = 0x2C,
                  EFLG = 0x2D, TXB0CTRL = 0x30, RXB0CTRL = 0x60, RXB1CTRL = 0x70;

struct Mcp2515Driver : ::testing::Test {
    mcp2515_model_t model;
    mcp2515_t drv;
    mcp2515_config_t cfg;
    std::vector<mcp2515_frame_t> received;
    std::vector<mcp2515_model_frame_t> on_wire;
    std::vector<mcp2515_model_tx_t> answers; // what the bus does next (then ACK)
    unsigned tx_free_calls = 0;
    mcp2515_model_frame_t flood{}; // delivered again from inside the receive callback
    unsigned flood_left = 0;

    static void on_rx(void *arg, const mcp2515_frame_t *f)
    {
        auto *self = static_cast<Mcp2515Driver *>(arg);
        self->received.push_back(*f);
        if (self->flood_left) {
            self->flood_left--;
            mcp2515_model_receive(&self->model, &self->flood);
        }
    }
    static void on_tx(void *arg)
    {
        static_cast<Mcp2515Driver *>(arg)->tx_free_calls++;
    }
    static mcp2515_model_tx_t on_bus(void *arg, const mcp2515_model_frame_t *f)
    {
        auto *self = static_cast<Mcp2515Driver *>(arg);
        self->on_wire.push_back(*f);
        if (self->answers.empty())
            return MCP2515_MODEL_TX_ACK;
        mcp2515_model_tx_t a = self->answers.front();
        self->answers.erase(self->answers.begin());
        return a;
    }

    void SetUp() override
    {
        mcp2515_model_init(&model, on_bus, this);
        mcp2515_spi_attach(&model);
        cfg = {};
        cfg.bus = HAL_SPI_BUS_B0;
        cfg.cs = HAL_SPI_CS_CAN;
        cfg.osc_hz = 16000000;
        cfg.bitrate_bps = 500000;
        cfg.mode = MCP2515_MODE_NORMAL;
        cfg.filters.accept_all = 1;
        cfg.rx_cb = on_rx;
        cfg.tx_cb = on_tx;
        cfg.arg = this;
    }
    uint8_t reg(uint8_t a)
    {
        return mcp2515_model_peek(&model, a);
    }
    // Serve the INT line the way the port interrupt does: while it is low.
    void service()
    {
        for (int i = 0; i < 8 && mcp2515_model_int(&model) == 0; i++)
            ASSERT_GE(mcp2515_isr(&drv), 0);
        ASSERT_EQ(mcp2515_model_int(&model), 1) << "INT released";
    }
    static mcp2515_frame_t frame(uint32_t id, std::vector<uint8_t> data, uint8_t ext = 0,
                                 uint8_t rtr = 0)
    {
        mcp2515_frame_t f{};
        f.id = id;
        f.ext = ext;
        f.rtr = rtr;
        f.len = static_cast<uint8_t>(data.size());
        std::copy(data.begin(), data.end(), f.data);
        return f;
    }
    static mcp2515_model_frame_t wire(uint32_t id, std::vector<uint8_t> data, uint8_t ext = 0,
                                      uint8_t rtr = 0)
    {
        mcp2515_model_frame_t f{};
        f.id = id;
        f.ext = ext;
        f.rtr = rtr;
        f.dlc = static_cast<uint8_t>(data.size());
        std::copy(data.begin(), data.end(), f.data);
        return f;
    }
};

// The data sheet's bit timing (section 5): TQ = 2 (BRP + 1) / Fosc, a bit = SyncSeg (1 TQ)
// + PropSeg + PS1 + PS2, sample point at the end of PS1; CNF1 = SJW-1 (7-6), BRP (5-0); CNF2 =
// BTLMODE (7), SAM (6), PHSEG1 (5-3), PRSEG (2-0); CNF3 = PHSEG2 (2-0) (Registers 5-1 to 5-3);
// PropSeg 1-8, PS1 1-8, PS2 2-8 TQ, PropSeg + PS1 >= PS2, PS2 > SJW (section 5.3).
struct Segments {
    unsigned brp, prop, ps1, ps2, sjw;
};

static bool rules_hold(const Segments &g)
{
    return g.brp <= 63 && g.prop >= 1 && g.prop <= 8 && g.ps1 >= 1 && g.ps1 <= 8 && g.ps2 >= 2 &&
           g.ps2 <= 8 && g.prop + g.ps1 >= g.ps2 && g.ps2 > g.sjw && g.sjw >= 1 && g.sjw <= 4;
}

// Does any timing within the rules give @p rate exactly from @p osc with the sample point
// between 75 and 87.5 %?
static bool any_timing(uint32_t osc, uint32_t rate)
{
    for (unsigned brp = 0; brp <= 63; brp++)
        for (unsigned prop = 1; prop <= 8; prop++)
            for (unsigned ps1 = 1; ps1 <= 8; ps1++)
                for (unsigned ps2 = 2; ps2 <= 8; ps2++) {
                    unsigned n = 1 + prop + ps1 + ps2;
                    if (!rules_hold({brp, prop, ps1, ps2, 1}) ||
                        uint64_t(2) * (brp + 1) * n * rate != osc)
                        continue;
                    if (8 * (1 + prop + ps1) >= 6 * n && 8 * (1 + prop + ps1) <= 7 * n)
                        return true;
                }
    return false;
}

TEST(Mcp2515Timing, EveryEntryFollowsTheDataSheetFormulas)
{
    const uint32_t oscs[] = {8000000, 16000000, 20000000};
    const uint32_t rates[] = {10000, 20000, 50000, 125000, 250000, 500000, 800000, 1000000};
    std::printf("Fosc MHz  kbit/s  CNF1 CNF2 CNF3  BRP  TQ ns  N  Prop PS1 PS2 SJW  sample\n");
    unsigned supported = 0;
    for (uint32_t osc : oscs) {
        for (uint32_t rate : rates) {
            mcp2515_cnf_t c{};
            if (mcp2515_bit_timing(osc, rate, &c) != MCP2515_OK) {
                EXPECT_FALSE(any_timing(osc, rate)) << osc << " " << rate << " is possible";
                std::printf("%8u  %6u  none\n", osc / 1000000, rate / 1000);
                continue;
            }
            supported++;
            Segments g{c.cnf1 & 0x3Fu, (c.cnf2 & 7u) + 1u, ((c.cnf2 >> 3) & 7u) + 1u,
                       (c.cnf3 & 7u) + 1u, (c.cnf1 >> 6) + 1u};
            unsigned n = 1u + g.prop + g.ps1 + g.ps2;
            EXPECT_TRUE(c.cnf2 & 0x80) << "BTLMODE: PS2 from CNF3";
            EXPECT_FALSE(c.cnf2 & 0x40) << "one sample per bit";
            EXPECT_EQ(c.cnf3 & 0xC0, 0) << "SOF and WAKFIL off";
            EXPECT_TRUE(rules_hold(g)) << osc << " " << rate;
            EXPECT_EQ(g.sjw, 1u);
            // exact bit rate: Fosc / (2 (BRP + 1) N)
            EXPECT_EQ(uint64_t(2) * (g.brp + 1u) * n * rate, uint64_t(osc)) << osc << " " << rate;
            double sample = double(1u + g.prop + g.ps1) / n;
            EXPECT_GE(sample, 0.75);
            EXPECT_LE(sample, 0.875);
            std::printf("%8u  %6u  0x%02X 0x%02X 0x%02X  %3u  %5.0f %2u  %4u %3u %3u %3u  %.1f%%\n",
                        osc / 1000000, rate / 1000, c.cnf1, c.cnf2, c.cnf3, g.brp,
                        2e9 * (g.brp + 1) / osc, n, g.prop, g.ps1, g.ps2, g.sjw, 100 * sample);
        }
    }
    EXPECT_EQ(supported, 21u);
    // The brief's grid and hal/can.h's promise (every CiA 301 rate from 16 MHz) are there.
    mcp2515_cnf_t c{1, 2, 3};
    for (uint32_t osc : oscs)
        for (uint32_t rate : {125000u, 250000u, 500000u})
            EXPECT_EQ(mcp2515_bit_timing(osc, rate, &c), MCP2515_OK);
    for (uint32_t rate : rates)
        EXPECT_EQ(mcp2515_bit_timing(16000000, rate, &c), MCP2515_OK);
    c = {1, 2, 3};
    EXPECT_EQ(mcp2515_bit_timing(10000000, 500000, &c), MCP2515_ERR_ARG);
    EXPECT_EQ(mcp2515_bit_timing(16000000, 400000, &c), MCP2515_ERR_ARG);
    EXPECT_EQ(mcp2515_bit_timing(16000000, 500000, nullptr), MCP2515_ERR_ARG);
    EXPECT_EQ(c.cnf1, 1);
    EXPECT_EQ(c.cnf3, 3) << "untouched on an error";
}

// docs/can.md's bit timing table is the driver's: every row, and every pair the driver has.
TEST(Mcp2515Timing, DocsTableMatches)
{
    std::ifstream doc(CY_CAN_DOC);
    ASSERT_TRUE(doc.good()) << CY_CAN_DOC;
    std::regex row(
        R"(^\| (\d+) \| (\d+) \| 0x([0-9A-F]{2}) \| 0x([0-9A-F]{2}) \| 0x([0-9A-F]{2}) \|)");
    std::string line;
    unsigned rows = 0;
    while (std::getline(doc, line)) {
        std::smatch m;
        if (!std::regex_search(line, m, row))
            continue;
        uint32_t osc = std::stoul(m[1]) * 1000000u, rate = std::stoul(m[2]) * 1000u;
        mcp2515_cnf_t c{};
        ASSERT_EQ(mcp2515_bit_timing(osc, rate, &c), MCP2515_OK) << line;
        EXPECT_EQ(c.cnf1, std::stoul(m[3], nullptr, 16)) << line;
        EXPECT_EQ(c.cnf2, std::stoul(m[4], nullptr, 16)) << line;
        EXPECT_EQ(c.cnf3, std::stoul(m[5], nullptr, 16)) << line;
        rows++;
    }
    EXPECT_EQ(rows, 21u) << "one row per supported pair";
}

TEST_F(Mcp2515Driver, InitLeavesTheDataSheetRegisterValues)
{
    cfg.filters.accept_all = 0;
    cfg.filters.mask[0] = 0x7FF;
    cfg.filters.mask[1] = 0x7F0;
    cfg.filters.filter[0] = 0x123;
    cfg.filters.filter[2] = 0x450;
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    const mcp2515_spi_stats_t *bus = mcp2515_spi_stats();
    EXPECT_EQ(bus->mode, HAL_SPI_MODE_0) << "the MCP2515 takes modes 0,0 and 1,1";
    EXPECT_LE(bus->rate_hz, 10000000u) << "SPI clock at most 10 MHz";
    EXPECT_EQ(model.violations, 0) << "no write the data sheet forbids";
    // Normal mode (CANSTAT.OPMOD = 000), CLKOUT off (CANCTRL.CLKEN = 0).
    EXPECT_EQ(reg(CANSTAT) & 0xE0, 0x00);
    EXPECT_EQ(reg(CANCTRL), 0x00);
    // Interrupts: RX0IE, RX1IE, TX0IE-TX2IE, ERRIE, MERRE (Register 7-1), none pending.
    EXPECT_EQ(reg(CANINTE), 0x01 | 0x02 | 0x04 | 0x08 | 0x10 | 0x20 | 0x80);
    EXPECT_EQ(reg(CANINTF), 0x00);
    // Bit timing: 16 MHz, 500 kbit/s.
    unsigned brp = reg(CNF1) & 0x3F;
    unsigned n = 1u + (reg(CNF2) & 7) + 1u + ((reg(CNF2) >> 3) & 7) + 1u + (reg(CNF3) & 7) + 1u;
    EXPECT_EQ(16000000u / (2u * (brp + 1u) * n), 500000u);
    // Filters on both buffers (RXM = 00), rollover from RXB0 into RXB1 (BUKT).
    EXPECT_EQ(reg(RXB0CTRL), 0x04);
    EXPECT_EQ(reg(RXB1CTRL), 0x00);
    // RXF0 = 0x123: SIDH = SID10-3, SIDL = SID2-0 in bits 7-5, EXIDE 0 (Registers 4-10, 4-11).
    EXPECT_EQ(reg(RXF0SIDH), 0x123 >> 3);
    EXPECT_EQ(reg(RXF0SIDH + 1), (0x123 & 7) << 5);
    EXPECT_EQ(reg(0x08), 0x450 >> 3) << "RXF2";
    EXPECT_EQ(reg(RXM0SIDH), 0xFF);
    EXPECT_EQ(reg(RXM0SIDH + 1), 0xE0);
    EXPECT_EQ(reg(RXM0SIDH + 2), 0x00) << "no data-byte filtering of standard frames";
    EXPECT_EQ(reg(0x24), 0x7F0 >> 3) << "RXM1";
    EXPECT_EQ(reg(0x25), 0x00);
    EXPECT_EQ(mcp2515_state(&drv), MCP2515_ERROR_ACTIVE);
    EXPECT_EQ(mcp2515_tx_free(&drv), 3);
}

TEST_F(Mcp2515Driver, InitRefusesBadConfigurationsAndMissingParts)
{
    mcp2515_config_t bad = cfg;
    bad.rx_cb = nullptr;
    EXPECT_EQ(mcp2515_init(&drv, &bad), MCP2515_ERR_ARG);
    bad = cfg;
    bad.mode = MCP2515_MODE_COUNT;
    EXPECT_EQ(mcp2515_init(&drv, &bad), MCP2515_ERR_ARG);
    bad = cfg;
    bad.filters.filter[5] = 0x800;
    EXPECT_EQ(mcp2515_init(&drv, &bad), MCP2515_ERR_ARG);
    bad = cfg;
    bad.filters.mask[1] = 0x800;
    EXPECT_EQ(mcp2515_init(&drv, &bad), MCP2515_ERR_ARG);
    bad = cfg;
    bad.tx_fifo = 2;
    EXPECT_EQ(mcp2515_init(&drv, &bad), MCP2515_ERR_ARG);
    bad = cfg;
    bad.manual_recovery = 2;
    EXPECT_EQ(mcp2515_init(&drv, &bad), MCP2515_ERR_ARG);
    bad = cfg;
    bad.osc_hz = 12000000;
    EXPECT_EQ(mcp2515_init(&drv, &bad), MCP2515_ERR_ARG);
    bad = cfg;
    bad.bitrate_bps = 400000;
    EXPECT_EQ(mcp2515_init(&drv, &bad), MCP2515_ERR_ARG);
    EXPECT_EQ(mcp2515_init(nullptr, &cfg), MCP2515_ERR_ARG);
    EXPECT_EQ(mcp2515_init(&drv, nullptr), MCP2515_ERR_ARG);
    EXPECT_EQ(mcp2515_spi_stats()->frames, 0u) << "nothing on the bus for bad arguments";
    // No part on the bus: SO floats high (0xFF), CANSTAT never reads configuration mode.
    mcp2515_spi_attach(nullptr);
    EXPECT_EQ(mcp2515_init(&drv, &cfg), MCP2515_ERR_DEVICE);
    auto f = frame(1, {});
    EXPECT_EQ(mcp2515_send(&drv, &f), MCP2515_ERR_DEVICE);
    EXPECT_EQ(mcp2515_isr(&drv), MCP2515_ERR_DEVICE);
    EXPECT_EQ(mcp2515_poll(&drv), MCP2515_ERR_DEVICE);
    EXPECT_EQ(mcp2515_set_mode(&drv, MCP2515_MODE_LOOPBACK), MCP2515_ERR_DEVICE);
    EXPECT_EQ(mcp2515_tx_free(&drv), 0);
    EXPECT_EQ(mcp2515_state(&drv), MCP2515_BUS_OFF);
    // A bad bus: hal/spi.h refuses the bus number.
    mcp2515_spi_attach(&model);
    bad = cfg;
    bad.bus = HAL_SPI_BUS_COUNT;
    EXPECT_EQ(mcp2515_init(&drv, &bad), MCP2515_ERR_SPI);
}

TEST_F(Mcp2515Driver, SendsStandardExtendedAndRemoteFrames)
{
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    auto a = frame(0x7FF, {1, 2, 3, 4, 5, 6, 7, 8});
    auto b = frame(0x1ABCDEF5, {0xEE}, 1);
    auto c = frame(0x0, {}, 0, 1);
    c.len = 4; // a remote frame asks for 4 bytes
    for (auto *f : {&a, &b, &c}) {
        ASSERT_EQ(mcp2515_send(&drv, f), MCP2515_OK);
        ASSERT_GE(mcp2515_model_bus_tick(&model), 0);
        service();
    }
    ASSERT_EQ(on_wire.size(), 3u);
    EXPECT_EQ(on_wire[0].id, 0x7FFu);
    EXPECT_EQ(on_wire[0].ext, 0);
    EXPECT_EQ(on_wire[0].dlc, 8);
    EXPECT_EQ(on_wire[0].data[7], 8);
    EXPECT_EQ(on_wire[1].id, 0x1ABCDEF5u);
    EXPECT_EQ(on_wire[1].ext, 1);
    EXPECT_EQ(on_wire[1].dlc, 1);
    EXPECT_EQ(on_wire[1].data[0], 0xEE);
    EXPECT_EQ(on_wire[2].rtr, 1);
    EXPECT_EQ(on_wire[2].dlc, 4);
    EXPECT_EQ(mcp2515_stats(&drv)->tx_frames, 3);
    EXPECT_EQ(tx_free_calls, 3u);
    EXPECT_EQ(model.violations, 0);
}

TEST_F(Mcp2515Driver, ThreeBuffersGoInIdentifierOrder)
{
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    // Every order of three identifiers (one twice: sent first goes first).
    std::vector<uint32_t> ids = {0x300, 0x100, 0x200};
    std::sort(ids.begin(), ids.end());
    do {
        on_wire.clear();
        for (uint32_t id : ids) {
            auto f = frame(id, {static_cast<uint8_t>(id >> 8)});
            ASSERT_EQ(mcp2515_send(&drv, &f), MCP2515_OK);
        }
        EXPECT_EQ(mcp2515_tx_free(&drv), 0);
        auto extra = frame(0x001, {});
        EXPECT_EQ(mcp2515_send(&drv, &extra), MCP2515_ERR_FULL);
        for (int i = 0; i < 3; i++)
            ASSERT_GE(mcp2515_model_bus_tick(&model), 0);
        service();
        ASSERT_EQ(on_wire.size(), 3u);
        EXPECT_EQ(on_wire[0].id, 0x100u);
        EXPECT_EQ(on_wire[1].id, 0x200u);
        EXPECT_EQ(on_wire[2].id, 0x300u);
        EXPECT_EQ(mcp2515_tx_free(&drv), 3);
    } while (std::next_permutation(ids.begin(), ids.end()));
    on_wire.clear();
    for (uint8_t k = 0; k < 3; k++) {
        auto f = frame(0x123, {k});
        ASSERT_EQ(mcp2515_send(&drv, &f), MCP2515_OK);
    }
    for (int i = 0; i < 3; i++)
        mcp2515_model_bus_tick(&model);
    service();
    ASSERT_EQ(on_wire.size(), 3u);
    for (uint8_t k = 0; k < 3; k++)
        EXPECT_EQ(on_wire[k].data[0], k) << "equal identifiers in the order sent";
    EXPECT_EQ(model.violations, 0);
}

TEST_F(Mcp2515Driver, UrgentFrameOvertakesAPendingOneThatKeepsLosing)
{
    // Priority inversion: 0x400 waits (it loses arbitration twice); 0x050 sent meanwhile must
    // leave before it although 0x400 sits in the lower buffer with the earlier request.
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    answers = {MCP2515_MODEL_TX_LOST, MCP2515_MODEL_TX_LOST};
    auto slow = frame(0x400, {1});
    ASSERT_EQ(mcp2515_send(&drv, &slow), MCP2515_OK);
    mcp2515_model_bus_tick(&model);
    mcp2515_model_bus_tick(&model);
    auto urgent = frame(0x050, {2});
    ASSERT_EQ(mcp2515_send(&drv, &urgent), MCP2515_OK);
    auto ext = frame(0x00000001, {3}, 1); // extended: base id 0 beats 0x050
    ASSERT_EQ(mcp2515_send(&drv, &ext), MCP2515_OK);
    while (mcp2515_model_bus_tick(&model) >= 0)
        ;
    service();
    std::vector<uint32_t> order;
    for (auto &f : on_wire)
        order.push_back(f.id);
    EXPECT_EQ(order, (std::vector<uint32_t>{0x400, 0x400, 0x00000001, 0x050, 0x400}));
}

TEST_F(Mcp2515Driver, ReceivesThroughFiltersIntoBothBuffers)
{
    cfg.filters.accept_all = 0;
    cfg.filters.mask[0] = 0x7FF;
    cfg.filters.filter[0] = 0x100;
    cfg.filters.filter[1] = 0x101;
    cfg.filters.mask[1] = 0x7F0;
    for (int i = 2; i < 6; i++)
        cfg.filters.filter[i] = 0x230;
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    struct {
        uint32_t id;
        uint8_t ext;
        bool taken;
    } cases[] = {{0x100, 0, true},  {0x101, 0, true},  {0x102, 0, false},
                 {0x230, 0, true},  {0x23F, 0, true},  {0x240, 0, false},
                 {0x100, 1, false}, {0x7FF, 0, false}, {0x000, 0, false}};
    for (const auto &c : cases) {
        received.clear();
        auto w = wire(c.id, {0x11, 0x22, 0x33}, c.ext);
        mcp2515_model_receive(&model, &w);
        service();
        if (!c.taken) {
            EXPECT_TRUE(received.empty()) << std::hex << c.id;
            continue;
        }
        ASSERT_EQ(received.size(), 1u) << std::hex << c.id;
        EXPECT_EQ(received[0].id, c.id);
        EXPECT_EQ(received[0].len, 3);
        EXPECT_EQ(received[0].data[2], 0x33);
    }
}

TEST_F(Mcp2515Driver, AcceptAllTakesExtendedAndRemoteFrames)
{
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    auto e = wire(0x1FFFFFFF, {9, 8, 7, 6, 5, 4, 3, 2}, 1);
    auto r = wire(0x555, {}, 0, 1);
    r.dlc = 2;
    auto long_dlc = wire(0x10, {1, 2, 3, 4, 5, 6, 7, 8});
    long_dlc.dlc = 15;
    for (auto *w : {&e, &r, &long_dlc}) {
        mcp2515_model_receive(&model, w);
        service();
    }
    ASSERT_EQ(received.size(), 3u);
    EXPECT_EQ(received[0].id, 0x1FFFFFFFu);
    EXPECT_EQ(received[0].ext, 1);
    EXPECT_EQ(received[0].data[7], 2);
    EXPECT_EQ(received[1].id, 0x555u);
    EXPECT_EQ(received[1].rtr, 1);
    EXPECT_EQ(received[1].len, 2);
    EXPECT_EQ(received[2].len, 8) << "DLC 15 carries 8 bytes";
    EXPECT_EQ(mcp2515_stats(&drv)->rx_frames, 3);
}

TEST_F(Mcp2515Driver, OverflowIsCountedAndCleared)
{
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    // Three frames while nobody serves INT: RXB0, RXB1 (rollover), the third is lost.
    for (uint8_t k = 0; k < 3; k++) {
        auto w = wire(0x200 + k, {k});
        mcp2515_model_receive(&model, &w);
    }
    EXPECT_EQ(reg(EFLG) & 0xC0, 0x80) << "RX1OVR";
    service();
    ASSERT_EQ(received.size(), 2u);
    EXPECT_EQ(received[0].id, 0x200u) << "RXB0 (the older) first";
    EXPECT_EQ(received[1].id, 0x201u);
    EXPECT_EQ(mcp2515_stats(&drv)->rx_overflows, 1);
    EXPECT_EQ(reg(EFLG) & 0xC0, 0x00) << "overflow flags cleared";
    EXPECT_EQ(reg(CANINTF), 0x00);
}

TEST_F(Mcp2515Driver, HandlerServesAFloodInBoundedPasses)
{
    // A frame arrives each time one is read: the handler stops after 4 passes with the line
    // still low and says so; the next call goes on.
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    flood = wire(0x42, {1});
    flood_left = 10;
    mcp2515_model_receive(&model, &flood);
    EXPECT_EQ(mcp2515_isr(&drv), 1);
    EXPECT_EQ(received.size(), 4u);
    EXPECT_EQ(mcp2515_model_int(&model), 0);
    service();
    EXPECT_EQ(received.size(), 11u);
}

TEST_F(Mcp2515Driver, SpiTrafficOfOneReceivedFrame)
{
    // docs/can.md: READ CANINTF..EFLG (4) + READ RX BUFFER (1 + 5 + 8) + the final READ (4).
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    auto w = wire(0x123, {1, 2, 3, 4, 5, 6, 7, 8});
    mcp2515_model_receive(&model, &w);
    uint32_t before = mcp2515_spi_stats()->bytes;
    EXPECT_EQ(mcp2515_isr(&drv), 0);
    EXPECT_EQ(mcp2515_spi_stats()->bytes - before, 22u);
}

TEST_F(Mcp2515Driver, ErrorStatesUpToBusOffAndRecovery)
{
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    auto f = frame(0x321, {0xAB});
    ASSERT_EQ(mcp2515_send(&drv, &f), MCP2515_OK);
    auto g = frame(0x322, {0xCD});
    ASSERT_EQ(mcp2515_send(&drv, &g), MCP2515_OK);
    answers.assign(40, MCP2515_MODEL_TX_ERROR);
    uint8_t tec = 0, rec = 0;
    for (int i = 1; i <= 16; i++) {
        mcp2515_model_bus_tick(&model);
        service();
        mcp2515_error_counters(&drv, &tec, &rec);
        if (i < 16) {
            EXPECT_EQ(mcp2515_state(&drv), MCP2515_ERROR_ACTIVE) << i;
        }
    }
    EXPECT_EQ(mcp2515_state(&drv), MCP2515_ERROR_PASSIVE);
    EXPECT_EQ(tec, 128);
    EXPECT_EQ(mcp2515_stats(&drv)->tx_errors, 16);
    EXPECT_EQ(mcp2515_stats(&drv)->rx_errors, 0);
    EXPECT_EQ(mcp2515_stats(&drv)->error_passive, 1);
    EXPECT_EQ(mcp2515_recovering(&drv), 0);
    for (int i = 17; i <= 32; i++) {
        mcp2515_model_bus_tick(&model);
        service();
    }
    EXPECT_EQ(mcp2515_state(&drv), MCP2515_BUS_OFF);
    EXPECT_EQ(mcp2515_stats(&drv)->bus_offs, 1);
    EXPECT_EQ(mcp2515_stats(&drv)->tx_aborted, 2) << "both pending frames aborted";
    EXPECT_EQ(mcp2515_recovering(&drv), 1) << "counting its way back by itself";
    EXPECT_EQ(reg(TXB0CTRL) & 0x08, 0) << "TXREQ cleared by ABAT";
    EXPECT_EQ(reg(TXB0CTRL + 0x10) & 0x08, 0);
    EXPECT_EQ(reg(CANCTRL) & 0x10, 0x10) << "ABAT held while bus-off";
    EXPECT_EQ(mcp2515_tx_free(&drv), 0);
    EXPECT_EQ(mcp2515_send(&drv, &f), MCP2515_ERR_BUS_OFF);
    mcp2515_model_idle(&model, 127);
    EXPECT_EQ(mcp2515_send(&drv, &f), MCP2515_ERR_BUS_OFF) << "127 x 11 recessive bits";
    // Recovery: the part recovers by itself; the driver notices at its next send (or through
    // ERRIF, or mcp2515_poll) and sending resumes with ABAT released.
    mcp2515_model_idle(&model, 1);
    on_wire.clear();
    answers.clear();
    ASSERT_EQ(mcp2515_send(&drv, &f), MCP2515_OK);
    EXPECT_EQ(mcp2515_state(&drv), MCP2515_ERROR_ACTIVE);
    mcp2515_error_counters(&drv, &tec, &rec);
    EXPECT_EQ(tec, 0);
    EXPECT_EQ(reg(CANCTRL) & 0x10, 0x00);
    EXPECT_EQ(mcp2515_stats(&drv)->recoveries, 1);
    EXPECT_EQ(mcp2515_recovering(&drv), 0);
    EXPECT_EQ(mcp2515_recover(&drv), MCP2515_ERR_STATE) << "not bus-off";
    ASSERT_EQ(mcp2515_model_bus_tick(&model), 0);
    ASSERT_EQ(on_wire.size(), 1u);
    EXPECT_EQ(on_wire[0].id, 0x321u);
    service();
    EXPECT_EQ(model.violations, 0);
}

TEST_F(Mcp2515Driver, RecoveryThroughTheErrorInterruptAndPoll)
{
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    auto f = frame(0x10, {});
    ASSERT_EQ(mcp2515_send(&drv, &f), MCP2515_OK);
    answers.assign(32, MCP2515_MODEL_TX_ERROR);
    for (int i = 0; i < 32; i++)
        mcp2515_model_bus_tick(&model);
    ASSERT_EQ(mcp2515_poll(&drv), MCP2515_OK);
    EXPECT_EQ(mcp2515_state(&drv), MCP2515_BUS_OFF);
    service();
    mcp2515_model_idle(&model, 128);
    EXPECT_EQ(mcp2515_model_int(&model), 0) << "ERRIF: the error state changed";
    service();
    EXPECT_EQ(mcp2515_state(&drv), MCP2515_ERROR_ACTIVE);
    EXPECT_EQ(mcp2515_tx_free(&drv), 3);
}

TEST_F(Mcp2515Driver, ManualRecoveryWaitsForTheRequest)
{
    cfg.manual_recovery = 1;
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    auto f = frame(0x10, {});
    ASSERT_EQ(mcp2515_send(&drv, &f), MCP2515_OK);
    answers.assign(32, MCP2515_MODEL_TX_ERROR);
    for (int i = 0; i < 32; i++)
        mcp2515_model_bus_tick(&model);
    service();
    EXPECT_EQ(mcp2515_state(&drv), MCP2515_BUS_OFF);
    EXPECT_EQ(reg(CANSTAT) & 0xE0, 0x80) << "held in configuration mode";
    EXPECT_EQ(mcp2515_recovering(&drv), 0);
    mcp2515_model_idle(&model, 500);
    ASSERT_EQ(mcp2515_poll(&drv), MCP2515_OK);
    EXPECT_EQ(mcp2515_state(&drv), MCP2515_BUS_OFF) << "no way back without the request";
    ASSERT_EQ(mcp2515_recover(&drv), MCP2515_OK);
    EXPECT_EQ(reg(CANSTAT) & 0xE0, 0x00) << "normal mode again";
    EXPECT_EQ(mcp2515_recovering(&drv), 1);
    EXPECT_EQ(mcp2515_send(&drv, &f), MCP2515_ERR_BUS_OFF);
    mcp2515_model_idle(&model, 127);
    service();
    EXPECT_EQ(mcp2515_state(&drv), MCP2515_BUS_OFF);
    mcp2515_model_idle(&model, 1);
    service();
    EXPECT_EQ(mcp2515_state(&drv), MCP2515_ERROR_ACTIVE);
    EXPECT_EQ(mcp2515_stats(&drv)->recoveries, 1);
    EXPECT_EQ(mcp2515_send(&drv, &f), MCP2515_OK);
    EXPECT_EQ(model.violations, 0);
}

TEST_F(Mcp2515Driver, FifoOrderWhenAsked)
{
    cfg.tx_fifo = 1;
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    // Sent 0x300, 0x100, 0x200: they leave in that order, also after the first one is gone
    // and a fourth joins (its buffer's priority ranks behind the two still pending).
    for (uint32_t id : {0x300u, 0x100u, 0x200u}) {
        auto f = frame(id, {});
        ASSERT_EQ(mcp2515_send(&drv, &f), MCP2515_OK);
    }
    ASSERT_GE(mcp2515_model_bus_tick(&model), 0);
    service();
    auto g = frame(0x001, {});
    ASSERT_EQ(mcp2515_send(&drv, &g), MCP2515_OK);
    while (mcp2515_model_bus_tick(&model) >= 0)
        ;
    service();
    std::vector<uint32_t> order;
    for (auto &w : on_wire)
        order.push_back(w.id);
    EXPECT_EQ(order, (std::vector<uint32_t>{0x300, 0x100, 0x200, 0x001}));
}

TEST_F(Mcp2515Driver, TransmitAndReceiveErrorsAreTold)
{
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    for (int i = 0; i < 5; i++)
        mcp2515_model_rx_error(&model);
    service();
    auto f = frame(0x10, {});
    ASSERT_EQ(mcp2515_send(&drv, &f), MCP2515_OK);
    answers = {MCP2515_MODEL_TX_NO_ACK, MCP2515_MODEL_TX_ERROR};
    mcp2515_model_bus_tick(&model);
    service();
    mcp2515_model_bus_tick(&model);
    service();
    mcp2515_model_bus_tick(&model);
    service();
    EXPECT_EQ(mcp2515_stats(&drv)->rx_errors, 5);
    EXPECT_EQ(mcp2515_stats(&drv)->tx_errors, 2);
    EXPECT_EQ(mcp2515_stats(&drv)->tx_frames, 1u);
}

TEST_F(Mcp2515Driver, ReceiveErrorsMakeItErrorPassive)
{
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    for (int i = 0; i < 128; i++)
        mcp2515_model_rx_error(&model);
    service();
    uint8_t tec = 1, rec = 0;
    mcp2515_error_counters(&drv, &tec, &rec);
    EXPECT_EQ(rec, 128);
    EXPECT_EQ(tec, 0);
    EXPECT_EQ(mcp2515_state(&drv), MCP2515_ERROR_PASSIVE);
    auto w = wire(0x1, {});
    mcp2515_model_receive(&model, &w);
    service();
    EXPECT_EQ(mcp2515_state(&drv), MCP2515_ERROR_ACTIVE);
}

TEST_F(Mcp2515Driver, LoopbackSelfTestAndListenOnly)
{
    cfg.mode = MCP2515_MODE_LOOPBACK;
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    EXPECT_EQ(reg(CANSTAT) & 0xE0, 0x40);
    auto f = frame(0x2AA, {0xDE, 0xAD, 0xBE, 0xEF});
    ASSERT_EQ(mcp2515_send(&drv, &f), MCP2515_OK);
    ASSERT_EQ(mcp2515_model_bus_tick(&model), 0);
    service();
    EXPECT_TRUE(on_wire.empty()) << "loopback does not drive the bus";
    ASSERT_EQ(received.size(), 1u);
    EXPECT_EQ(received[0].id, 0x2AAu);
    EXPECT_EQ(received[0].len, 4);
    EXPECT_EQ(received[0].data[3], 0xEF);
    ASSERT_EQ(mcp2515_set_mode(&drv, MCP2515_MODE_LISTEN), MCP2515_OK);
    EXPECT_EQ(reg(CANSTAT) & 0xE0, 0x60);
    EXPECT_EQ(mcp2515_send(&drv, &f), MCP2515_ERR_MODE);
    ASSERT_EQ(mcp2515_set_mode(&drv, MCP2515_MODE_NORMAL), MCP2515_OK);
    EXPECT_EQ(reg(CANSTAT) & 0xE0, 0x00);
    EXPECT_EQ(mcp2515_set_mode(&drv, MCP2515_MODE_COUNT), MCP2515_ERR_ARG);
}

TEST_F(Mcp2515Driver, SendRefusesBadFramesWithoutTouchingTheBus)
{
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    uint32_t before = mcp2515_spi_stats()->bytes;
    auto too_big_std = frame(0x800, {});
    auto too_big_ext = frame(0x20000000, {}, 1);
    auto too_long = frame(0x1, {});
    too_long.len = 9;
    auto bad_ext = frame(0x1, {});
    bad_ext.ext = 2;
    auto bad_rtr = frame(0x1, {});
    bad_rtr.rtr = 7;
    for (auto *f : {&too_big_std, &too_big_ext, &too_long, &bad_ext, &bad_rtr})
        EXPECT_EQ(mcp2515_send(&drv, f), MCP2515_ERR_ARG);
    EXPECT_EQ(mcp2515_send(&drv, nullptr), MCP2515_ERR_ARG);
    EXPECT_EQ(mcp2515_send(nullptr, &too_long), MCP2515_ERR_ARG);
    EXPECT_EQ(mcp2515_spi_stats()->bytes, before);
    EXPECT_EQ(mcp2515_tx_free(&drv), 3);
    EXPECT_EQ(mcp2515_isr(nullptr), MCP2515_ERR_DEVICE);
    EXPECT_EQ(mcp2515_stats(nullptr), nullptr);
}

TEST_F(Mcp2515Driver, SpiErrorsAreReported)
{
    ASSERT_EQ(mcp2515_init(&drv, &cfg), MCP2515_OK);
    mcp2515_spi_attach(&model); // the bus forgets its set-up: transfers are refused
    auto f = frame(0x1, {});
    EXPECT_EQ(mcp2515_send(&drv, &f), MCP2515_ERR_SPI);
    EXPECT_EQ(mcp2515_isr(&drv), MCP2515_ERR_SPI);
    EXPECT_EQ(mcp2515_poll(&drv), MCP2515_ERR_SPI);
}

} // namespace
