// The MCP2515 register model (tests/support/mcp2515_model.c) against the data sheet
// (DS20001801): each expected value below is typed from the data sheet's instruction set
// (Table 12-1 and Figures 12-1 to 12-9), register map (Table 11-1), register descriptions and
// behaviour (sections 3-7, 10), not from the model.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

extern "C" {
#include "mcp2515_model.h"
}

namespace
{

// DS20001801 Table 11-1
constexpr uint8_t RXF0SIDH = 0x00, RXF1SIDH = 0x04, RXF2SIDH = 0x08, BFPCTRL = 0x0C,
                  TXRTSCTRL = 0x0D, CANSTAT = 0x0E, CANCTRL = 0x0F, TEC = 0x1C, REC = 0x1D,
                  RXM0SIDH = 0x20, RXM1SIDH = 0x24, CNF3 = 0x28, CNF2 = 0x29, CNF1 = 0x2A,
                  CANINTE = 0x2B, CANINTF = 0x2C, EFLG = 0x2D, TXB0CTRL = 0x30, TXB1CTRL = 0x40,
                  TXB2CTRL = 0x50, RXB0CTRL = 0x60, RXB1CTRL = 0x70;

struct Mcp2515Model : ::testing::Test {
    mcp2515_model_t m;
    std::vector<mcp2515_model_frame_t> sent;
    mcp2515_model_tx_t answer = MCP2515_MODEL_TX_ACK;

    static mcp2515_model_tx_t on_bus(void *arg, const mcp2515_model_frame_t *f)
    {
        auto *self = static_cast<Mcp2515Model *>(arg);
        self->sent.push_back(*f);
        return self->answer;
    }

    void SetUp() override
    {
        mcp2515_model_init(&m, on_bus, this);
    }

    // One SPI frame: /CS low, the bytes, /CS high; returns the bytes clocked out.
    std::vector<uint8_t> spi(std::vector<uint8_t> out)
    {
        std::vector<uint8_t> in;
        mcp2515_model_select(&m);
        for (uint8_t b : out)
            in.push_back(mcp2515_model_exchange(&m, b));
        mcp2515_model_deselect(&m);
        return in;
    }
    uint8_t read(uint8_t a)
    {
        return spi({0x03, a, 0x00})[2];
    }
    void write(uint8_t a, std::vector<uint8_t> v)
    {
        v.insert(v.begin(), {0x02, a});
        spi(v);
    }
    void modify(uint8_t a, uint8_t mask, uint8_t data)
    {
        spi({0x05, a, mask, data});
    }
    void mode(uint8_t reqop)
    {
        modify(CANCTRL, 0xE0, reqop);
    }
    mcp2515_model_frame_t frame(uint32_t id, std::vector<uint8_t> data, uint8_t ext = 0,
                                uint8_t rtr = 0)
    {
        mcp2515_model_frame_t f{};
        f.id = id;
        f.ext = ext;
        f.rtr = rtr;
        f.dlc = static_cast<uint8_t>(data.size());
        for (size_t i = 0; i < data.size(); i++)
            f.data[i] = data[i];
        return f;
    }
    // A standard identifier as SIDH, SIDL (Register 4-4/4-5 layout, EXIDE 0).
    static std::vector<uint8_t> std_regs(uint16_t id)
    {
        return std_regs_data(id, 0, 0);
    }
    // ... with the extended bits EID15-8, EID7-0 (for standard frames: data bytes 0, 1).
    static std::vector<uint8_t> std_regs_data(uint16_t id, uint8_t d0, uint8_t d1)
    {
        return {static_cast<uint8_t>(id >> 3), static_cast<uint8_t>((id & 7) << 5), d0, d1};
    }
};

TEST_F(Mcp2515Model, PowerOnRegisterValues)
{
    // Register 10-1: CANCTRL POR 1000 0111 (configuration, CLKEN, CLKPRE = 11); 10-2: CANSTAT
    // 100x 000x with OPMOD = configuration, no interrupt.
    EXPECT_EQ(read(CANCTRL), 0x87);
    EXPECT_EQ(read(CANSTAT), 0x80);
    for (uint8_t a : {CANINTE, CANINTF, EFLG, TEC, REC, TXB0CTRL, TXB1CTRL, TXB2CTRL, RXB0CTRL,
                      RXB1CTRL, CNF1, CNF2, CNF3})
        EXPECT_EQ(read(a), 0x00) << "address " << int(a);
    // CANSTAT and CANCTRL answer at every xEh / xFh address (Table 11-1).
    for (uint8_t row = 0; row < 8; row++) {
        EXPECT_EQ(read(static_cast<uint8_t>(row * 16 + 0x0E)), 0x80);
        EXPECT_EQ(read(static_cast<uint8_t>(row * 16 + 0x0F)), 0x87);
    }
    EXPECT_EQ(mcp2515_model_int(&m), 1) << "INT idles high";
}

TEST_F(Mcp2515Model, ReadAndWriteAutoIncrementAndUnimplementedBits)
{
    // Figure 12-2/12-4: the address pointer moves on after each data byte.
    write(CNF3, {0xFF, 0xA5, 0x3C});
    auto in = spi({0x03, CNF3, 0, 0, 0});
    EXPECT_EQ(in[0], 0xFF) << "SO is not driven during the instruction";
    EXPECT_EQ(in[1], 0xFF) << "nor during the address";
    EXPECT_EQ(in[2], 0xC7) << "CNF3 bits 5-3 are unimplemented (Register 5-3)";
    EXPECT_EQ(in[3], 0xA5);
    EXPECT_EQ(in[4], 0x3C);
    // Read-only registers: TEC, REC (Registers 6-1, 6-2); EFLG only RX1OVR/RX0OVR (6-3).
    write(TEC, {0x55, 0x66});
    EXPECT_EQ(read(TEC), 0x00);
    EXPECT_EQ(read(REC), 0x00);
    write(EFLG, {0xFF});
    EXPECT_EQ(read(EFLG), 0xC0);
    // TXBnSIDL bits 4 and 2, TXBnDLC bits 7, 5, 4 unimplemented (Registers 3-4, 3-7).
    write(0x32, {0xFF, 0x12, 0x34, 0xFF});
    EXPECT_EQ(read(0x32), 0xEB);
    EXPECT_EQ(read(0x35), 0x4F);
    // RXBnCTRL: RXB0 writes RXM and BUKT only, RXB1 RXM only (Registers 4-1, 4-2).
    write(RXB0CTRL, {0xFF});
    EXPECT_EQ(read(RXB0CTRL), 0x64);
    write(RXB1CTRL, {0xFF});
    EXPECT_EQ(read(RXB1CTRL), 0x60);
    EXPECT_EQ(m.violations, 0);
}

TEST_F(Mcp2515Model, ConfigurationRegistersOnlyInConfigurationMode)
{
    // Sections 4.5.5 and 5.5: masks, filters and CNF1-3 only in configuration mode.
    mode(0x00);
    EXPECT_EQ(read(CANSTAT) & 0xE0, 0x00) << "normal mode";
    write(CNF1, {0x41});
    write(RXF0SIDH, {0x12});
    write(RXM0SIDH, {0x34});
    write(TXRTSCTRL, {0x07});
    EXPECT_EQ(read(CNF1), 0x00);
    EXPECT_EQ(read(RXF0SIDH), 0x00);
    EXPECT_EQ(read(RXM0SIDH), 0x00);
    EXPECT_EQ(read(TXRTSCTRL), 0x00);
    EXPECT_EQ(m.violations, 4);
    mode(0x80);
    write(CNF1, {0x41});
    EXPECT_EQ(read(CNF1), 0x41);
    EXPECT_EQ(m.violations, 4);
}

TEST_F(Mcp2515Model, BitModifyAsFigure12_1)
{
    // Figure 12-1: mask 0011 0101, data xx10 x0x1, previous 0101 0001 -> 0110 0001.
    write(CANINTE, {0x51});
    modify(CANINTE, 0x35, 0xEB);
    EXPECT_EQ(read(CANINTE), 0x61);
    modify(CANINTE, 0x35, 0x00);
    EXPECT_EQ(read(CANINTE), 0x40);
    // Not bit-modifiable (a filter register): the mask is forced to FFh (Table 12-1 note).
    write(RXF1SIDH, {0xF0});
    modify(RXF1SIDH, 0x01, 0x0F);
    EXPECT_EQ(read(RXF1SIDH), 0x0F);
    // BFPCTRL is bit-modifiable (bits 5-0 implemented).
    modify(BFPCTRL, 0x05, 0xFF);
    EXPECT_EQ(read(BFPCTRL), 0x05);
}

TEST_F(Mcp2515Model, ReadStatusAndRxStatusLayouts)
{
    // Figure 12-8: bit 0 RX0IF, 1 RX1IF, 2 TXB0 TXREQ, 3 TX0IF, 4 TXB1 TXREQ, 5 TX1IF,
    // 6 TXB2 TXREQ, 7 TX2IF; the byte repeats while clocked.
    write(CANINTF, {0x01 | 0x10}); // RX0IF, TX2IF
    spi({0x82});                   // RTS TXB1
    auto in = spi({0xA0, 0, 0, 0});
    EXPECT_EQ(in[1], 0x01 | 0x10 | 0x80);
    EXPECT_EQ(in[2], in[1]);
    EXPECT_EQ(in[3], in[1]);
    // Figure 12-9 with no message: 0.
    write(CANINTF, {0x00});
    EXPECT_EQ(spi({0xB0, 0})[1], 0x00);
    // An extended remote frame in RXB0 (filters off): bits 7-6 = 01, bit 4 extended, bit 3
    // remote, filter bits RXF0.
    mode(0x00);
    write(RXB0CTRL, {0x60});
    auto f = frame(0x1234567, {}, 1, 1);
    ASSERT_EQ(mcp2515_model_receive(&m, &f), MCP2515_MODEL_RX_BUF0);
    EXPECT_EQ(spi({0xB0, 0, 0})[1], 0x40 | 0x10 | 0x08);
    EXPECT_EQ(spi({0xB0, 0, 0})[2], 0x40 | 0x10 | 0x08) << "repeats while clocked";
}

TEST_F(Mcp2515Model, ResetInstructionRestoresPowerOnState)
{
    write(CNF1, {0x03});
    write(CANINTE, {0xFF});
    mode(0x40);
    mcp2515_model_select(&m);
    mcp2515_model_exchange(&m, 0xC0);
    EXPECT_EQ(mcp2515_model_peek(&m, CNF1), 0x03) << "RESET acts when /CS rises";
    mcp2515_model_deselect(&m);
    EXPECT_EQ(read(CNF1), 0x00);
    EXPECT_EQ(read(CANINTE), 0x00);
    EXPECT_EQ(read(CANCTRL), 0x87);
    EXPECT_EQ(read(CANSTAT), 0x80);
}

TEST_F(Mcp2515Model, LoadTxBufferStartAddresses)
{
    // Table 12-1 / Figure 12-5: 0100 0abc starts at TXB0SIDH, TXB0D0, TXB1SIDH, TXB1D0,
    // TXB2SIDH, TXB2D0.
    const uint8_t start[6] = {0x31, 0x36, 0x41, 0x46, 0x51, 0x56};
    for (uint8_t abc = 0; abc < 6; abc++) {
        spi({static_cast<uint8_t>(0x40 | abc), static_cast<uint8_t>(0x10 + abc),
             static_cast<uint8_t>(0x20 + abc)});
        EXPECT_EQ(read(start[abc]), 0x10 + abc) << "abc " << int(abc);
    }
    // The second byte lands on the next register: TXBnSIDL (unimplemented bits 4 and 2 read
    // 0) after a SIDH start, TXBnD1 after a D0 start.
    EXPECT_EQ(read(0x32), 0x20 & 0xEB);
    EXPECT_EQ(read(0x37), 0x21);
    EXPECT_EQ(read(0x52), 0x24 & 0xEB);
    EXPECT_EQ(read(0x57), 0x25);
}

TEST_F(Mcp2515Model, ReadRxBufferStartAddressesAndFlagClear)
{
    // RXB0 with filters off and rollover, normal mode: the first frame into RXB0, the second
    // rolls over into RXB1 (section 4.2).
    mode(0x00);
    write(RXB0CTRL, {0x60 | 0x04});
    auto a = frame(0x123, {1, 2, 3, 4, 5, 6, 7, 8});
    auto b = frame(0x456, {9, 10});
    ASSERT_EQ(mcp2515_model_receive(&m, &a), MCP2515_MODEL_RX_BUF0);
    ASSERT_EQ(mcp2515_model_receive(&m, &b), MCP2515_MODEL_RX_BUF1);
    EXPECT_EQ(read(CANINTF) & 0x03, 0x03);
    // 1001 0nm0: nm = 00 RXB0SIDH, 01 RXB0D0, 10 RXB1SIDH, 11 RXB1D0 (Figure 12-3).
    auto in = spi({0x92, 0, 0});
    EXPECT_EQ(in[1], 1);
    EXPECT_EQ(in[2], 2);
    EXPECT_EQ(read(CANINTF) & 0x01, 0x00) << "RX0IF cleared as /CS rose";
    EXPECT_EQ(read(CANINTF) & 0x02, 0x02);
    mcp2515_model_select(&m);
    mcp2515_model_exchange(&m, 0x94);
    EXPECT_EQ(mcp2515_model_exchange(&m, 0), 0x456 >> 3);
    EXPECT_EQ(mcp2515_model_exchange(&m, 0), (0x456 & 7) << 5);
    EXPECT_EQ(mcp2515_model_peek(&m, CANINTF) & 0x02, 0x02) << "not before /CS rises";
    mcp2515_model_deselect(&m);
    EXPECT_EQ(read(CANINTF) & 0x02, 0x00);
    in = spi({0x96, 0, 0});
    EXPECT_EQ(in[1], 9);
    EXPECT_EQ(in[2], 10);
    // RXB1CTRL FILHIT = 000: RXF0 rolled over from RXB0 (section 4.5.3).
    EXPECT_EQ(read(RXB1CTRL) & 0x07, 0x00);
}

TEST_F(Mcp2515Model, OverflowWithoutRollover)
{
    // Figure 4-2: a frame for RXB0 while RX0IF is set and BUKT clear is lost (RX0OVR), even if
    // RXB1's filters would take it; ERRIF follows (section 7.6.1).
    mode(0x00);
    write(RXB0CTRL, {0x60});
    write(RXB1CTRL, {0x60});
    write(CANINTE, {0x20});
    auto a = frame(0x10, {1});
    ASSERT_EQ(mcp2515_model_receive(&m, &a), MCP2515_MODEL_RX_BUF0);
    EXPECT_EQ(mcp2515_model_int(&m), 1) << "RX0IE is off: the flag is set, INT stays high";
    EXPECT_EQ(read(CANINTF), 0x01);
    ASSERT_EQ(mcp2515_model_receive(&m, &a), MCP2515_MODEL_RX_OVERFLOW);
    EXPECT_EQ(read(EFLG), 0x40);
    EXPECT_EQ(read(CANINTF), 0x21);
    EXPECT_EQ(mcp2515_model_int(&m), 0);
    EXPECT_EQ(read(CANSTAT) & 0x0E, 0x01 << 1) << "ICOD 001: error";
    // With rollover, a third frame overflows RXB1.
    write(RXB0CTRL, {0x64});
    ASSERT_EQ(mcp2515_model_receive(&m, &a), MCP2515_MODEL_RX_BUF1);
    ASSERT_EQ(mcp2515_model_receive(&m, &a), MCP2515_MODEL_RX_OVERFLOW);
    EXPECT_EQ(read(EFLG), 0xC0);
    modify(EFLG, 0xC0, 0x00);
    EXPECT_EQ(read(EFLG), 0x00);
}

TEST_F(Mcp2515Model, MasksAndFiltersAsTable4_2)
{
    // RXB0: mask 0x7F0, RXF0 = 0x120, RXF1 = 0x3A5 (exact through the same mask: 0x3A0-0x3AF);
    // RXB1: every mask bit set, RXF2 = 0x555 standard, RXF3 extended 0x1ABCDEF0 (EXIDE set),
    // RXF4 = RXF5 = 0x7FF; the mask's extended bits compare the standard frames' data bytes
    // with the filters' (AA BB, the frames' data).
    write(RXF0SIDH, std_regs(0x120));
    write(RXF1SIDH, std_regs(0x3A5));
    write(RXF2SIDH, std_regs_data(0x555, 0xAA, 0xBB));
    const uint32_t x = 0x1ABCDEF0;
    write(0x10, {static_cast<uint8_t>(x >> 21),
                 static_cast<uint8_t>(((x >> 18) & 7) << 5 | 0x08 | ((x >> 16) & 3)),
                 static_cast<uint8_t>(x >> 8), static_cast<uint8_t>(x)});
    write(0x14, std_regs_data(0x7FF, 0xAA, 0xBB));
    write(0x18, std_regs_data(0x7FF, 0xAA, 0xBB));
    write(RXM0SIDH, std_regs(0x7F0));
    write(RXM1SIDH, {0xFF, 0xE3, 0xFF, 0xFF});
    mode(0x00);
    struct Case {
        uint32_t id;
        uint8_t ext;
        int where;
        uint8_t filhit;
    } cases[] = {
        {0x120, 0, 0, 0}, {0x12F, 0, 0, 0},  {0x130, 0, -1, 0}, {0x3A0, 0, 0, 1},
        {0x555, 0, 1, 2}, {0x554, 0, -1, 0}, {x, 1, 1, 3},      {x ^ 1, 1, -1, 0},
        {0x7FF, 0, 1, 4}, {0x120, 1, -1, 0}, // an extended frame never matches an EXIDE 0 filter
    };
    for (const auto &c : cases) {
        auto f = frame(c.id, {0xAA, 0xBB}, c.ext);
        int r = mcp2515_model_receive(&m, &f);
        if (c.where < 0) {
            EXPECT_EQ(r, MCP2515_MODEL_RX_REJECTED) << std::hex << c.id;
            continue;
        }
        EXPECT_EQ(r, c.where) << std::hex << c.id;
        uint8_t ctrl = read(c.where ? RXB1CTRL : RXB0CTRL);
        EXPECT_EQ(ctrl & (c.where ? 0x07 : 0x01), c.filhit) << std::hex << c.id;
        spi({static_cast<uint8_t>(c.where ? 0x94 : 0x90)}); // empty the buffer
    }
}

TEST_F(Mcp2515Model, StandardFrameDataBytesAgainstExtendedFilterBits)
{
    // Register 4-1, RXM = 00: RXFnEID8:RXFnEID0 apply to the first two data bytes of
    // standard frames.
    write(RXF0SIDH, {0x24, 0x00, 0xC0, 0xDE}); // id 0x120, data C0 DE
    write(RXF1SIDH, std_regs(0));
    write(RXM0SIDH, {0xFF, 0xE0, 0xFF, 0x00}); // all id bits, data byte 0 only
    write(RXM1SIDH, {0xFF, 0xE3, 0xFF, 0xFF}); // RXB1's filters (all 0) take nothing here
    mode(0x00);
    auto hit = frame(0x120, {0xC0, 0x11});
    auto miss = frame(0x120, {0xC1, 0xDE});
    EXPECT_EQ(mcp2515_model_receive(&m, &hit), MCP2515_MODEL_RX_BUF0);
    spi({0x90});
    EXPECT_EQ(mcp2515_model_receive(&m, &miss), MCP2515_MODEL_RX_REJECTED);
}

TEST_F(Mcp2515Model, ReceivedIdentifierLayout)
{
    // Registers 4-4 to 4-8: standard remote frames show SRR in SIDL and RXRTR; extended frames
    // IDE, the split identifier and RTR in DLC.
    mode(0x00);
    write(RXB0CTRL, {0x64});
    auto r = frame(0x7FF, {}, 0, 1);
    r.dlc = 3;
    ASSERT_EQ(mcp2515_model_receive(&m, &r), MCP2515_MODEL_RX_BUF0);
    auto in = spi({0x90, 0, 0, 0, 0, 0});
    EXPECT_EQ(in[1], 0xFF);
    EXPECT_EQ(in[2], 0xE0 | 0x10);
    EXPECT_EQ(in[5], 0x03);
    auto e = frame(0x15555555, {1, 2, 3, 4, 5, 6, 7, 8}, 1, 0);
    e.dlc = 12; // DLC 9..15: 8 bytes
    ASSERT_EQ(mcp2515_model_receive(&m, &e), MCP2515_MODEL_RX_BUF0);
    EXPECT_EQ(read(RXB0CTRL) & 0x08, 0x00);
    in = spi({0x90, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
    EXPECT_EQ(in[1], 0x15555555u >> 21);
    EXPECT_EQ(in[2], ((0x15555555u >> 18) & 7) << 5 | 0x08 | ((0x15555555u >> 16) & 3));
    EXPECT_EQ(in[3], 0x55);
    EXPECT_EQ(in[4], 0x55);
    EXPECT_EQ(in[5], 12);
    EXPECT_EQ(in[13], 8);
}

TEST_F(Mcp2515Model, TransmitPriorityAndBufferOrder)
{
    // Section 3.2: the highest TXP first; equal TXP: the higher buffer number first.
    mode(0x00);
    for (uint8_t n = 0; n < 3; n++) {
        uint8_t base = static_cast<uint8_t>(0x30 + 16 * n);
        write(static_cast<uint8_t>(base + 1), std_regs(static_cast<uint16_t>(0x100 + n)));
        write(static_cast<uint8_t>(base + 5), {0x00});
    }
    write(TXB0CTRL, {0x02});
    write(TXB1CTRL, {0x02});
    write(TXB2CTRL, {0x01});
    spi({0x87}); // RTS all three
    EXPECT_EQ(spi({0xA0, 0})[1], 0x04 | 0x10 | 0x40) << "READ STATUS shows three TXREQ";
    EXPECT_EQ(mcp2515_model_bus_tick(&m), 1);
    EXPECT_EQ(mcp2515_model_bus_tick(&m), 0);
    EXPECT_EQ(mcp2515_model_bus_tick(&m), 2);
    EXPECT_EQ(mcp2515_model_bus_tick(&m), -1);
    ASSERT_EQ(sent.size(), 3u);
    EXPECT_EQ(sent[0].id, 0x101u);
    EXPECT_EQ(sent[1].id, 0x100u);
    EXPECT_EQ(sent[2].id, 0x102u);
    EXPECT_EQ(read(CANINTF), 0x1C) << "TX0IF, TX1IF, TX2IF";
    EXPECT_EQ(read(TXB0CTRL) & 0x08, 0x00);
}

TEST_F(Mcp2515Model, AbortFlagsAndWritesToPendingBuffers)
{
    mode(0x00);
    write(0x31, std_regs(0x42));
    answer = MCP2515_MODEL_TX_LOST;
    spi({0x81});
    EXPECT_EQ(mcp2515_model_bus_tick(&m), 0);
    EXPECT_EQ(read(TXB0CTRL), 0x08 | 0x20) << "MLOA, still pending";
    write(0x36, {0x99}); // section 3.1: not while TXREQ is set
    EXPECT_EQ(read(0x36), 0x00);
    EXPECT_EQ(m.violations, 1);
    modify(TXB0CTRL, 0x08, 0x00); // MCU aborts (Register 3-1)
    EXPECT_EQ(read(TXB0CTRL), 0x40 | 0x20) << "ABTF";
    modify(TXB0CTRL, 0x08, 0x08); // setting TXREQ clears ABTF, MLOA, TXERR
    EXPECT_EQ(read(TXB0CTRL), 0x08);
    answer = MCP2515_MODEL_TX_ERROR;
    EXPECT_EQ(mcp2515_model_bus_tick(&m), 0);
    EXPECT_EQ(read(TXB0CTRL), 0x08 | 0x10) << "TXERR";
    EXPECT_EQ(read(CANINTF) & 0x80, 0x80) << "MERRF";
    // CANCTRL.ABAT aborts every pending buffer; nothing starts while it is set.
    spi({0x86});
    modify(CANCTRL, 0x10, 0x10);
    EXPECT_EQ(read(TXB0CTRL) & 0x48, 0x40);
    EXPECT_EQ(read(TXB1CTRL) & 0x48, 0x40);
    spi({0x84});
    EXPECT_EQ(mcp2515_model_bus_tick(&m), -1);
    modify(CANCTRL, 0x10, 0x00);
    answer = MCP2515_MODEL_TX_ACK;
    EXPECT_EQ(mcp2515_model_bus_tick(&m), 2);
}

TEST_F(Mcp2515Model, InterruptPinAndIcodPriority)
{
    // Section 7: INT low while an enabled flag is set; ICOD: error 001, wake-up 010, TXB0
    // 011, TXB1 100, TXB2 101, RXB0 110, RXB1 111.
    write(CANINTE, {0x02 | 0x08});
    write(CANINTF, {0x02});
    EXPECT_EQ(mcp2515_model_int(&m), 0);
    EXPECT_EQ((read(CANSTAT) >> 1) & 7, 7);
    write(CANINTF, {0x02 | 0x08});
    EXPECT_EQ((read(CANSTAT) >> 1) & 7, 4);
    write(CANINTF, {0x01 | 0x04});
    EXPECT_EQ(mcp2515_model_int(&m), 1) << "flags set, none enabled";
    EXPECT_EQ((read(CANSTAT) >> 1) & 7, 0);
    write(CANINTE, {0xFF});
    write(CANINTF, {0x60});
    EXPECT_EQ((read(CANSTAT) >> 1) & 7, 1);
}

TEST_F(Mcp2515Model, ErrorCountersStatesBusOffAndRecovery)
{
    // Section 6: TEC +8 per transmit error; EFLG (Register 6-3): TXWAR and EWARN at 96,
    // TXEP at 128, TXBO past 255 (Figure 6-1), recovery after 128 x 11 recessive bits.
    mode(0x00);
    write(0x31, std_regs(0x42));
    spi({0x81});
    answer = MCP2515_MODEL_TX_ERROR;
    for (int i = 1; i <= 11; i++)
        mcp2515_model_bus_tick(&m);
    EXPECT_EQ(read(TEC), 88);
    EXPECT_EQ(read(EFLG), 0x00);
    EXPECT_EQ(read(CANINTF) & 0x20, 0x00) << "no ERRIF before a state change";
    mcp2515_model_bus_tick(&m);
    EXPECT_EQ(read(TEC), 96);
    EXPECT_EQ(read(EFLG), 0x05) << "TXWAR, EWARN";
    EXPECT_EQ(read(CANINTF) & 0x20, 0x20);
    for (int i = 13; i <= 16; i++)
        mcp2515_model_bus_tick(&m);
    EXPECT_EQ(read(TEC), 128);
    EXPECT_EQ(read(EFLG), 0x15) << "TXEP";
    // An acknowledge error while error-passive leaves TEC alone (CAN 2.0 fault confinement,
    // rule 3 exception 1).
    answer = MCP2515_MODEL_TX_NO_ACK;
    mcp2515_model_bus_tick(&m);
    EXPECT_EQ(read(TEC), 128);
    answer = MCP2515_MODEL_TX_ERROR;
    for (int i = 17; i <= 31; i++)
        mcp2515_model_bus_tick(&m);
    EXPECT_EQ(read(TEC), 248);
    EXPECT_EQ(read(EFLG) & 0x20, 0x00);
    mcp2515_model_bus_tick(&m);
    EXPECT_EQ(read(EFLG), 0x35) << "TXBO";
    EXPECT_EQ(read(TEC), 255);
    EXPECT_EQ(mcp2515_model_bus_tick(&m), -1) << "bus-off: nothing is sent";
    auto f = frame(0x1, {});
    EXPECT_EQ(mcp2515_model_receive(&m, &f), MCP2515_MODEL_RX_OFF);
    write(CANINTF, {0x00});
    mcp2515_model_idle(&m, 127);
    EXPECT_EQ(read(EFLG) & 0x20, 0x20);
    mcp2515_model_idle(&m, 1);
    EXPECT_EQ(read(EFLG), 0x00);
    EXPECT_EQ(read(TEC), 0);
    EXPECT_EQ(read(REC), 0);
    EXPECT_EQ(read(CANINTF) & 0x20, 0x20) << "the state changed back";
    answer = MCP2515_MODEL_TX_ACK;
    EXPECT_EQ(mcp2515_model_bus_tick(&m), 0) << "the pending frame goes after recovery";
}

TEST_F(Mcp2515Model, ReceiveErrorCounter)
{
    mode(0x00);
    for (int i = 0; i < 96; i++)
        mcp2515_model_rx_error(&m);
    EXPECT_EQ(read(REC), 96);
    EXPECT_EQ(read(EFLG), 0x03) << "RXWAR, EWARN";
    for (int i = 96; i < 128; i++)
        mcp2515_model_rx_error(&m);
    EXPECT_EQ(read(EFLG), 0x0B) << "RXEP";
    EXPECT_EQ(read(CANINTF) & 0xA0, 0xA0) << "MERRF, ERRIF";
    // A good frame brings REC from above 127 back into 119..127 (error-active).
    auto f = frame(0x5, {});
    mcp2515_model_receive(&m, &f);
    EXPECT_GE(read(REC), 119);
    EXPECT_LE(read(REC), 127);
    EXPECT_EQ(read(EFLG), 0x03);
    mcp2515_model_receive(&m, &f);
    EXPECT_EQ(read(REC), 126);
}

TEST_F(Mcp2515Model, LoopbackListenOnlyConfigurationAndSleep)
{
    write(RXB0CTRL, {0x60});
    write(0x31, std_regs(0x321));
    write(0x35, {0x02, 0xAB, 0xCD});
    spi({0x81});
    // Configuration mode: no traffic either way.
    EXPECT_EQ(mcp2515_model_bus_tick(&m), -1);
    // Loopback (section 10.4): the frame reaches the own RXB0, not the bus.
    mode(0x40);
    EXPECT_EQ(read(CANSTAT) & 0xE0, 0x40);
    EXPECT_EQ(mcp2515_model_bus_tick(&m), 0);
    EXPECT_TRUE(sent.empty());
    auto in = spi({0x90, 0, 0, 0, 0, 0, 0, 0});
    EXPECT_EQ(in[1], 0x321 >> 3);
    EXPECT_EQ(in[5], 2);
    EXPECT_EQ(in[6], 0xAB);
    EXPECT_EQ(in[7], 0xCD);
    auto f = frame(0x10, {});
    EXPECT_EQ(mcp2515_model_receive(&m, &f), MCP2515_MODEL_RX_OFF) << "the bus is not heard";
    // Listen-only (section 10.3): receives, never sends.
    mode(0x60);
    spi({0x81});
    EXPECT_EQ(mcp2515_model_bus_tick(&m), -1);
    EXPECT_EQ(mcp2515_model_receive(&m, &f), MCP2515_MODEL_RX_BUF0);
    // Sleep (section 10.2): bus activity sets WAKIF and wakes into listen-only.
    mode(0x20);
    EXPECT_EQ(read(CANSTAT) & 0xE0, 0x20);
    EXPECT_EQ(mcp2515_model_receive(&m, &f), MCP2515_MODEL_RX_OFF);
    EXPECT_EQ(read(CANINTF) & 0x40, 0x40);
    EXPECT_EQ(read(CANSTAT) & 0xE0, 0x60);
}

} // namespace
